#include "pathing/cooperative_search.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "pathing/moves.h"
#include "pathing/open_list.h"
#include "pathing/search.h"

namespace warpath::pathing {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Of two windows that reach the same state at the same time, the one with fewer moves wins: a
// unit waits rather than shuffle into a passage and back (a vehicle turning round in a
// corridor falls behind its plan).
constexpr double kMoveCost = 1e-4;

Cell cellAt(const GridMap& map, std::uint32_t index) {
  const auto w = static_cast<std::uint32_t>(map.width());
  return {static_cast<int>(index % w), static_cast<int>(index / w)};
}

}  // namespace

// --- Reverse Resumable A* ---

ReverseResumableSearch::ReverseResumableSearch(const AnnotatedGrid& grid, Agent agent, Cell goal,
                                               Cell start)
    : grid_(grid),
      agent_(agent),
      map_(grid.map()),
      moves_(grid.layer(agent).moveMasks()),
      target_(start) {
  if (!grid.canStand(agent, goal)) return;
  entries_.emplace(map_.indexOf(goal), Entry{0.0, false});
  push(map_.indexOf(goal), 0.0);
}

void ReverseResumableSearch::push(std::uint32_t cell, double g) {
  const Cell c = cellAt(map_, cell);
  const double f = g + octileDistance(c.x - target_.x, c.y - target_.y);
  open_.push_back({f, g, cell});
  std::push_heap(open_.begin(), open_.end(), [](const Open& a, const Open& b) {
    if (a.f != b.f) return a.f > b.f;
    if (a.g != b.g) return a.g < b.g;
    return a.cell > b.cell;
  });
}

double ReverseResumableSearch::distance(Cell c) {
  // Where the agent cannot stand nothing is reached: answered without searching everything.
  if (!grid_.canStand(agent_, c)) return kInfinity;
  const std::uint32_t wanted = map_.indexOf(c);
  if (const auto it = entries_.find(wanted); it != entries_.end() && it->second.closed)
    return it->second.g;
  const auto order = [](const Open& a, const Open& b) {
    if (a.f != b.f) return a.f > b.f;
    if (a.g != b.g) return a.g < b.g;
    return a.cell > b.cell;
  };
  while (!open_.empty()) {
    std::pop_heap(open_.begin(), open_.end(), order);
    const Open top = open_.back();
    open_.pop_back();
    Entry& e = entries_[top.cell];
    if (e.closed) continue;
    if (top.g > e.g) continue;  // a stale copy: a shorter one was pushed later
    e.closed = true;
    e.g = top.g;
    ++expanded_;
    const Cell here = cellAt(map_, top.cell);
    const std::uint8_t mask = moves_[top.cell];
    for (int d = 0; d < kDirectionCount; ++d) {
      if ((mask & (1u << d)) == 0) continue;
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      const std::uint32_t next = map_.indexOf({here.x + dir.dx, here.y + dir.dy});
      const double g = top.g + dir.cost;
      auto [it, fresh] = entries_.try_emplace(next, Entry{g, false});
      if (it->second.closed) continue;
      if (!fresh && it->second.g <= g) continue;
      it->second.g = g;
      push(next, g);
    }
    if (top.cell == wanted) return top.g;
  }
  return kInfinity;
}

// --- Corridor ---

