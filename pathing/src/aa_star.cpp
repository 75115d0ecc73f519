#include "pathing/aa_star.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "pathing/moves.h"

namespace warpath::pathing {

std::string_view toString(PathStatus status) {
  return kPathStatusNames.name(status);
}

AnnotatedAStar::AnnotatedAStar(const AnnotatedGrid& grid) : grid_(grid) {}

void AnnotatedAStar::resetScratch() {
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

PathResult AnnotatedAStar::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                                    const SearchLimits& limits) {
  return timing_.whole([&] {
    begin(agent, start, goal, nullptr, limits);
    updatePath(kUnboundedExpansions);
    return finalizePath(path);
  });
}

PathResult AnnotatedAStar::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                                    const CostField& costs, const SearchLimits& limits) {
  return timing_.whole([&] {
    begin(agent, start, goal, &costs, limits);
    updatePath(kUnboundedExpansions);
    return finalizePath(path);
  });
}

PathStatus AnnotatedAStar::beginPath(Agent agent, Cell start, Cell goal,
                                     const SearchLimits& limits) {
  return begin(agent, start, goal, nullptr, limits);
}

PathStatus AnnotatedAStar::beginPath(Agent agent, Cell start, Cell goal, const CostField& costs,
                                     const SearchLimits& limits) {
  return begin(agent, start, goal, &costs, limits);
}

PathStatus AnnotatedAStar::begin(Agent agent, Cell start, Cell goal, const CostField* costs,
                                 const SearchLimits& limits) {
  const QueryClock clock = timing_.phaseClock();
  result_ = PathResult{};
  result_.status = PathStatus::Pending;
  start_ = start;
  goal_ = goal;
  costs_ = costs;
  limits_ = limits;
  if (const auto answer = screenQuery(grid_, agent, start, goal, limits)) {
    result_.status = *answer;
  } else {
    layer_ = &grid_.layer(agent);
    agentSize_ = agent.size;
    resetScratch();
    const std::uint32_t startIndex = grid_.map().indexOf(start);
    const double h = octileDistance(goal.x - start.x, goal.y - start.y);
    stamps_[startIndex] = generation_ << kGenerationShift;
    g_[startIndex] = 0.0;
    open_.push(OpenList::makeKey(costs ? costs->cheapest() * h : h, 0.0), startIndex);
    ++result_.metrics.generated;
  }
  result_.metrics.microseconds += clock.elapsedMicroseconds();
  return result_.status;
}

PathStatus AnnotatedAStar::updatePath(std::uint64_t maxExpansions) {
  if (result_.status != PathStatus::Pending || maxExpansions == 0) return result_.status;
  const QueryClock clock = timing_.phaseClock();
  result_.status = limits_.avoid.empty() ? searchAvoiding<false>(maxExpansions)
                                         : searchAvoiding<true>(maxExpansions);
  result_.metrics.microseconds += clock.elapsedMicroseconds();
  return result_.status;
}

template <bool kAvoiding>
PathStatus AnnotatedAStar::searchAvoiding(std::uint64_t maxExpansions) {
  if (costs_) {
    return limits_.region ? search<true, true, kAvoiding>(maxExpansions)
                          : search<false, true, kAvoiding>(maxExpansions);
  }
  return limits_.region ? search<true, false, kAvoiding>(maxExpansions)
                        : search<false, false, kAvoiding>(maxExpansions);
}

PathResult AnnotatedAStar::finalizePath(std::vector<Cell>* path) {
  const QueryClock clock = timing_.phaseClock();
  if (path) path->clear();
  if (result_.status == PathStatus::Found && path) {
    const GridMap& map = grid_.map();
    const std::uint32_t startIndex = map.indexOf(start_);
    const auto width = static_cast<std::int64_t>(map.width());
    for (std::uint32_t at = map.indexOf(goal_);;) {
      path->push_back(map.cellAt(at));
      if (at == startIndex) break;
      const Direction& dir = kDirections[stamps_[at] & 7u];
      at = static_cast<std::uint32_t>(at - (dir.dy * width + dir.dx));
    }
    std::reverse(path->begin(), path->end());
    // The search's cost held the penalties of the footprints avoided: the path's own instead.
    if (!limits_.avoid.empty()) result_.cost = costs_ ? costs_->pathCost(*path) : pathCost(*path);
  }
  result_.metrics.microseconds += clock.elapsedMicroseconds();
  return result_;
}

