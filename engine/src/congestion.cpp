#include "engine/congestion.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "pathing/moves.h"

namespace warpath::engine {

using pathing::Cell;

namespace {

// A place bigger than this is not a bottleneck but a maze of them (ground strewn with
// obstacles): one queue for all of it would make every route through it wait for every other.
constexpr std::size_t kMaxPlaceCells = 2048;
// A body's width over its footprint's side, and the gap [Unit: cells] between bodies in a file.
constexpr double kBodyShare = 0.75;
constexpr double kFollowingGap = 0.25;

double stepLength(Cell a, Cell b) {
  return (a.x != b.x && a.y != b.y) ? pathing::kSqrt2 : 1.0;
}

}  // namespace

Congestion::Congestion(const pathing::AnnotatedGrid& grid, int clusterSize)
    : grid_(grid),
      clusterSize_(clusterSize),
      clustersX_((grid.map().width() + clusterSize - 1) / clusterSize) {}

void Congestion::terrainChanged() {
  layers_.clear();
  booked_.clear();
}

Congestion::Layer& Congestion::layerFor(pathing::Capability capability) {
  for (Layer& layer : layers_)
    if (layer.capability == capability.mask()) return layer;
  const pathing::GridMap& map = grid_.map();
  const int width = map.width();
  const int height = map.height();
  const pathing::ClearanceField& clearance = grid_.clearance(capability);
  // Each cell's run across: the shorter of its row's and its column's runs of open cells (0
  // where the capability cannot stand), by one pass along the rows and one along the columns.
  std::vector<int> across(map.cellCount(), INT32_MAX);
  const auto measureRuns = [&](int lines, int length, bool rows) {
    for (int line = 0; line < lines; ++line) {
      const auto at = [&](int k) { return rows ? Cell{k, line} : Cell{line, k}; };
      for (int k = 0; k < length;) {
        if (clearance.at(at(k)) < 1) {
          across[map.indexOf(at(k))] = 0;
          ++k;
          continue;
        }
        int end = k;
        while (end < length && clearance.at(at(end)) >= 1)
          ++end;
        for (int i = k; i < end; ++i) {
          int& run = across[map.indexOf(at(i))];
          run = std::min(run, end - k);
        }
        k = end;
      }
    }
  };
  measureRuns(height, width, true);
  measureRuns(width, height, false);
  Layer layer;
  layer.capability = capability.mask();
  layer.placeOf.assign(map.cellCount(), -1);
  const int clustersY = (height + clusterSize_ - 1) / clusterSize_;
  layer.placesInCluster.resize(static_cast<std::size_t>(clustersX_ * clustersY));
  // 8-connected sets of narrow cells, numbered in the order of their first cell.
  std::vector<Cell> stack;
  std::vector<Cell> cells;
  std::vector<int> runs;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint32_t index = map.indexOf({x, y});
      const int run = across[index];
      if (run == 0 || run > kNarrowWidth || layer.placeOf[index] != -1) continue;
      const auto id = static_cast<std::int32_t>(layer.places.size());
      cells.clear();
      stack.assign(1, {x, y});
      layer.placeOf[index] = id;
      while (!stack.empty()) {
        const Cell c = stack.back();
        stack.pop_back();
        cells.push_back(c);
        for (const pathing::Direction& d : pathing::kDirections) {
          const Cell n{c.x + d.dx, c.y + d.dy};
          if (!map.contains(n)) continue;
          const std::uint32_t ni = map.indexOf(n);
          if (layer.placeOf[ni] != -1 || across[ni] == 0 || across[ni] > kNarrowWidth) continue;
          layer.placeOf[ni] = id;
          stack.push_back(n);
        }
      }
      if (cells.size() > kMaxPlaceCells) {
        // Not a place: its cells stay marked (so the fill does not start again inside it) with
        // an id that has no queue.
        layer.places.push_back(Place{});
        continue;
      }
      runs.clear();
      for (const Cell& c : cells)
        runs.push_back(across[map.indexOf(c)]);
      std::nth_element(runs.begin(), runs.begin() + static_cast<std::ptrdiff_t>(runs.size() / 2),
                       runs.end());
      Place place;
      place.width = runs[runs.size() / 2];  // the median: ragged banks do not narrow a bridge
      layer.places.push_back(std::move(place));
      std::vector<int> clusters;
      for (const Cell& c : cells)
        clusters.push_back(clusterOf(c));
      std::sort(clusters.begin(), clusters.end());
      clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
      for (int cluster : clusters)
        layer.placesInCluster[static_cast<std::size_t>(cluster)].push_back(id);
    }
  }
  layers_.push_back(std::move(layer));
  return layers_.back();
}