CorridorDistance::CorridorDistance(const AnnotatedGrid& grid, Agent agent,
                                   std::span<const Cell> path, int radius) {
  const GridMap& map = grid.map();
  if (path.empty() || map.width() <= 0 || map.height() <= 0) return;
  // Each path cell's square, clipped to the map, marked in a bitmap over the squares' bounding
  // box. (Sorting row runs of every square cost most of a build on long paths.)
  int right = -1;
  int bottom = -1;
  int left = map.width();
  top_ = map.height();
  for (const Cell& p : path) {
    left = std::min(left, std::max(0, p.x - radius));
    right = std::max(right, std::min(map.width() - 1, p.x + radius));
    top_ = std::min(top_, std::max(0, p.y - radius));
    bottom = std::max(bottom, std::min(map.height() - 1, p.y + radius));
  }
  if (left > right || top_ > bottom) return;
  const int width = right - left + 1;
  const int height = bottom - top_ + 1;
  const auto words = static_cast<std::size_t>(width / 64 + 1);
  std::vector<std::uint64_t> marked(words * static_cast<std::size_t>(height), 0);
  for (const Cell& p : path) {
    const int x0 = std::max(0, p.x - radius - left);
    const int x1 = std::min(right, p.x + radius) - left;
    for (int y = std::max(top_, p.y - radius); y <= std::min(bottom, p.y + radius); ++y) {
      std::uint64_t* row = &marked[static_cast<std::size_t>(y - top_) * words];
      for (int w = x0 / 64; w <= x1 / 64; ++w) {
        const int lo = std::max(x0, w * 64) - w * 64;
        const int hi = std::min(x1, w * 64 + 63) - w * 64;
        row[w] |= (~std::uint64_t{0} >> (63 - hi)) & (~std::uint64_t{0} << lo);
      }
    }
  }
  // The corridor's runs: each row's runs of marked cells, their slots in row-major order.
  rowRuns_.assign(static_cast<std::size_t>(height) + 1, 0);
  std::uint32_t cells = 0;
  for (int r = 0; r < height; ++r) {
    rowRuns_[static_cast<std::size_t>(r)] = static_cast<std::uint32_t>(runs_.size());
    const std::uint64_t* row = &marked[static_cast<std::size_t>(r) * words];
    // The first cell at or after x whose bit is `set`, or width.
    const auto next = [&](int x, bool set) {
      while (x < width) {
        const std::uint64_t bits = (set ? row[x / 64] : ~row[x / 64]) >> (x % 64);
        if (bits != 0) return std::min(width, x + std::countr_zero(bits));
        x = (x / 64 + 1) * 64;
      }
      return width;
    };
    for (int x = next(0, true); x < width; x = next(x, true)) {
      const int end = next(x, false);
      runs_.push_back({top_ + r, left + x, left + end - 1, cells});
      cells += static_cast<std::uint32_t>(end - x);
      x = end;
    }
  }
  rowRuns_[static_cast<std::size_t>(height)] = static_cast<std::uint32_t>(runs_.size());
  distances_.assign(cells, kInfinity);

  // Dijkstra from the goal over the corridor (moves are symmetric; they lead only to cells the
  // agent may stand on). Final distances do not depend on the order among equal keys: a cell's
  // distance is the least of its closer neighbours' plus a move, and moves cost at least 1.
  if (!grid.canStand(agent, path.back())) return;
  const std::span<const std::uint8_t> moves = grid.layer(agent).moveMasks();
  std::vector<Cell> cellOf(cells);
  for (const Run& run : runs_) {
    for (int x = run.x0; x <= run.x1; ++x)
      cellOf[run.offset + static_cast<std::uint32_t>(x - run.x0)] = {x, run.y};
  }
  std::vector<bool> settled(cells, false);
  OpenList open;
  const auto goal = static_cast<std::uint32_t>(slot(path.back()));
  distances_[goal] = 0.0;
  open.push(OpenList::makeKey(0.0, 0.0), goal);
  while (!open.empty()) {
    const std::uint32_t current = open.pop();
    if (settled[current]) continue;
    settled[current] = true;
    ++expanded_;
    const double g = distances_[current];
    const Cell here = cellOf[current];
    for (unsigned mask = moves[map.indexOf(here)]; mask != 0; mask &= mask - 1) {
      const Direction& dir = kDirections[static_cast<std::size_t>(std::countr_zero(mask))];
      const std::ptrdiff_t at = slot({here.x + dir.dx, here.y + dir.dy});
      if (at < 0) continue;
      double& known = distances_[static_cast<std::size_t>(at)];
      if (known <= g + dir.cost) continue;
      known = g + dir.cost;
      open.push(OpenList::makeKey(known, known), static_cast<std::uint32_t>(at));
    }
  }
}

std::ptrdiff_t CorridorDistance::slot(Cell c) const {
  const int row = c.y - top_;
  if (row < 0 || row + 1 >= static_cast<int>(rowRuns_.size())) return -1;
  for (std::uint32_t i = rowRuns_[static_cast<std::size_t>(row)];
       i < rowRuns_[static_cast<std::size_t>(row) + 1]; ++i) {
    const Run& run = runs_[i];
    if (c.x < run.x0) return -1;
    if (c.x <= run.x1) return static_cast<std::ptrdiff_t>(run.offset) + (c.x - run.x0);
  }
  return -1;
}

double CorridorDistance::distance(Cell c) {
  const std::ptrdiff_t at = slot(c);
  return at < 0 ? kInfinity : distances_[static_cast<std::size_t>(at)];
}

// --- Passing room ---

