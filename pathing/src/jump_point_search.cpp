#include "pathing/jump_point_search.h"

#include <algorithm>
#include <cstdlib>

#include "pathing/moves.h"

namespace warpath::pathing {

// What the jumps of one query read: where the agent can stand, inside the map (or the
// query's region), and the goal.
struct JumpPointSearch::Query {
  const ClearanceField::Value* clearance = nullptr;
  int width = 0;
  CellRect bounds;
  int size = 1;
  std::uint32_t goal = 0;

  bool walkable(int x, int y) const {
    return bounds.contains({x, y}) &&
           clearance[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)] >= size;
  }
  std::uint32_t indexOf(int x, int y) const {
    return static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(width) +
           static_cast<std::uint32_t>(x);
  }
};

JumpPointSearch::JumpPointSearch(const AnnotatedGrid& grid) : grid_(grid) {}

void JumpPointSearch::beginQuery() {
  const std::size_t cells = grid_.map().cellCount();
  if (stamps_.size() != cells) {
    stamps_.assign(cells, 0);
    g_.assign(cells, 0.0);
    parent_.assign(cells, kNone);
    generation_ = 0;
  }
  if (++generation_ == (1u << 31)) {  // wrapped: forget every stamp
    std::fill(stamps_.begin(), stamps_.end(), 0);
    generation_ = 1;
  }
  open_.clear();
}

// From (x, y), straight along (dx, dy): the first cell with a neighbour beside the line that
// opens after a blocked cell behind it (only a path turning there reaches that neighbour
// optimally), or the goal; kNone at a wall.
std::uint32_t JumpPointSearch::jumpStraight(const Query& q, int x, int y, int dx, int dy) const {
  for (;;) {
    x += dx;
    y += dy;
    if (!q.walkable(x, y)) return kNone;
    const std::uint32_t at = q.indexOf(x, y);
    if (at == q.goal) return at;
    if (dx != 0) {
      if ((q.walkable(x, y - 1) && !q.walkable(x - dx, y - 1)) ||
          (q.walkable(x, y + 1) && !q.walkable(x - dx, y + 1)))
        return at;
    } else if ((q.walkable(x - 1, y) && !q.walkable(x - 1, y - dy)) ||
               (q.walkable(x + 1, y) && !q.walkable(x + 1, y - dy))) {
      return at;
    }
  }
}

// From (x, y) along (dx, dy), straight or diagonal. A diagonal step needs both cells beside
// it; a diagonal jump stops at a cell from which either straight jump finds something.
std::uint32_t JumpPointSearch::jump(const Query& q, int x, int y, int dx, int dy) const {
  if (dx == 0 || dy == 0) return jumpStraight(q, x, y, dx, dy);
  for (;;) {
    if (!q.walkable(x + dx, y) || !q.walkable(x, y + dy) || !q.walkable(x + dx, y + dy))
      return kNone;
    x += dx;
    y += dy;
    const std::uint32_t at = q.indexOf(x, y);
    if (at == q.goal || jumpStraight(q, x, y, dx, 0) != kNone ||
        jumpStraight(q, x, y, 0, dy) != kNone)
      return at;
  }
}

