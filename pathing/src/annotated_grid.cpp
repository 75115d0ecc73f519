#include "pathing/annotated_grid.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "parallel_for.h"
#include "pathing/moves.h"

namespace warpath::pathing {

namespace {

// Bit d set when an agent of `size` anchored at (x, y) may step in direction d: it stands at
// both ends and, on a diagonal, beside it (no corner cutting). Reads the eight neighbours once
// (the inner loop of every layer update), then combines their bits.
std::uint8_t movesFrom(const ClearanceField& clearance, int size, int x, int y) {
  if (clearance.at({x, y}) < size) return 0;
  unsigned stands = 0;  // bit d: the agent stands on the neighbour in direction d
  for (int d = 0; d < kDirectionCount; ++d) {
    const Direction& dir = kDirections[static_cast<std::size_t>(d)];
    stands |= (clearance.at({x + dir.dx, y + dir.dy}) >= size ? 1u : 0u) << d;
  }
  unsigned mask = stands & 0xFu;
  for (int d = 4; d < kDirectionCount; ++d) {
    const Direction& dir = kDirections[static_cast<std::size_t>(d)];
    const unsigned needs = (1u << d) | (1u << dir.cardinalA) | (1u << dir.cardinalB);
    if ((stands & needs) == needs) mask |= 1u << d;
  }
  return static_cast<std::uint8_t>(mask);
}

// Calls visit(neighbour) for each cardinal move `mask` allows from `cell` (an index in a map
// `width` cells wide): the moves that decide connectivity (a diagonal needs both cardinals).
template <class Visit>
void forCardinalMoves(std::uint8_t mask, std::uint32_t cell, int width, Visit visit) {
  for (int d = 0; d < 4; ++d) {
    if ((mask & (1u << d)) == 0) continue;
    const Direction& dir = kDirections[static_cast<std::size_t>(d)];
    visit(static_cast<std::uint32_t>(static_cast<std::int64_t>(cell) + dir.dy * width + dir.dx));
  }
}

}  // namespace

AgentLayer AgentLayer::compute(const GridMap& map, const ClearanceField& clearance, Agent agent) {
  AgentLayer layer;
  layer.moveMasks_.assign(map.cellCount(), 0);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x)
      layer.moveMasks_[map.indexOf({x, y})] = movesFrom(clearance, agent.size, x, y);
  }
  layer.labelComponents(map, clearance, agent);
  return layer;
}

// What a components update works in: the cells its searches reached (stamped, with the
// group that reached them), and the groups.
struct AgentLayer::Scratch {
  std::vector<std::uint32_t> stamp;  // per cell: == epoch when reached
  std::vector<std::uint32_t> group;  // per cell: the group that reached it
  std::uint32_t epoch = 0;
  std::vector<std::uint32_t> parent;   // union-find over groups
  std::vector<std::uint32_t> seed;     // per group: the cell it started from
  std::vector<std::uint32_t> oldId;    // per group: its seed's component before
  std::vector<std::uint32_t> sharing;  // per old component id: groups of it still searching
  std::vector<std::vector<std::uint32_t>> reached;  // per root: cells, in the order reached
  std::vector<std::size_t> head;                    // per root: next of `reached` to expand
};

void AgentLayer::update(const GridMap& map, const ClearanceField& clearance, Agent agent,
                        CellRect changed, Scratch& scratch) {
  if (changed.width <= 0 || changed.height <= 0) return;
  // A cell's moves depend on the cells around it.
  const int x0 = std::max(0, changed.x - 1);
  const int y0 = std::max(0, changed.y - 1);
  const int x1 = std::min(map.width(), changed.x + changed.width + 1);
  const int y1 = std::min(map.height(), changed.y + changed.height + 1);
  // Components follow from where the agent stands alone (a cardinal move needs it at both
  // ends, and diagonals join nothing the cardinals do not): a change that only removed such
  // cells can split components but not join them, one that only added them the reverse.
  bool lost = false;
  bool gained = false;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint32_t i = map.indexOf({x, y});
      moveMasks_[i] = movesFrom(clearance, agent.size, x, y);
      const bool stands = clearance.values()[i] >= agent.size;
      const bool stood = components_[i] != 0;
      lost = lost || (stood && !stands);
      gained = gained || (stands && !stood);
    }
  }
  if (!lost && !gained) return;
  const Change change = !gained ? Change::Split : !lost ? Change::Join : Change::Both;
  relabel(map, clearance, agent, {x0, y0, x1 - x0, y1 - y0}, change, scratch);
}