std::vector<std::uint8_t> passingRoom(const AnnotatedGrid& grid, Agent agent) {
  const GridMap& map = grid.map();
  const int w = map.width();
  const int h = map.height();
  const int s = std::max(1, agent.size);
  const ClearanceField& clearance = grid.clearance(agent.capability);
  // Integral image of "a 2s×2s square of the capability starts here".
  std::vector<std::int32_t> sum(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1),
                                0);
  const auto at = [&](int x, int y) -> std::int32_t& {
    return sum[static_cast<std::size_t>(y) * static_cast<std::size_t>(w + 1) +
               static_cast<std::size_t>(x)];
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int big = clearance.at({x, y}) >= 2 * s ? 1 : 0;
      at(x + 1, y + 1) = big + at(x, y + 1) + at(x + 1, y) - at(x, y);
    }
  }
  std::vector<std::uint8_t> room(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // Square anchors b with b.x in [x - s, x], b.y in [y - s, y] contain this footprint.
      const int x0 = std::max(0, x - s);
      const int y0 = std::max(0, y - s);
      const int n = at(x + 1, y + 1) - at(x0, y + 1) - at(x + 1, y0) + at(x0, y0);
      room[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
           static_cast<std::size_t>(x)] = n > 0 ? 1 : 0;
    }
  }
  return room;
}

std::vector<std::uint8_t> contestedCells(const AnnotatedGrid& grid, std::span<const Agent> agents) {
  const GridMap& map = grid.map();
  const int w = map.width();
  const int h = map.height();
  std::vector<std::uint8_t> contested(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (const Agent& agent : agents) {
    const std::vector<std::uint8_t> room = passingRoom(grid, agent);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        if (room[i] != 0 || !grid.canStand(agent, {x, y})) continue;
        for (int dy = 0; dy < agent.size && y + dy < h; ++dy) {
          for (int dx = 0; dx < agent.size && x + dx < w; ++dx)
            contested[i + static_cast<std::size_t>(dy) * static_cast<std::size_t>(w) +
                      static_cast<std::size_t>(dx)] = 1;
        }
      }
    }
  }
  return contested;
}

// --- The space-time search ---

std::string problemWith(const CooperativeRequest& r) {
  if (r.agent.size < 1) return "agent.size must be >= 1 (got " + std::to_string(r.agent.size) + ")";
  if (r.startTicks < 0) return "startTicks must be >= 0 (got " + std::to_string(r.startTicks) + ")";
  if (r.waitTicks < 1) return "waitTicks must be >= 1 (got " + std::to_string(r.waitTicks) + ")";
  if (r.window < 1) return "window must be >= 1 (got " + std::to_string(r.window) + ")";
  if (r.maxWindow < r.window) {
    return "maxWindow must be >= window (" + std::to_string(r.window) + "), got " +
           std::to_string(r.maxWindow);
  }
  if (r.holdTicks < 0) return "holdTicks must be >= 0 (got " + std::to_string(r.holdTicks) + ")";
  if (r.expansionLimit < 1) return "expansionLimit must be >= 1 (got 0)";
  bool any = false;
  for (int slot = 0; slot < kTraversableTerrainSlots; ++slot) {
    const double t = r.ticksPerCell[static_cast<std::size_t>(slot)];
    any = any ||
          (r.agent.capability.allows(static_cast<Terrain>(slot)) && t > 0.0 && std::isfinite(t));
  }
  if (!any) return "ticksPerCell must be positive on a terrain of the agent's capability";
  return {};
}

CooperativeSearch::CooperativeSearch(const AnnotatedGrid& grid) : grid_(grid) {}