double Congestion::waitAt(Place& place, double t) {
  if (place.width == 0 || place.bookings.empty()) return 0.0;
  if (place.dirty) {
    std::sort(place.bookings.begin(), place.bookings.end(), [](const Booking& a, const Booking& b) {
      return a.arrival != b.arrival ? a.arrival < b.arrival : a.unit.index < b.unit.index;
    });
    place.arrivals.clear();
    place.ends.clear();
    double end = -INFINITY;
    for (const Booking& b : place.bookings) {
      end = std::max(b.arrival, end) + b.hold;
      place.arrivals.push_back(b.arrival);
      place.ends.push_back(end);
    }
    place.dirty = false;
  }
  const auto after = std::upper_bound(place.arrivals.begin(), place.arrivals.end(), t);
  if (after == place.arrivals.begin()) return 0.0;
  const double end = place.ends[static_cast<std::size_t>(after - place.arrivals.begin()) - 1];
  return std::max(0.0, end - t);
}

template <class Visit>
double Congestion::walk(Layer& layer, double speed, double now, std::span<const Cell> cells,
                        double startSeconds, Visit&& visit) {
  if (cells.empty() || layer.places.empty()) return 0.0;
  const pathing::GridMap& map = grid_.map();
  double waits = 0.0;
  double distance = 0.0;
  std::int32_t previous = layer.placeOf[map.indexOf(cells[0])];
  for (std::size_t i = 1; i < cells.size(); ++i) {
    distance += stepLength(cells[i - 1], cells[i]);
    const std::int32_t place = layer.placeOf[map.indexOf(cells[i])];
    if (place >= 0 && place != previous && layer.places[static_cast<std::size_t>(place)].width > 0)
      waits += visit(place, now + startSeconds + distance / speed + waits);
    previous = place;
  }
  return waits;
}

double Congestion::waitAlong(pathing::Agent agent, double speed, std::span<const Cell> path,
                             double now) {
  Layer& layer = layerFor(agent.capability);
  return walk(layer, speed, now, path, 0.0, [&](std::int32_t p, double t) {
    return waitAt(layer.places[static_cast<std::size_t>(p)], t);
  });
}

void Congestion::book(UnitId unit, pathing::Agent agent, double speed, std::span<const Cell> path,
                      double now) {
  cancel(unit);
  const std::size_t layerIndex =
      static_cast<std::size_t>(&layerFor(agent.capability) - layers_.data());
  Layer& layer = layers_[layerIndex];
  std::vector<std::pair<std::size_t, std::int32_t>> places;
  walk(layer, speed, now, path, 0.0, [&](std::int32_t p, double t) {
    Place& place = layer.places[static_cast<std::size_t>(p)];
    const double wait = waitAt(place, t);
    // Bodies are about 3/4 of their footprint across and close up to a quarter cell apart:
    // that is the 6.5 infantry a second gap_200's three-cell gap passes (docs/cooperative.md).
    const double body = kBodyShare * agent.size;
    const int files = std::max(1, static_cast<int>(place.width / body));
    const double hold = (body + kFollowingGap) / (speed * files);
    // Bookings the queue has served by now go first: they no longer hold anyone.
    if (!place.dirty && !place.ends.empty() && place.ends.back() < now) place.bookings.clear();
    place.bookings.push_back({unit, t, hold});
    place.dirty = true;
    places.push_back({layerIndex, p});
    return wait;
  });
  if (!places.empty()) booked_[unit.index] = std::move(places);
}