void AgentLayer::relabel(const GridMap& map, const ClearanceField& clearance, Agent agent,
                         CellRect region, Change change, Scratch& s) {
  // Connectivity changed only through the cells of `region`. Searches start from every cell
  // there and next to it where the agent stands, one group each, and advance a cell per group
  // in turn; groups that meet merge. A group that runs out of cells holds a whole component
  // and gets a new id; once at most one group is still searching, the rest is the component of
  // every id that group met (merged under the largest). A change in the open thus costs about
  // its own area, and a split costs the smaller side.
  // Knowing the kind of change saves most searches: after cells were only removed, groups of
  // different old components cannot meet, and a group alone in its old component holds all of
  // it that is left (were it split, each part would border the region, in a group of its own),
  // so only groups sharing an old component search, until one of each is left. After cells
  // were only added, nothing splits: each group joins the components it touches, unsearched.
  const int w = map.width();
  if (s.stamp.size() != components_.size()) {
    s.stamp.assign(components_.size(), 0);
    s.group.assign(components_.size(), 0);
    s.epoch = 0;
  }
  if (++s.epoch == 0) {
    std::fill(s.stamp.begin(), s.stamp.end(), 0);
    s.epoch = 1;
  }
  s.parent.clear();
  s.seed.clear();
  s.oldId.clear();
  for (std::vector<std::uint32_t>& cells : s.reached)
    cells.clear();  // keeps their memory for the next update
  s.head.clear();
  const auto root = [&](std::uint32_t g) {
    while (s.parent[g] != g)
      g = s.parent[g] = s.parent[s.parent[g]];
    return g;
  };
  const auto stands = [&](std::uint32_t cell) { return clearance.values()[cell] >= agent.size; };
  const int gx0 = std::max(0, region.x - 1);
  const int gy0 = std::max(0, region.y - 1);
  const int gx1 = std::min(map.width(), region.x + region.width + 1);
  const int gy1 = std::min(map.height(), region.y + region.height + 1);
  for (int y = gy0; y < gy1; ++y) {
    for (int x = gx0; x < gx1; ++x) {
      const std::uint32_t cell = map.indexOf({x, y});
      if (!stands(cell)) {
        if (components_[cell] != 0 && components_[cell] < sizes_.size())
          --sizes_[components_[cell]];
        components_[cell] = 0;
        continue;
      }
      const auto g = static_cast<std::uint32_t>(s.parent.size());
      s.parent.push_back(g);
      s.seed.push_back(cell);
      s.oldId.push_back(components_[cell]);
      s.stamp[cell] = s.epoch;
      s.group[cell] = g;
    }
  }
  // Cells joined by a move inside the region start as one group: after a change in the open
  // the region is connected in itself, one group remains and no search runs at all.
  for (const std::uint32_t cell : s.seed) {
    forCardinalMoves(moveMasks_[cell], cell, w, [&](std::uint32_t neighbour) {
      if (s.stamp[neighbour] != s.epoch) return;
      const std::uint32_t a = root(s.group[cell]);
      const std::uint32_t b = root(s.group[neighbour]);
      if (a != b) s.parent[std::max(a, b)] = std::min(a, b);
    });
  }
  s.reached.resize(s.parent.size());
  s.head.assign(s.parent.size(), 0);
  std::vector<std::uint32_t> live;
  for (std::uint32_t g = 0; g < s.parent.size(); ++g) {
    const std::uint32_t r = root(g);
    s.reached[r].push_back(s.seed[g]);
    if (r == g) live.push_back(g);
  }
  // Every id met among `cells` (joined now) is one component, under the largest of them.
  const auto joinAll = [&](const std::vector<std::uint32_t>& cells) {
    std::vector<std::uint32_t> met;
    for (std::uint32_t cell : cells) {
      const std::uint32_t id = components_[cell];
      if (id != 0 && (met.empty() || met.back() != id)) met.push_back(id);  // runs of one id
    }
    std::sort(met.begin(), met.end());
    met.erase(std::unique(met.begin(), met.end()), met.end());
    std::uint32_t keep = 0;
    for (std::uint32_t id : met) {
      if (keep == 0 || sizes_[id] > sizes_[keep]) keep = id;
    }
    if (keep == 0) {
      keep = ++componentCount_;
      sizes_.resize(componentCount_ + 1, 0);
    }
    std::vector<std::uint32_t> stack;
    for (std::uint32_t id : met) {
      if (id == keep) continue;
      // Every cell of `id` left is joined to these cells: flood it from them.
      for (std::uint32_t cell : cells) {
        if (components_[cell] == id) stack.push_back(cell);
      }
      while (!stack.empty()) {
        const std::uint32_t cell = stack.back();
        stack.pop_back();
        if (components_[cell] != id) continue;
        components_[cell] = keep;
        ++sizes_[keep];
        forCardinalMoves(moveMasks_[cell], cell, w, [&](std::uint32_t next) {
          if (components_[next] == id) stack.push_back(next);
        });
      }
      sizes_[id] = 0;
    }
    for (std::uint32_t cell : cells) {
      if (components_[cell] == 0) ++sizes_[keep];
      components_[cell] = keep;
    }
  };
  if (change == Change::Join) {
    for (const std::uint32_t g : live)
      joinAll(s.reached[g]);
    return;
  }
  // After a split, a group searches while another shares its old component.
  const bool split = change == Change::Split;
  if (split) {
    s.sharing.resize(componentCount_ + 1, 0);
    for (const std::uint32_t g : live)
      ++s.sharing[s.oldId[g]];
  }
  const auto searching = [&](std::uint32_t g) { return !split || s.sharing[s.oldId[g]] > 1; };
  std::erase_if(live, [&](std::uint32_t g) { return !searching(g); });
  std::vector<std::uint32_t> done;  // roots that ran out of cells
  std::vector<std::uint32_t> stillLive;
  std::vector<std::uint32_t> pending;
  while (split ? !live.empty() : live.size() > 1) {
    stillLive.clear();
    for (std::uint32_t g : live) {
      if (root(g) != g) continue;  // merged into another this round
      if (s.head[g] == s.reached[g].size()) {
        done.push_back(g);
        if (split) --s.sharing[s.oldId[g]];
        continue;
      }
      const std::uint32_t cell = s.reached[g][s.head[g]++];
      forCardinalMoves(moveMasks_[cell], cell, w, [&](std::uint32_t neighbour) {
        if (s.stamp[neighbour] != s.epoch) {
          s.stamp[neighbour] = s.epoch;
          s.group[neighbour] = g;
          s.reached[g].push_back(neighbour);
          return;
        }
        const std::uint32_t other = root(s.group[neighbour]);
        if (other == g) return;
        // Merge the smaller into the larger; the survivor keeps searching from where each was.
        std::uint32_t keep = g;
        std::uint32_t gone = other;
        if (s.reached[keep].size() < s.reached[gone].size()) std::swap(keep, gone);
        s.parent[gone] = keep;
        if (split) --s.sharing[s.oldId[keep]];  // both of one old component
        std::vector<std::uint32_t>& into = s.reached[keep];
        std::vector<std::uint32_t>& from = s.reached[gone];
        // Cells not yet expanded go to the end of the survivor's list; expanded ones need not.
        pending.assign(into.begin() + static_cast<std::ptrdiff_t>(s.head[keep]), into.end());
        into.resize(s.head[keep]);
        into.insert(into.end(), from.begin(),
                    from.begin() + static_cast<std::ptrdiff_t>(s.head[gone]));
        s.head[keep] = into.size();
        into.insert(into.end(), pending.begin(), pending.end());
        into.insert(into.end(), from.begin() + static_cast<std::ptrdiff_t>(s.head[gone]),
                    from.end());
        from.clear();
        from.shrink_to_fit();
        g = keep;
      });
      stillLive.push_back(g);
    }
    // In order unless a merge kept a group listed before the one it met.
    if (!std::is_sorted(stillLive.begin(), stillLive.end()))
      std::sort(stillLive.begin(), stillLive.end());
    stillLive.erase(std::unique(stillLive.begin(), stillLive.end()), stillLive.end());
    std::erase_if(stillLive, [&](std::uint32_t g) { return root(g) != g || !searching(g); });
    std::swap(live, stillLive);
  }
  if (split) {
    for (const std::uint32_t id : s.oldId)
      s.sharing[id] = 0;
  }
  // Groups that ran out hold whole components: new ids.
  for (std::uint32_t g : done) {
    if (root(g) != g) continue;
    const std::uint32_t id = ++componentCount_;
    sizes_.resize(componentCount_ + 1, 0);
    for (std::uint32_t cell : s.reached[g]) {
      const std::uint32_t old = components_[cell];
      if (old != 0 && old < sizes_.size() && sizes_[old] > 0) --sizes_[old];
      components_[cell] = id;
    }
    sizes_[id] = static_cast<std::uint32_t>(s.reached[g].size());
  }
  // After a split the groups left each hold what is left of their old component, whose id
  // they keep; otherwise the last group joins every id it met.
  if (split || live.empty()) return;
  joinAll(s.reached[root(live.front())]);
}