CooperativePlan CooperativeSearch::plan(const CooperativeRequest& r, DistanceField& field,
                                        const ReservationTable& table) {
  const QueryClock clock;
  CooperativePlan out;
  const GridMap& map = grid_.map();
  if (!problemWith(r).empty() || !grid_.canStand(r.agent, r.start)) {
    out.status = CooperativeStatus::InvalidStart;
    return out;
  }
  if (!grid_.canStand(r.agent, r.goal)) {
    out.status = CooperativeStatus::InvalidGoal;
    return out;
  }
  const double startDistance = field.distance(r.start);
  if (!std::isfinite(startDistance)) {
    out.status = CooperativeStatus::Unreachable;
    return out;
  }
  double minTicks = kInfinity;
  for (int slot = 0; slot < kTraversableTerrainSlots; ++slot) {
    const double t = r.ticksPerCell[static_cast<std::size_t>(slot)];
    if (r.agent.capability.allows(static_cast<Terrain>(slot)) && t > 0.0 && std::isfinite(t))
      minTicks = std::min(minTicks, t);
  }
  const int size = r.agent.size;
  const int half = size / 2;
  const std::span<const std::uint8_t> moves = grid_.layer(r.agent).moveMasks();
  const Tick windowEnd = r.startTick + r.window;
  const Tick hardEnd = r.startTick + r.maxWindow;

  nodes_.clear();
  open_.clear();
  seen_.clear();
  const auto order = [](const Open& a, const Open& b) {
    if (a.f != b.f) return a.f > b.f;
    if (a.g != b.g) return a.g < b.g;
    return a.node > b.node;
  };
  const auto key = [&](std::uint32_t cell, Tick tick) {
    return static_cast<std::uint64_t>(cell) << 32 | static_cast<std::uint32_t>(tick - r.startTick);
  };
  const auto add = [&](std::uint32_t cell, Tick tick, std::int32_t parent, double h) {
    if (!seen_.try_emplace(key(cell, tick), static_cast<std::uint32_t>(nodes_.size())).second)
      return;
    const bool moved = parent >= 0 && nodes_[static_cast<std::size_t>(parent)].cell != cell;
    const std::uint32_t moveCount =
        (parent >= 0 ? nodes_[static_cast<std::size_t>(parent)].moves : 0) + (moved ? 1 : 0);
    nodes_.push_back({cell, tick, parent, moveCount});
    const Tick g = tick - r.startTick;
    open_.push_back({static_cast<double>(g) + kMoveCost * moveCount + h * minTicks, g,
                     static_cast<std::uint32_t>(nodes_.size() - 1)});
    std::push_heap(open_.begin(), open_.end(), order);
    ++out.metrics.generated;
  };
  // True for the start and the waits at it that lead the plan.
  const auto startChain = [&](std::int32_t at) {
    for (; at >= 0; at = nodes_[static_cast<std::size_t>(at)].parent) {
      if (nodes_[static_cast<std::size_t>(at)].cell != nodes_.front().cell) return false;
    }
    return true;
  };
  const auto free = [&](Cell c, Tick from, Tick to) {
    return r.sharing != nullptr ? table.isFree(c, size, from, to, r.self, *r.sharing)
                                : table.isFree(c, size, from, to, r.self);
  };
  // Whoever shares the start with the agent now (bodies are not cells: two can round to one
  // anchor) does not stop it from staying there at first or leaving; anyone else who reserved
  // it later does.
  const std::vector<std::uint32_t> sharing =
      table.holders(r.start, size, r.startTick, r.startTick + 1, r.self);
  const auto freeAtStart = [&](Tick from, Tick to) {
    return table.isFree(r.start, size, from, to, r.self, sharing);
  };
  const auto keptOut = [&](Cell anchor) {
    int level = 0;
    if (r.keepOut == nullptr) return level;
    for (int dy = 0; dy < size; ++dy) {
      for (int dx = 0; dx < size; ++dx) {
        const Cell c{anchor.x + dx, anchor.y + dy};
        if (map.contains(c)) level = std::max<int>(level, (*r.keepOut)[map.indexOf(c)]);
      }
    }
    return level;
  };

  add(map.indexOf(r.start), r.startTick, -1, startDistance);
  std::int32_t found = -1;
  std::int32_t deepest = 0;  // the node reached latest: the longest safe prefix
  double deepestH = startDistance;
  while (!open_.empty() && out.metrics.expanded < r.expansionLimit) {
    std::pop_heap(open_.begin(), open_.end(), order);
    const auto index = static_cast<std::int32_t>(open_.back().node);
    open_.pop_back();
    const Node node = nodes_[static_cast<std::size_t>(index)];
    const Cell here = cellAt(map, node.cell);
    const double h = field.distance(here);
    if (node.tick > nodes_[static_cast<std::size_t>(deepest)].tick ||
        (node.tick == nodes_[static_cast<std::size_t>(deepest)].tick && h < deepestH)) {
      deepest = index;
      deepestH = h;
    }
    if (here == r.goal && free(here, node.tick, kForever)) {
      out.status = CooperativeStatus::ReachedGoal;
      found = index;
      break;
    }
    // Within a wait of the window's end counts as there, so waiting is never outdone by a
    // shuffle that lands on the end tick exactly.
    const int level = keptOut(here);
    if (node.tick + r.waitTicks > windowEnd && free(here, node.tick, node.tick + r.holdTicks) &&
        (((r.passing == nullptr || (*r.passing)[node.cell] != 0) && level == 0) ||
         node.tick >= hardEnd)) {
      out.status = CooperativeStatus::Windowed;
      found = index;
      break;
    }
    ++out.metrics.expanded;
    if (node.tick >= hardEnd) continue;  // a dead end: not free to stay, and no time left
    // The agent stands at its start already: staying there at first, and leaving it, are
    // checked against the table without those who share it now (freeAtStart).
    const bool atStart = node.cell == nodes_.front().cell && node.tick - r.startTick <= r.window &&
                         startChain(index);
    // A move from rest takes longer: the schedule is one the agent can keep to.
    const bool atRest = node.parent < 0
                            ? r.startsAtRest
                            : nodes_[static_cast<std::size_t>(node.parent)].cell == node.cell;
    const std::uint8_t mask = moves[node.cell];
    // Whether the agent may hold `here` until each leaving time asked so far: moves differ in
    // length and terrain, but few leave at different times.
    std::array<std::pair<Tick, bool>, kDirectionCount> leaving{};
    std::size_t leavings = 0;
    const auto mayLeaveBy = [&](Tick leaveBy) {
      for (std::size_t i = 0; i < leavings; ++i) {
        if (leaving[i].first == leaveBy) return leaving[i].second;
      }
      const bool ok = atStart ? freeAtStart(node.tick, leaveBy) : free(here, node.tick, leaveBy);
      leaving[leavings++] = {leaveBy, ok};
      return ok;
    };
    for (int d = 0; d < kDirectionCount; ++d) {
      if ((mask & (1u << d)) == 0) continue;
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      const Cell next{here.x + dir.dx, here.y + dir.dy};
      const Terrain under = map.at({next.x + half, next.y + half});
      if (!isTraversable(under)) continue;
      const double perCell = r.ticksPerCell[static_cast<std::size_t>(under)];
      if (!(perCell > 0.0) || !std::isfinite(perCell)) continue;
      const Tick duration =
          std::max<Tick>(1, static_cast<Tick>(std::ceil(dir.cost * perCell - 1e-9))) +
          (atRest ? r.startTicks : 0);
      const double nextH = field.distance(next);
      if (!std::isfinite(nextH)) continue;
      if (const int nextLevel = keptOut(next); nextLevel > 0 && nextLevel >= level) continue;
      const MoveSpan span = moveSpan(node.tick, duration);
      if (!mayLeaveBy(span.leaveBy) || !free(next, span.enterAt, node.tick + duration)) continue;
      add(map.indexOf(next), node.tick + duration, index, nextH);
    }
    // Nobody waits where others cannot pass or where kept out (but one already standing there
    // may stay at first).
    const bool roomToWait = (r.passing == nullptr || (*r.passing)[node.cell] != 0) && level == 0;
    if (atStart ? freeAtStart(node.tick, node.tick + r.waitTicks)
                : roomToWait && free(here, node.tick, node.tick + r.waitTicks))
      add(node.cell, node.tick + r.waitTicks, index, h);
  }
  if (found < 0) {
    out.status = CooperativeStatus::Blocked;
    found = deepest;
  }
  for (std::int32_t at = found; at >= 0; at = nodes_[static_cast<std::size_t>(at)].parent) {
    const Node& n = nodes_[static_cast<std::size_t>(at)];
    out.steps.push_back({cellAt(map, n.cell), n.tick});
  }
  std::reverse(out.steps.begin(), out.steps.end());
  out.metrics.microseconds = clock.elapsedMicroseconds();
  return out;
}

void CooperativeSearch::reserve(ReservationTable& table, std::span<const TimedCell> steps, int size,
                                std::uint32_t owner, Tick hold) {
  for (std::size_t i = 0; i + 1 < steps.size(); ++i) {
    const TimedCell& a = steps[i];
    const TimedCell& b = steps[i + 1];
    if (b.cell == a.cell) {
      table.reserve(a.cell, size, a.tick, b.tick, owner);
      continue;
    }
    const MoveSpan span = moveSpan(a.tick, b.tick - a.tick);
    table.reserve(a.cell, size, a.tick, span.leaveBy, owner);
    table.reserve(b.cell, size, span.enterAt, b.tick, owner);
  }
  if (steps.empty()) return;
  const TimedCell& last = steps.back();
  const Tick until = hold == kForever || last.tick > kForever - hold ? kForever : last.tick + hold;
  table.reserve(last.cell, size, last.tick, until, owner);
}

}  // namespace warpath::pathing