void Congestion::cancel(UnitId unit) {
  const auto it = booked_.find(unit.index);
  if (it == booked_.end()) return;
  for (const auto& [layerIndex, p] : it->second) {
    Place& place = layers_[layerIndex].places[static_cast<std::size_t>(p)];
    const std::size_t before = place.bookings.size();
    std::erase_if(place.bookings, [&](const Booking& b) { return b.unit == unit; });
    if (place.bookings.size() != before) place.dirty = true;
  }
  booked_.erase(it);
}

bool Congestion::anyQueueNear(Layer& layer, int cluster, double now) {
  for (std::int32_t p : layer.placesInCluster[static_cast<std::size_t>(cluster)]) {
    Place& place = layer.places[static_cast<std::size_t>(p)];
    if (place.bookings.empty()) continue;
    waitAt(place, now);  // brings the queue's ends up to date
    if (!place.ends.empty() && place.ends.back() > now) return true;
  }
  return false;
}

std::size_t Congestion::queuesAt(double now) {
  std::size_t queues = 0;
  for (Layer& layer : layers_) {
    for (Place& place : layer.places) {
      if (place.bookings.empty()) continue;
      waitAt(place, now);
      queues += !place.ends.empty() && place.ends.back() > now;
    }
  }
  return queues;
}

Congestion::Layer& Congestion::Surcharge::layer() const {
  // The layers are found again after a terrain change, maybe in another order.
  std::vector<Layer>& layers = congestion_.layers_;
  if (layer_ < layers.size() && layers[layer_].capability == agent_.capability.mask())
    return layers[layer_];
  Layer& found = congestion_.layerFor(agent_.capability);
  layer_ = static_cast<std::size_t>(&found - layers.data());
  return found;
}

double Congestion::Surcharge::on(const pathing::ClusterAbstraction& graph, std::uint32_t from,
                                 const pathing::AbstractEdge& edge, double g) const {
  Congestion& c = congestion_;
  Layer& layer = this->layer();
  if (layer.places.empty()) return 0.0;
  const Cell a = graph.nodeCell(from);
  const Cell b = graph.nodeCell(edge.target);
  if (!c.anyQueueNear(layer, c.clusterOf(a), now_) &&
      (c.clusterOf(b) == c.clusterOf(a) || !c.anyQueueNear(layer, c.clusterOf(b), now_)))
    return 0.0;
  c.edgeCells_.assign(1, a);
  if (edge.intra && edge.path == pathing::AbstractEdge::kNoPath)
    c.edgeCells_.push_back(b);  // no cached path: the wait where the edge ends
  else
    graph.appendEdgeCells(from, edge, &c.edgeCells_);
  const double startSeconds = seconds_ ? g : g / speed_;
  const double waits =
      c.walk(layer, speed_, now_, c.edgeCells_, startSeconds, [&](std::int32_t p, double t) {
        return c.waitAt(layer.places[static_cast<std::size_t>(p)], t);
      });
  return seconds_ ? waits : waits * speed_;
}

bool Congestion::Surcharge::freeWithin(const pathing::ClusterAbstraction& graph,
                                       int levelTwoCluster) const {
  Congestion& c = congestion_;
  Layer& layer = this->layer();
  if (layer.places.empty()) return true;
  const pathing::CellRect r = graph.levelTwoClusterBounds(levelTwoCluster);
  for (int y = r.y; y < r.y + r.height; y += c.clusterSize_) {
    for (int x = r.x; x < r.x + r.width; x += c.clusterSize_) {
      if (c.anyQueueNear(layer, c.clusterOf({x, y}), now_)) return false;
    }
  }
  return true;
}

}  // namespace warpath::engine