void AgentLayer::labelComponents(const GridMap& map, const ClearanceField& clearance, Agent agent) {
  // Moves are symmetric, so a flood fill over the cardinal moves alone labels components
  // (a legal diagonal implies both cardinal detours are legal).
  const int w = map.width();
  components_.assign(map.cellCount(), 0);
  componentCount_ = 0;
  sizes_.assign(1, 0);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t seed = 0; seed < components_.size(); ++seed) {
    if (components_[seed] != 0 || clearance.values()[seed] < agent.size) continue;
    const std::uint32_t id = ++componentCount_;
    components_[seed] = id;
    sizes_.push_back(0);
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::uint32_t cell = stack.back();
      stack.pop_back();
      ++sizes_[id];
      forCardinalMoves(moveMasks_[cell], cell, w, [&](std::uint32_t next) {
        if (components_[next] != 0) return;
        components_[next] = id;
        stack.push_back(next);
      });
    }
  }
}

AnnotatedGrid::AnnotatedGrid(GridMap map) : map_(std::move(map)) {}
AnnotatedGrid::~AnnotatedGrid() = default;

const ClearanceField& AnnotatedGrid::clearance(Capability capability) const {
  std::lock_guard lock(mutex_);
  auto& slot = clearances_[capability];
  if (!slot) slot = std::make_unique<ClearanceField>(ClearanceField::compute(map_, capability));
  return *slot;
}

