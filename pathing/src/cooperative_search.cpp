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

bool ReverseResumableSearch::settle(Cell c, std::uint64_t& allowance) {
  // Where the agent cannot stand nothing is reached: answered without searching everything.
  if (!grid_.canStand(agent_, c)) return true;
  const std::uint32_t wanted = map_.indexOf(c);
  if (const auto it = entries_.find(wanted); it != entries_.end() && it->second.closed) return true;
  const auto order = [](const Open& a, const Open& b) {
    if (a.f != b.f) return a.f > b.f;
    if (a.g != b.g) return a.g < b.g;
    return a.cell > b.cell;
  };
  while (!open_.empty()) {
    if (allowance == 0) return false;
    std::pop_heap(open_.begin(), open_.end(), order);
    const Open top = open_.back();
    open_.pop_back();
    Entry& e = entries_[top.cell];
    if (e.closed) continue;
    if (top.g > e.g) continue;  // a stale copy: a shorter one was pushed later
    e.closed = true;
    e.g = top.g;
    ++expanded_;
    --allowance;
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
    if (top.cell == wanted) return true;
  }
  return true;  // the open list ran out: unreachable
}

double ReverseResumableSearch::settled(Cell c) const {
  if (!grid_.canStand(agent_, c)) return kInfinity;
  const auto it = entries_.find(map_.indexOf(c));
  return it != entries_.end() && it->second.closed ? it->second.g : kInfinity;
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
  // Each row's span, from its first marked cell to its last; a slot per cell of it.
  rowX0_.assign(static_cast<std::size_t>(height), 0);
  rowBegin_.assign(static_cast<std::size_t>(height) + 1, 0);
  std::uint32_t cells = 0;
  for (int r = 0; r < height; ++r) {
    const std::uint64_t* row = &marked[static_cast<std::size_t>(r) * words];
    int first = width;
    int last = -1;
    for (std::size_t w = 0; w < words; ++w) {
      if (row[w] == 0) continue;
      const int base = static_cast<int>(w) * 64;
      first = std::min(first, base + std::countr_zero(row[w]));
      last = std::max(last, base + 63 - std::countl_zero(row[w]));
    }
    rowBegin_[static_cast<std::size_t>(r)] = cells;
    rowX0_[static_cast<std::size_t>(r)] = left + (last >= first ? first : 0);
    if (last >= first) cells += static_cast<std::uint32_t>(last - first + 1);
  }
  rowBegin_[static_cast<std::size_t>(height)] = cells;
  distances_.assign(cells, kInfinity);

  // Dijkstra from the goal over the corridor (moves are symmetric; they lead only to cells the
  // agent may stand on), run by settle(). Final distances do not depend on the order among
  // equal keys, nor on where slices end: a cell's distance is the least of its closer
  // neighbours' plus a move, and moves cost at least 1.
  if (!grid.canStand(agent, path.back())) return;
  const std::span<const std::uint8_t> moves = grid.layer(agent).moveMasks();
  cellOf_.resize(cells);
  state_.assign(cells, kOutside);
  moves_.assign(cells, 0);
  for (int r = 0; r < height; ++r) {
    const std::uint64_t* row = &marked[static_cast<std::size_t>(r) * words];
    const auto ri = static_cast<std::size_t>(r);
    for (std::uint32_t at = rowBegin_[ri]; at < rowBegin_[ri + 1]; ++at) {
      const int x = rowX0_[ri] + static_cast<int>(at - rowBegin_[ri]);
      const int bit = x - left;
      cellOf_[at] = {x, top_ + r};
      if (((row[bit / 64] >> (bit % 64)) & 1u) == 0) continue;
      state_[at] = kOpen;
      moves_[at] = moves[map.indexOf({x, top_ + r})];
    }
  }
  const auto goal = static_cast<std::uint32_t>(slot(path.back()));
  distances_[goal] = 0.0;
  open_.push(false, OpenList::makeKey(0.0, 0.0), goal);
}

