#include "pathing/aa_star.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>

#include "pathing/moves.h"

namespace warpath::pathing {

std::string_view toString(PathStatus status) {
  switch (status) {
    case PathStatus::Found:
      return "found";
    case PathStatus::Unreachable:
      return "unreachable";
    case PathStatus::InvalidStart:
      return "invalid-start";
    case PathStatus::InvalidGoal:
      return "invalid-goal";
  }
  return "unknown";
}

namespace {

double elapsedMicroseconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - since)
      .count();
}

}  // namespace

AnnotatedAStar::AnnotatedAStar(const AnnotatedGrid& grid) : grid_(grid) {}

void AnnotatedAStar::beginQuery() {
  if (stamps_.size() != grid_.map().cellCount()) {
    stamps_.assign(grid_.map().cellCount(), 0);
    g_.assign(grid_.map().cellCount(), 0.0);
    generation_ = 0;
  }
  if (++generation_ == (1u << (32 - kGenerationShift))) {  // wrapped: forget every stamp
    std::fill(stamps_.begin(), stamps_.end(), 0);
    generation_ = 1;
  }
  open_.clear();
}

PathResult AnnotatedAStar::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path) {
  const auto began = std::chrono::steady_clock::now();
  PathResult result;
  if (path) path->clear();
  const auto finish = [&](PathStatus status) {
    result.status = status;
    result.metrics.microseconds = elapsedMicroseconds(began);
    return result;
  };

  const GridMap& map = grid_.map();
  if (!grid_.canStand(agent, start)) return finish(PathStatus::InvalidStart);
  if (!grid_.canStand(agent, goal)) return finish(PathStatus::InvalidGoal);
  const AgentLayer& layer = grid_.layer(agent);
  const std::uint32_t startIndex = map.indexOf(start);
  const std::uint32_t goalIndex = map.indexOf(goal);
  if (layer.components()[startIndex] != layer.components()[goalIndex]) {
    return finish(PathStatus::Unreachable);
  }

  beginQuery();
  const std::uint8_t* masks = layer.moveMasks().data();
  const std::uint32_t width = static_cast<std::uint32_t>(map.width());
  const double inverseWidth = 1.0 / static_cast<double>(width);
  std::array<std::int64_t, kDirectionCount> offset{};
  for (std::size_t d = 0; d < kDirectionCount; ++d) {
    offset[d] = static_cast<std::int64_t>(kDirections[d].dy) * width + kDirections[d].dx;
  }
  const auto heuristic = [&](int x, int y) { return octileDistance(goal.x - x, goal.y - y); };

  const std::uint32_t openStamp = generation_ << kGenerationShift;
  const std::uint32_t closedStamp = openStamp | kClosedBit;
  stamps_[startIndex] = openStamp;
  g_[startIndex] = 0.0;
  open_.push(OpenList::makeKey(heuristic(start.x, start.y), 0.0), startIndex);
  ++result.metrics.generated;

  bool reached = false;
  while (!open_.empty()) {
    const std::uint32_t current = open_.pop();
    std::uint32_t& stamp = stamps_[current];
    // A cell can be queued more than once; its cheapest entry pops first (same h).
    if ((stamp & ~7u) == closedStamp) continue;
    stamp |= kClosedBit;
    ++result.metrics.expanded;
    if (current == goalIndex) {
      reached = true;
      break;
    }
    const double currentG = g_[current];
    // Row by multiplication instead of an integer division (a measurable share of the
    // expansion cost); the estimate is exact or off by one, and corrected.
    int y = static_cast<int>(static_cast<double>(current) * inverseWidth);
    int x = static_cast<int>(current) - y * static_cast<int>(width);
    if (x < 0) {
      --y;
      x += static_cast<int>(width);
    } else if (x >= static_cast<int>(width)) {
      ++y;
      x -= static_cast<int>(width);
    }
    for (unsigned mask = masks[current]; mask != 0; mask &= mask - 1) {
      const int d = std::countr_zero(mask);
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      const std::uint32_t next =
          static_cast<std::uint32_t>(current + offset[static_cast<std::size_t>(d)]);
      const double g = currentG + dir.cost;
      const std::uint32_t seen = stamps_[next] & ~7u;
      if (seen == closedStamp || (seen == openStamp && g >= g_[next])) continue;
      stamps_[next] = openStamp | static_cast<std::uint32_t>(d);
      g_[next] = g;
      open_.push(OpenList::makeKey(g + heuristic(x + dir.dx, y + dir.dy), g), next);
      ++result.metrics.generated;
    }
  }
  // Same component guarantees a path; this guards the invariant rather than assuming it.
  if (!reached) return finish(PathStatus::Unreachable);

  result.cost = g_[goalIndex];
  if (path) {
    for (std::uint32_t at = goalIndex;;) {
      path->push_back(map.cellAt(at));
      if (at == startIndex) break;
      at = static_cast<std::uint32_t>(at - offset[stamps_[at] & 7u]);
    }
    std::reverse(path->begin(), path->end());
  }
  return finish(PathStatus::Found);
}

}  // namespace warpath::pathing