const AgentLayer& AnnotatedGrid::layer(Agent agent) const {
  const ClearanceField& field = clearance(agent.capability);
  std::lock_guard lock(mutex_);
  auto& slot = layers_[agent];
  if (!slot) slot = std::make_unique<AgentLayer>(AgentLayer::compute(map_, field, agent));
  return *slot;
}

void AnnotatedGrid::prepare(std::span<const Agent> agents, int threads) const {
  // What is missing, found under the lock; computed outside it (layer() holds it while it
  // computes, which would make the threads take turns); stored under it.
  std::vector<Capability> capabilities;
  std::vector<Agent> missing;
  {
    std::lock_guard lock(mutex_);
    for (const Agent& agent : agents) {
      if (!clearances_.contains(agent.capability) &&
          std::find(capabilities.begin(), capabilities.end(), agent.capability) ==
              capabilities.end())
        capabilities.push_back(agent.capability);
      if (!layers_.contains(agent) &&
          std::find(missing.begin(), missing.end(), agent) == missing.end())
        missing.push_back(agent);
    }
  }
  std::vector<std::unique_ptr<ClearanceField>> fields(capabilities.size());
  parallelFor(capabilities.size(), threads, [&](std::size_t, std::size_t i) {
    fields[i] = std::make_unique<ClearanceField>(ClearanceField::compute(map_, capabilities[i]));
  });
  {
    std::lock_guard lock(mutex_);
    for (std::size_t i = 0; i < capabilities.size(); ++i)
      clearances_.try_emplace(capabilities[i], std::move(fields[i]));
  }
  std::vector<const ClearanceField*> fieldOf(missing.size());
  for (std::size_t i = 0; i < missing.size(); ++i)
    fieldOf[i] = &clearance(missing[i].capability);
  std::vector<std::unique_ptr<AgentLayer>> layers(missing.size());
  parallelFor(missing.size(), threads, [&](std::size_t, std::size_t i) {
    layers[i] = std::make_unique<AgentLayer>(AgentLayer::compute(map_, *fieldOf[i], missing[i]));
  });
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < missing.size(); ++i)
    layers_.try_emplace(missing[i], std::move(layers[i]));
}