bool CorridorDistance::settle(Cell /*c*/, std::uint64_t& allowance) {
  // Raw pointers: the stores to state_ would otherwise make the compiler reload the vectors'
  // data pointers (a byte store may alias them).
  double* const distances = distances_.data();
  std::uint8_t* const state = state_.data();
  const Cell* const cellOf = cellOf_.data();
  const std::uint8_t* const moves = moves_.data();
  while (!open_.empty()) {
    if (allowance == 0) return false;
    const std::uint32_t current = open_.pop();
    if (state[current] == kClosed) continue;
    state[current] = kClosed;
    ++expanded_;
    --allowance;
    const double g = distances[current];
    const Cell here = cellOf[current];
    for (unsigned mask = moves[current]; mask != 0; mask &= mask - 1) {
      const int d = std::countr_zero(mask);
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      const std::ptrdiff_t at = slot({here.x + dir.dx, here.y + dir.dy});
      if (at < 0 || state[at] == kOutside) continue;
      double& known = distances[at];
      if (known <= g + dir.cost) continue;
      known = g + dir.cost;
      open_.push(isDiagonal(d), OpenList::makeKey(known, known), static_cast<std::uint32_t>(at));
    }
  }
  if (!cellOf_.empty()) {  // done: the scratch goes
    cellOf_ = {};
    state_ = {};
    moves_ = {};
    open_ = {};
  }
  return true;
}

double CorridorDistance::settled(Cell c) const {
  const std::ptrdiff_t at = slot(c);
  return at < 0 ? kInfinity : distances_[static_cast<std::size_t>(at)];
}

// --- Passing room ---

namespace {

// Gives passing room to the dents among the anchors without it (Dents::Open): 8-connected sets
// of such anchors at most 2s + 1 across whose bordering anchors with room are joined through
// anchors with room close by (the set's bounding box grown by 2s + 1 cells). A notch in a
// forest's ragged edge is one, and so is a gap between a rock and a swamp: a unit standing
// there blocks nobody, as the others go by just outside. A door is not (its two sides meet only
// through it, or far away), nor a corridor or a bridge (longer than that as well).
void openDents(const AnnotatedGrid& grid, Agent agent, std::vector<std::uint8_t>& room) {
  const GridMap& map = grid.map();
  const int w = map.width();
  const int h = map.height();
  const std::span<const std::uint8_t> moves = grid.layer(agent).moveMasks();
  const auto index = [w](Cell c) {
    return static_cast<std::size_t>(c.y) * static_cast<std::size_t>(w) +
           static_cast<std::size_t>(c.x);
  };
  const auto withRoom = [&](Cell c) { return room[index(c)] != 0 && grid.canStand(agent, c); };
  const auto narrow = [&](Cell c) { return room[index(c)] == 0 && grid.canStand(agent, c); };
  const auto forNeighbours = [&](Cell c, auto&& f) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const Cell n{c.x + dx, c.y + dy};
        if ((dx != 0 || dy != 0) && map.contains(n)) f(n);
      }
    }
  };
  // The last visit per anchor: a set's members keep its stamp, so each set is found once.
  std::vector<std::uint32_t> stamp(room.size(), 0);
  std::uint32_t visit = 0;
  std::vector<Cell> members;
  std::vector<Cell> dents;  // opened once all are found: a set is judged by the room of before
  std::vector<Cell> border;
  std::vector<Cell> stack;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!narrow({x, y}) || stamp[index({x, y})] != 0) continue;
      const std::uint32_t set = ++visit;
      members.clear();
      stack.assign(1, {x, y});
      stamp[index({x, y})] = set;
      Cell low{x, y};
      Cell high{x, y};
      while (!stack.empty()) {
        const Cell c = stack.back();
        stack.pop_back();
        members.push_back(c);
        low = {std::min(low.x, c.x), std::min(low.y, c.y)};
        high = {std::max(high.x, c.x), std::max(high.y, c.y)};
        forNeighbours(c, [&](Cell n) {
          if (!narrow(n) || stamp[index(n)] == set) return;
          stamp[index(n)] = set;
          stack.push_back(n);
        });
      }
      const int span = 2 * std::max(1, agent.size) + 1;
      if (high.x - low.x >= span || high.y - low.y >= span) continue;
      // Its border.
      const std::uint32_t bordering = ++visit;
      border.clear();
      for (const Cell& c : members) {
        forNeighbours(c, [&](Cell n) {
          if (!withRoom(n) || stamp[index(n)] == bordering) return;
          stamp[index(n)] = bordering;
          border.push_back(n);
        });
      }
      if (border.empty()) continue;
      // Round it: from one bordering anchor, by the agent's moves through anchors with room.
      const int margin = span;
      const Cell boxLow{std::max(0, low.x - margin), std::max(0, low.y - margin)};
      const Cell boxHigh{std::min(w - 1, high.x + margin), std::min(h - 1, high.y + margin)};
      const std::uint32_t round = ++visit;
      stack.assign(1, border.front());
      stamp[index(border.front())] = round;
      while (!stack.empty()) {
        const Cell c = stack.back();
        stack.pop_back();
        const std::uint8_t mask = moves[index(c)];
        for (int d = 0; d < kDirectionCount; ++d) {
          if ((mask & (1u << d)) == 0) continue;
          const Direction& dir = kDirections[static_cast<std::size_t>(d)];
          const Cell n{c.x + dir.dx, c.y + dir.dy};
          if (n.x < boxLow.x || n.x > boxHigh.x || n.y < boxLow.y || n.y > boxHigh.y) continue;
          if (stamp[index(n)] == round || !withRoom(n)) continue;
          stamp[index(n)] = round;
          stack.push_back(n);
        }
      }
      if (!std::all_of(border.begin(), border.end(),
                       [&](Cell b) { return stamp[index(b)] == round; }))
        continue;
      dents.insert(dents.end(), members.begin(), members.end());
    }
  }
  for (const Cell& c : dents)
    room[index(c)] = 1;
}

}  // namespace