template <bool kInRegion, bool kWeighted, bool kAvoiding>
PathStatus AnnotatedAStar::search(std::uint64_t maxExpansions) {
  const GridMap& map = grid_.map();
  const Cell goal = goal_;
  const CostField* costs = costs_;
  const SearchLimits& limits = limits_;
  PathResult& result = result_;
  const std::uint32_t goalIndex = map.indexOf(goal);
  const std::uint8_t* masks = layer_->moveMasks().data();
  const std::uint32_t width = static_cast<std::uint32_t>(map.width());
  const double inverseWidth = 1.0 / static_cast<double>(width);
  std::array<std::int64_t, kDirectionCount> offset{};
  for (std::size_t d = 0; d < kDirectionCount; ++d) {
    offset[d] = static_cast<std::int64_t>(kDirections[d].dy) * width + kDirections[d].dx;
  }
  const double scale = kWeighted ? costs->cheapest() : 1.0;
  const auto heuristic = [&](int x, int y) {
    if constexpr (kWeighted) return scale * octileDistance(goal.x - x, goal.y - y);
    return octileDistance(goal.x - x, goal.y - y);
  };
  const CellRect region = limits.region.value_or(CellRect{});
  const int size = agentSize_;
  // Whether the footprint at anchor (x, y) overlaps an area to avoid.
  const auto inTheWay = [&](int x, int y) {
    const CellRect footprint{x, y, size, size};
    return std::any_of(limits.avoid.begin(), limits.avoid.end(),
                       [&](const CellRect& a) { return a.overlaps(footprint); });
  };

  const std::uint32_t openStamp = generation_ << kGenerationShift;
  const std::uint32_t closedStamp = openStamp | kClosedBit;
  const std::uint64_t end = sliceEnd(result.metrics.expanded, maxExpansions);

  while (!open_.empty()) {
    if (result.metrics.expanded >= end) return PathStatus::Pending;
    const std::uint32_t current = open_.pop();
    std::uint32_t& stamp = stamps_[current];
    // A cell can be queued more than once; its cheapest entry pops first (same h).
    if ((stamp & ~7u) == closedStamp) continue;
    stamp |= kClosedBit;
    ++result.metrics.expanded;
    if (current == goalIndex) {
      result.cost = g_[goalIndex];
      return PathStatus::Found;
    }
    if (result.metrics.expanded >= limits.maxExpanded) return PathStatus::BudgetExhausted;
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
      if constexpr (kInRegion) {
        if (!region.contains({x + dir.dx, y + dir.dy})) continue;
      }
      const std::uint32_t next =
          static_cast<std::uint32_t>(current + offset[static_cast<std::size_t>(d)]);
      double step = dir.cost;
      if constexpr (kWeighted) {
        step = costs->moveCost({x, y}, d);
        if (!std::isfinite(step)) continue;
      }
      if constexpr (kAvoiding) {
        if (inTheWay(x + dir.dx, y + dir.dy)) step += limits.avoidPenalty;
      }
      const double g = currentG + step;
      const std::uint32_t seen = stamps_[next] & ~7u;
      if (seen == closedStamp || (seen == openStamp && g >= g_[next])) continue;
      stamps_[next] = openStamp | static_cast<std::uint32_t>(d);
      g_[next] = g;
      open_.push(OpenList::makeKey(g + heuristic(x + dir.dx, y + dir.dy), g), next);
      ++result.metrics.generated;
    }
  }
  // Without a region, the same component guarantees a path (uniform costs); inside one, or
  // where terrains without a cost cut it, it may not exist.
  return PathStatus::Unreachable;
}

}  // namespace warpath::pathing