TerrainChange AnnotatedGrid::setTerrain(CellRect area, Terrain terrain) {
  area = map_.clip(area);
  bool changed = false;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      const std::size_t i = map_.indexOf(c);
      if (!obstacles_.empty() && obstacles_[i] > 0) {
        underneath_[i] = terrain;
      } else if (map_.at(c) != terrain) {
        map_.set(c, terrain);
        changed = true;
      }
    }
  }
  if (changed) refresh(area);
  return {area, changed};
}

TerrainChange AnnotatedGrid::placeObstacle(CellRect area) {
  area = map_.clip(area);
  if (obstacles_.empty()) {
    obstacles_.assign(map_.cellCount(), 0);
    underneath_.assign(map_.cellCount(), Terrain::Blocked);
  }
  bool changed = false;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      const std::size_t i = map_.indexOf(c);
      if (obstacles_[i]++ > 0) continue;
      underneath_[i] = map_.at(c);
      if (map_.at(c) != Terrain::Blocked) {
        map_.set(c, Terrain::Blocked);
        changed = true;
      }
    }
  }
  if (changed) refresh(area);
  return {area, changed};
}

TerrainChange AnnotatedGrid::clearObstacle(CellRect area) {
  area = map_.clip(area);
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      if (obstacles_.empty() || obstacles_[map_.indexOf({x, y})] == 0)
        throw std::invalid_argument("clearObstacle: no obstacle stands on (" + std::to_string(x) +
                                    "," + std::to_string(y) + ")");
    }
  }
  bool changed = false;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      const std::size_t i = map_.indexOf(c);
      if (--obstacles_[i] > 0 || underneath_[i] == map_.at(c)) continue;
      map_.set(c, underneath_[i]);
      changed = true;
    }
  }
  if (changed) refresh(area);
  return {area, changed};
}

std::optional<CellRect> AnnotatedGrid::changedSince(std::uint64_t revision) const {
  if (revision > revision_ || revision_ - revision > changes_.size()) return std::nullopt;
  std::optional<CellRect> all;
  for (std::size_t i = changes_.size() - static_cast<std::size_t>(revision_ - revision);
       i < changes_.size(); ++i) {
    const CellRect& c = changes_[i];
    all = all ? all->joinedWith(c) : c;
  }
  return all.value_or(CellRect{0, 0, 0, 0});
}