std::vector<std::uint8_t> passingRoom(const AnnotatedGrid& grid, Agent agent, Dents dents) {
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
  if (dents == Dents::Open) openDents(grid, agent, room);
  return room;
}

std::vector<std::uint8_t> contestedCells(const AnnotatedGrid& grid, std::span<const Agent> agents,
                                         Dents dents) {
  const GridMap& map = grid.map();
  const int w = map.width();
  const int h = map.height();
  std::vector<std::uint8_t> contested(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (const Agent& agent : agents) {
    const std::vector<std::uint8_t> room = passingRoom(grid, agent, dents);
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
  beginPlan(r, field, table);
  updatePlan(kUnboundedExpansions);
  return finalizePlan();
}

CooperativeSearch::OpenHeap::Entry CooperativeSearch::OpenHeap::entry(double f, Tick g,
                                                                      std::uint32_t node) {
  // g is ticks since the start, within a window (the state keys take 32 bits of it too).
  const auto ticks = static_cast<std::uint64_t>(std::clamp<Tick>(g, 0, 0xFFFFFFFF));
  return {std::bit_cast<std::uint64_t>(f), (0xFFFFFFFFull - ticks) << 32 | node};
}

void CooperativeSearch::OpenHeap::push(Entry e) {
  std::size_t i = heap_.size();
  heap_.push_back(e);
  Entry* const h = heap_.data();
  while (i > 0) {
    const std::size_t parent = (i - 1) / 4;
    if (!before(e, h[parent])) break;
    h[i] = h[parent];
    i = parent;
  }
  h[i] = e;
}

CooperativeSearch::OpenHeap::Entry CooperativeSearch::OpenHeap::pop() {
  const Entry top = heap_.front();
  const Entry last = heap_.back();
  heap_.pop_back();
  const std::size_t n = heap_.size();
  if (n == 0) return top;
  Entry* const h = heap_.data();
  std::size_t i = 0;
  for (;;) {
    const std::size_t first = 4 * i + 1;
    if (first >= n) break;
    std::size_t best = first;
    const std::size_t end = std::min(first + 4, n);
    for (std::size_t c = first + 1; c < end; ++c) {
      if (before(h[c], h[best])) best = c;
    }
    if (!before(h[best], last)) break;
    h[i] = h[best];
    i = best;
  }
  h[i] = last;
  return top;
}

CooperativeStatus CooperativeSearch::beginPlan(const CooperativeRequest& r, DistanceField& field,
                                               const ReservationTable& table) {
  const QueryClock clock;
  request_ = r;
  field_ = &field;
  fieldComplete_ = false;
  table_ = &table;
  plan_ = {};
  current_ = -1;
  phase_ = Phase::Done;
  if (!problemWith(r).empty() || !grid_.canStand(r.agent, r.start)) {
    plan_.status = CooperativeStatus::InvalidStart;
  } else if (!grid_.canStand(r.agent, r.goal)) {
    plan_.status = CooperativeStatus::InvalidGoal;
  } else {
    plan_.status = CooperativeStatus::Pending;
    phase_ = Phase::Start;
  }
  plan_.metrics.microseconds = clock.elapsedMicroseconds();
  return plan_.status;
}

bool CooperativeSearch::settle(Cell c, std::uint64_t& allowance) {
  if (fieldComplete_) return true;
  const std::uint64_t before = allowance;
  const bool done = field_->settle(c, allowance);
  plan_.fieldExpanded += before - allowance;
  fieldComplete_ = done && field_->complete();
  return done;
}

std::size_t CooperativeSearch::movesFrom(Cell here, std::array<Move, kDirectionCount>& out) const {
  const GridMap& map = grid_.map();
  const int half = request_.agent.size / 2;
  const std::uint8_t mask = moveMasks_[map.indexOf(here)];
  std::size_t count = 0;
  for (unsigned bits = mask; bits != 0; bits &= bits - 1) {
    const int d = std::countr_zero(bits);
    const Direction& dir = kDirections[static_cast<std::size_t>(d)];
    const Cell next{here.x + dir.dx, here.y + dir.dy};
    const Terrain under = map.at({next.x + half, next.y + half});
    if (!isTraversable(under)) continue;
    const Tick ticks = moveTicks_[isDiagonal(d) ? 1 : 0][static_cast<std::size_t>(under)];
    if (ticks > 0) out[count++] = {next, ticks};
  }
  return count;
}

void CooperativeSearch::add(std::uint32_t cell, Tick tick, std::int32_t parent, double h) {
  const CooperativeRequest& r = request_;
  const auto key =
      static_cast<std::uint64_t>(cell) << 32 | static_cast<std::uint32_t>(tick - r.startTick);
  if (!seen_.insert(key)) return;
  const bool moved = parent >= 0 && nodes_[static_cast<std::size_t>(parent)].cell != cell;
  const std::uint32_t moveCount =
      (parent >= 0 ? nodes_[static_cast<std::size_t>(parent)].moves : 0) + (moved ? 1 : 0);
  nodes_.push_back({cell, tick, parent, moveCount});
  const Tick g = tick - r.startTick;
  open_.push(OpenHeap::entry(static_cast<double>(g) + kMoveCost * moveCount + h * minTicks_, g,
                             static_cast<std::uint32_t>(nodes_.size() - 1)));
  ++plan_.metrics.generated;
}

void CooperativeSearch::SeenStates::clear() {
  // Sized for the plan just done, as most plans reach few states.
  if (slots_.size() > kSmallSlots && used_.size() * 16 < slots_.size()) {
    slots_.assign(kSmallSlots, Slot{});
  } else {
    for (const std::uint32_t i : used_)
      slots_[i] = Slot{};
  }
  used_.clear();
  bits_.clear();
}

std::size_t CooperativeSearch::SeenStates::home(std::uint64_t block) const {
  // Fibonacci hashing: the top bits of block * 2^64 / phi.
  return static_cast<std::size_t>((block * 0x9E3779B97F4A7C15ull) >> 32) & (slots_.size() - 1);
}

std::size_t CooperativeSearch::SeenStates::slotOf(std::uint64_t block) const {
  std::size_t i = home(block);
  while (slots_[i].block != block && slots_[i].block != kEmptySlot)
    i = (i + 1) & (slots_.size() - 1);
  return i;
}

bool CooperativeSearch::SeenStates::insert(std::uint64_t key) {
  if ((used_.size() + 1) * 2 > slots_.size()) grow();
  const std::uint64_t block = (key >> 32) << 32 | (key & 0xFFFFFFFFu) >> kTickBits;
  const std::size_t i = slotOf(block);
  Slot& slot = slots_[i];
  if (slot.block == kEmptySlot) {
    slot = {block, static_cast<std::uint32_t>(bits_.size())};
    used_.push_back(static_cast<std::uint32_t>(i));
    bits_.resize(bits_.size() + kWords, 0);
  }
  const std::uint64_t tick = key & ((std::uint64_t{1} << kTickBits) - 1);
  std::uint64_t& word = bits_[slot.bits + tick / 64];
  const std::uint64_t bit = std::uint64_t{1} << (tick % 64);
  if ((word & bit) != 0) return false;
  word |= bit;
  return true;
}

void CooperativeSearch::SeenStates::grow() {
  std::vector<Slot> held;
  held.reserve(used_.size());
  for (const std::uint32_t i : used_)
    held.push_back(slots_[i]);
  slots_.assign(std::max(slots_.size() * 2, kSmallSlots), Slot{});
  used_.clear();
  for (const Slot& slot : held) {
    const std::size_t i = slotOf(slot.block);  // an empty one: the blocks are distinct
    slots_[i] = slot;
    used_.push_back(static_cast<std::uint32_t>(i));
  }
}

bool CooperativeSearch::startChain(std::int32_t at) const {
  // True for the start and the waits at it that lead the plan.
  for (; at >= 0; at = nodes_[static_cast<std::size_t>(at)].parent) {
    if (nodes_[static_cast<std::size_t>(at)].cell != nodes_.front().cell) return false;
  }
  return true;
}

bool CooperativeSearch::free(Cell c, Tick from, Tick to) const {
  const CooperativeRequest& r = request_;
  return r.sharing != nullptr ? table_->isFree(c, r.agent.size, from, to, r.self, *r.sharing)
                              : table_->isFree(c, r.agent.size, from, to, r.self);
}

bool CooperativeSearch::freeAtStart(const std::vector<std::uint32_t>& startSharing, Tick from,
                                    Tick to) const {
  return table_->isFree(request_.start, request_.agent.size, from, to, request_.self, startSharing);
}

int CooperativeSearch::keptOut(Cell anchor) const {
  if (request_.keepOut == nullptr) return 0;
  const GridMap& map = grid_.map();
  const int size = request_.agent.size;
  const std::uint8_t* const levels = request_.keepOut->data();
  if (size == 1) {  // most agents: one cell, a level alone
    if (!map.contains(anchor)) return 0;
    const int level = levels[map.indexOf(anchor)];
    return level == 0 || request_.keepOutExit == KeepOutExit::HighestLevel ? level : 2 * level + 1;
  }
  const CellRect on = map.clip({anchor.x, anchor.y, size, size});
  int level = 0;
  int atLevel = 0;  // cells of the footprint at `level`
  for (int y = on.y; y < on.y + on.height; ++y) {
    const std::uint8_t* const row = levels + map.indexOf({0, y});
    for (int x = on.x; x < on.x + on.width; ++x) {
      const int here = row[x];
      if (here > level) {
        level = here;
        atLevel = 0;
      }
      if (here == level) ++atLevel;
    }
  }
  if (level == 0 || request_.keepOutExit == KeepOutExit::HighestLevel) return level;
  return level * (size * size + 1) + atLevel;  // by level, then by cells at it (<= size^2)
}

CooperativeStatus CooperativeSearch::updatePlan(std::uint64_t maxExpansions) {
  if (phase_ != Phase::Start && phase_ != Phase::Search) return plan_.status;
  const QueryClock clock;
  const CooperativeRequest& r = request_;
  const GridMap& map = grid_.map();
  std::uint64_t allowance = sliceEnd(expandedSoFar(), maxExpansions) - expandedSoFar();
  if (phase_ == Phase::Start) {
    if (!settle(r.start, allowance)) {
      plan_.metrics.microseconds += clock.elapsedMicroseconds();
      return plan_.status;
    }
    const double startDistance = field_->settled(r.start);
    if (!std::isfinite(startDistance)) {
      finish(CooperativeStatus::Unreachable, -1);
      plan_.metrics.microseconds += clock.elapsedMicroseconds();
      return plan_.status;
    }
    minTicks_ = kInfinity;
    for (int slot = 0; slot < kTraversableTerrainSlots; ++slot) {
      const double t = r.ticksPerCell[static_cast<std::size_t>(slot)];
      if (r.agent.capability.allows(static_cast<Terrain>(slot)) && t > 0.0 && std::isfinite(t))
        minTicks_ = std::min(minTicks_, t);
      for (const bool diagonal : {false, true}) {
        const double cost = diagonal ? kSqrt2 : 1.0;  // kDirections' costs
        moveTicks_[diagonal ? 1 : 0][static_cast<std::size_t>(slot)] =
            t > 0.0 && std::isfinite(t)
                ? std::max<Tick>(1, static_cast<Tick>(std::ceil(cost * t - 1e-9)))
                : 0;
      }
    }
    moveMasks_ = grid_.layer(r.agent).moveMasks();  // looked up once: the grid is locked
    windowEnd_ = r.startTick + r.window;
    hardEnd_ = r.startTick + r.maxWindow;
    nodes_.clear();
    open_.clear();
    seen_.clear();
    startSharing_ = table_->holders(r.start, r.agent.size, r.startTick, r.startTick + 1, r.self);
    add(map.indexOf(r.start), r.startTick, -1, startDistance);
    deepest_ = 0;
    deepestH_ = startDistance;
    phase_ = Phase::Search;
  }
  std::array<Move, kDirectionCount> moves{};
  while (phase_ == Phase::Search) {
    if (current_ < 0) {
      if (open_.empty() || plan_.metrics.expanded >= r.expansionLimit) {
        finish(CooperativeStatus::Blocked, deepest_);
        break;
      }
      if (allowance == 0) break;
      current_ = static_cast<std::int32_t>(OpenHeap::nodeOf(open_.pop()));
    }
    // What follows is done again for the same node when a slice ends before its expansion:
    // everything up to the expansion only reads (the deepest node is the same again).
    const std::int32_t index = current_;
    const Node node = nodes_[static_cast<std::size_t>(index)];
    const Cell here = cellAt(map, node.cell);
    if (!settle(here, allowance)) break;
    const double h = field_->settled(here);
    if (node.tick > nodes_[static_cast<std::size_t>(deepest_)].tick ||
        (node.tick == nodes_[static_cast<std::size_t>(deepest_)].tick && h < deepestH_)) {
      deepest_ = index;
      deepestH_ = h;
    }
    if (here == r.goal && free(here, node.tick, kForever)) {
      finish(CooperativeStatus::ReachedGoal, index);
      break;
    }
    // Within a wait of the window's end counts as there, so waiting is never outdone by a
    // shuffle that lands on the end tick exactly.
    const int rank = keptOut(here);
    if (node.tick + r.waitTicks > windowEnd_ && free(here, node.tick, node.tick + r.holdTicks) &&
        (((r.passing == nullptr || (*r.passing)[node.cell] != 0) && rank == 0) ||
         node.tick >= hardEnd_)) {
      finish(CooperativeStatus::Windowed, index);
      break;
    }
    // The expansion: the distances of the cells its moves reach first, then one expansion.
    const bool deadEnd = node.tick >= hardEnd_;  // not free to stay, and no time left
    bool settled = true;
    const std::size_t count = deadEnd ? 0 : movesFrom(here, moves);
    for (std::size_t i = 0; i < count && settled; ++i)
      settled = settle(moves[i].next, allowance);
    if (!settled || allowance == 0) break;
    --allowance;
    ++plan_.metrics.expanded;
    current_ = -1;
    if (!deadEnd) expand(index, here, h, rank, std::span(moves).first(count));
  }
  plan_.metrics.microseconds += clock.elapsedMicroseconds();
  return plan_.status;
}

void CooperativeSearch::expand(std::int32_t index, Cell here, double h, int rank,
                               std::span<const Move> moves) {
  const CooperativeRequest& r = request_;
  const GridMap& map = grid_.map();
  const Node node = nodes_[static_cast<std::size_t>(index)];
  // The agent stands at its start already: staying there at first, and leaving it, are
  // checked against the table without those who share it now (startSharing_).
  const bool atStart =
      node.cell == nodes_.front().cell && node.tick - r.startTick <= r.window && startChain(index);
  // A move from rest takes longer: the schedule is one the agent can keep to.
  const bool atRest = node.parent < 0
                          ? r.startsAtRest
                          : nodes_[static_cast<std::size_t>(node.parent)].cell == node.cell;
  // Whether the agent may hold `here` until each leaving time asked so far: moves differ in
  // length and terrain, but few leave at different times.
  std::array<std::pair<Tick, bool>, kDirectionCount> leaving{};
  std::size_t leavings = 0;
  const auto mayLeaveBy = [&](Tick leaveBy) {
    for (std::size_t i = 0; i < leavings; ++i) {
      if (leaving[i].first == leaveBy) return leaving[i].second;
    }
    const bool ok =
        atStart ? freeAtStart(startSharing_, node.tick, leaveBy) : free(here, node.tick, leaveBy);
    leaving[leavings++] = {leaveBy, ok};
    return ok;
  };
  for (const Move& move : moves) {
    const Cell next = move.next;
    const Tick duration = move.ticks + (atRest ? r.startTicks : 0);
    const double nextH = field_->settled(next);
    if (!std::isfinite(nextH)) continue;
    if (const int nextRank = keptOut(next); nextRank > 0 && nextRank >= rank) continue;
    const MoveSpan span = moveSpan(node.tick, duration);
    if (!mayLeaveBy(span.leaveBy) || !free(next, span.enterAt, node.tick + duration)) continue;
    add(map.indexOf(next), node.tick + duration, index, nextH);
  }
  // Nobody waits where others cannot pass or where kept out (but one already standing where
  // others cannot pass may stay at first, and one kept out as keepOutExit says).
  const bool roomToWait = (r.passing == nullptr || (*r.passing)[node.cell] != 0) && rank == 0;
  const bool mayStayAtStart = rank == 0 || r.keepOutExit == KeepOutExit::HighestLevel;
  if (atStart ? mayStayAtStart && freeAtStart(startSharing_, node.tick, node.tick + r.waitTicks)
              : roomToWait && free(here, node.tick, node.tick + r.waitTicks))
    add(node.cell, node.tick + r.waitTicks, index, h);
}

void CooperativeSearch::finish(CooperativeStatus status, std::int32_t at) {
  plan_.status = status;
  phase_ = Phase::Done;
  current_ = -1;
  const GridMap& map = grid_.map();
  for (; at >= 0; at = nodes_[static_cast<std::size_t>(at)].parent) {
    const Node& n = nodes_[static_cast<std::size_t>(at)];
    plan_.steps.push_back({cellAt(map, n.cell), n.tick});
  }
  std::reverse(plan_.steps.begin(), plan_.steps.end());
}

CooperativePlan CooperativeSearch::finalizePlan() const {
  if (phase_ != Phase::Done) {
    CooperativePlan pending;
    pending.status = CooperativeStatus::Pending;
    pending.metrics = plan_.metrics;
    pending.fieldExpanded = plan_.fieldExpanded;
    return pending;
  }
  return plan_;
}

CooperativePlan CooperativeSearch::finalizePlanAt(Tick startTick) const {
  CooperativePlan out = finalizePlan();
  const Tick delay = startTick - request_.startTick;
  if (out.steps.empty() || delay <= 0) return out;
  // Planned at speed, the first move now starts from rest (a leading wait was planned so).
  const bool slower =
      !request_.startsAtRest && out.steps.size() > 1 && out.steps[1].cell != out.steps[0].cell;
  for (std::size_t i = 0; i < out.steps.size(); ++i)
    out.steps[i].tick += delay + (slower && i > 0 ? request_.startTicks : 0);
  if (!stillFree(out)) {
    out.status = CooperativeStatus::Blocked;
    out.steps = {{request_.start, startTick}};
  }
  return out;
}

bool CooperativeSearch::stillFree(const CooperativePlan& plan) const {
  const CooperativeRequest& r = request_;
  const std::vector<TimedCell>& steps = plan.steps;
  const std::vector<std::uint32_t> startSharing =
      table_->holders(r.start, r.agent.size, steps.front().tick, steps.front().tick + 1, r.self);
  bool atStart = true;  // the start and the waits there that lead the plan
  for (std::size_t i = 0; i + 1 < steps.size(); ++i) {
    const TimedCell& a = steps[i];
    const TimedCell& b = steps[i + 1];
    atStart = atStart && a.cell == r.start && a.tick - steps.front().tick <= r.window;
    if (b.cell == a.cell) {
      if (!(atStart ? freeAtStart(startSharing, a.tick, b.tick) : free(a.cell, a.tick, b.tick)))
        return false;
      continue;
    }
    const MoveSpan span = moveSpan(a.tick, b.tick - a.tick);
    if (!(atStart ? freeAtStart(startSharing, a.tick, span.leaveBy)
                  : free(a.cell, a.tick, span.leaveBy)) ||
        !free(b.cell, span.enterAt, b.tick))
      return false;
  }
  const TimedCell& last = steps.back();
  Tick hold = r.waitTicks;
  if (plan.status == CooperativeStatus::Windowed) hold = r.holdTicks;
  if (plan.status == CooperativeStatus::ReachedGoal) hold = kForever - last.tick;
  return free(last.cell, last.tick, last.tick + hold);
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