PathResult JumpPointSearch::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                                     const SearchLimits& limits) {
  const QueryClock clock;
  PathResult result;
  if (path) path->clear();
  const auto finish = [&](PathStatus status) { return finishQuery(result, status, clock); };
  if (const auto answer = screenEndpoints(grid_, agent, start, goal)) return finish(*answer);
  const GridMap& map = grid_.map();
  if (limits.region && (!limits.region->contains(start) || !limits.region->contains(goal)))
    return finish(PathStatus::Unreachable);
  if (limits.maxExpanded == 0) return finish(PathStatus::BudgetExhausted);
  // Different components: no search can connect them (as AA* answers, without a search).
  const auto& components = grid_.layer(agent).components();
  if (!limits.region && components[map.indexOf(start)] != components[map.indexOf(goal)])
    return finish(PathStatus::Unreachable);

  Query q;
  q.clearance = grid_.clearance(agent.capability).values().data();
  q.width = map.width();
  q.bounds = limits.region.value_or(CellRect{0, 0, map.width(), map.height()});
  q.size = agent.size;
  q.goal = map.indexOf(goal);

  beginQuery();
  const std::uint32_t openStamp = generation_ << 1;
  const std::uint32_t closedStamp = openStamp | 1u;
  const std::uint32_t startIndex = map.indexOf(start);
  const auto heuristic = [&](int x, int y) { return octileDistance(goal.x - x, goal.y - y); };
  stamps_[startIndex] = openStamp;
  g_[startIndex] = 0.0;
  parent_[startIndex] = kNone;
  open_.push(OpenList::makeKey(heuristic(start.x, start.y), 0.0), startIndex);
  ++result.metrics.generated;

  PathStatus status = PathStatus::Unreachable;
  while (!open_.empty()) {
    const std::uint32_t current = open_.pop();
    if (stamps_[current] == closedStamp) continue;  // a dearer duplicate
    stamps_[current] = closedStamp;
    ++result.metrics.expanded;
    if (current == q.goal) {
      result.cost = g_[current];
      status = PathStatus::Found;
      break;
    }
    if (result.metrics.expanded >= limits.maxExpanded) {
      status = PathStatus::BudgetExhausted;
      break;
    }
    const Cell here = map.cellAt(current);
    const double g = g_[current];
    // The directions worth jumping in: all from the start; else the way the parent came, the
    // cardinal parts of a diagonal, and the sides of a straight move (pruned by the jumps).
    int dirs[kDirectionCount][2];
    int count = 0;
    const auto add = [&](int dx, int dy) {
      dirs[count][0] = dx;
      dirs[count][1] = dy;
      ++count;
    };
    if (parent_[current] == kNone) {
      for (const Direction& dir : kDirections)
        add(dir.dx, dir.dy);
    } else {
      const Cell from = map.cellAt(parent_[current]);
      const int dx = (here.x > from.x) - (here.x < from.x);
      const int dy = (here.y > from.y) - (here.y < from.y);
      if (dx != 0 && dy != 0) {
        add(dx, dy);
        add(dx, 0);
        add(0, dy);
      } else if (dx != 0) {
        add(dx, 0);
        add(dx, -1);
        add(dx, 1);
        add(0, -1);
        add(0, 1);
      } else {
        add(0, dy);
        add(-1, dy);
        add(1, dy);
        add(-1, 0);
        add(1, 0);
      }
    }
    for (int k = 0; k < count; ++k) {
      const std::uint32_t next = jump(q, here.x, here.y, dirs[k][0], dirs[k][1]);
      if (next == kNone) continue;
      const Cell there = map.cellAt(next);
      const double ng = g + octileDistance(there.x - here.x, there.y - here.y);
      const std::uint32_t seen = stamps_[next];
      if (seen == closedStamp || (seen == openStamp && ng >= g_[next])) continue;
      stamps_[next] = openStamp;
      g_[next] = ng;
      parent_[next] = current;
      open_.push(OpenList::makeKey(ng + heuristic(there.x, there.y), ng), next);
      ++result.metrics.generated;
    }
  }
  if (status == PathStatus::Found && path) {
    // Jump points are joined by straight or diagonal runs: fill in their cells.
    for (std::uint32_t at = q.goal; at != startIndex; at = parent_[at]) {
      const Cell to = map.cellAt(at);
      const Cell from = map.cellAt(parent_[at]);
      const int dx = (to.x > from.x) - (to.x < from.x);
      const int dy = (to.y > from.y) - (to.y < from.y);
      for (Cell c = to; c != from; c = {c.x - dx, c.y - dy})
        path->push_back(c);
    }
    path->push_back(start);
    std::reverse(path->begin(), path->end());
  }
  return finish(status);
}

}  // namespace warpath::pathing