void AnnotatedGrid::refresh(CellRect area) {
  ++revision_;
  changes_.push_back(area);
  if (changes_.size() > kChangesKept) changes_.pop_front();
  std::lock_guard lock(mutex_);
  // A capability's clearance and layers depend on no other capability's: one task each.
  std::vector<std::pair<Capability, ClearanceField*>> fields;
  for (auto& [capability, field] : clearances_)
    fields.push_back({capability, field.get()});
  while (scratch_.size() < workersFor(fields.size(), updateThreads_))
    scratch_.push_back(std::make_unique<AgentLayer::Scratch>());
  parallelFor(fields.size(), updateThreads_, [&](std::size_t worker, std::size_t i) {
    const auto& [capability, field] = fields[i];
    const CellRect changed = field->update(map_, area);
    for (auto& [agent, layer] : layers_) {
      if (agent.capability == capability)
        layer->update(map_, *field, agent, changed, *scratch_[worker]);
    }
  });
}

std::size_t AnnotatedGrid::cacheBytes() const {
  std::lock_guard lock(mutex_);
  std::size_t bytes = 0;
  for (const auto& [capability, field] : clearances_) {
    bytes += field->values().size_bytes();
  }
  for (const auto& [agent, layer] : layers_) {
    bytes += layer->moveMasks().size_bytes() + layer->components().size_bytes();
  }
  return bytes;
}

std::optional<PathStatus> screenEndpoints(const AnnotatedGrid& grid, Agent agent, Cell start,
                                          Cell goal, const AgentLayer* layer) {
  // One look-up of the layer (the grid's caches take a lock): its component is 0 exactly
  // where the agent cannot stand.
  const GridMap& map = grid.map();
  if (agent.size < 1 || !map.contains(start)) return PathStatus::InvalidStart;
  const std::span<const std::uint32_t> components =
      (layer ? *layer : grid.layer(agent)).components();
  const std::uint32_t from = components[map.indexOf(start)];
  if (from == 0) return PathStatus::InvalidStart;
  if (!map.contains(goal)) return PathStatus::InvalidGoal;
  const std::uint32_t to = components[map.indexOf(goal)];
  if (to == 0) return PathStatus::InvalidGoal;
  if (from != to) return PathStatus::Unreachable;
  return std::nullopt;
}

std::optional<PathStatus> screenQuery(const AnnotatedGrid& grid, Agent agent, Cell start, Cell goal,
                                      const SearchLimits& limits, const AgentLayer* layer) {
  if (const auto answer = screenEndpoints(grid, agent, start, goal, layer)) return answer;
  if (limits.region && (!limits.region->contains(start) || !limits.region->contains(goal)))
    return PathStatus::Unreachable;
  if (limits.maxExpanded == 0) return PathStatus::BudgetExhausted;
  return std::nullopt;
}

std::string findIllegalStep(const AnnotatedGrid& grid, Agent agent, std::span<const Cell> path) {
  if (path.empty()) return "path is empty";
  std::ostringstream problem;
  const auto cell = [](Cell c) {
    std::ostringstream out;
    out << '(' << c.x << ',' << c.y << ')';
    return out.str();
  };
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!grid.canStand(agent, path[i])) {
      problem << "step " << i << ": agent cannot stand on " << cell(path[i]);
      return problem.str();
    }
    if (i == 0) continue;
    const int dx = path[i].x - path[i - 1].x;
    const int dy = path[i].y - path[i - 1].y;
    if (std::abs(dx) > 1 || std::abs(dy) > 1 || (dx == 0 && dy == 0)) {
      problem << "step " << i << ": " << cell(path[i - 1]) << " -> " << cell(path[i])
              << " is not a single move";
      return problem.str();
    }
    if (dx != 0 && dy != 0 &&
        (!grid.canStand(agent, {path[i - 1].x + dx, path[i - 1].y}) ||
         !grid.canStand(agent, {path[i - 1].x, path[i - 1].y + dy}))) {
      problem << "step " << i << ": diagonal " << cell(path[i - 1]) << " -> " << cell(path[i])
              << " cuts a corner";
      return problem.str();
    }
  }
  return {};
}

double pathCost(std::span<const Cell> path) {
  double cost = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const bool diagonal = path[i].x != path[i - 1].x && path[i].y != path[i - 1].y;
    cost += diagonal ? kSqrt2 : 1.0;
  }
  return cost;
}

}  // namespace warpath::pathing
