#include "cluster_dijkstra.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>

namespace warpath::pathing {

namespace {

// Per cell position in a block: the directions that stay inside it. Bit 0: on the west edge,
// 1: east edge, 2: north edge, 3: south edge.
constexpr std::array<std::uint8_t, 16> kInsideMasks = [] {
  std::array<std::uint8_t, 16> masks{};
  for (unsigned edges = 0; edges < 16; ++edges) {
    for (int d = 0; d < kDirectionCount; ++d) {
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      const bool out = ((edges & 1u) && dir.dx < 0) || ((edges & 2u) && dir.dx > 0) ||
                       ((edges & 4u) && dir.dy < 0) || ((edges & 8u) && dir.dy > 0);
      if (!out) masks[edges] = static_cast<std::uint8_t>(masks[edges] | (1u << d));
    }
  }
  return masks;
}();

}  // namespace

void RegionMoves::load(const GridMap& map, const AgentLayer& layer, CellRect region) {
  region_ = region;
  masks_.assign(regionCells(region), 0);
  const std::uint8_t* all = layer.moveMasks().data();
  for (int ly = 0; ly < region.height; ++ly) {
    const std::uint8_t* row = all + map.indexOf({region.x, region.y + ly});
    std::uint8_t* out = masks_.data() + regionIndex(region, {region.x, region.y + ly});
    const unsigned rowEdges = (ly == 0 ? 4u : 0u) | (ly == region.height - 1 ? 8u : 0u);
    for (int lx = 0; lx < region.width; ++lx) {
      const unsigned edges = rowEdges | (lx == 0 ? 1u : 0u) | (lx == region.width - 1 ? 2u : 0u);
      out[lx] = static_cast<std::uint8_t>(row[lx] & kInsideMasks[edges]);
    }
  }
}

void ClusterDijkstra::run(const GridMap& map, const AgentLayer& layer, CellRect region, Cell source,
                          std::span<const Cell> targets, const CostField* costs) {
  ownMoves_.load(map, layer, region);
  run(ownMoves_, source, targets, costs);
}

void ClusterDijkstra::run(const RegionMoves& moves, Cell source, std::span<const Cell> targets,
                          const CostField* costs) {
  if (costs) {
    search<true>(moves, source, targets, costs);
  } else {
    search<false>(moves, source, targets, nullptr);
  }
}

template <bool kWeighted>
void ClusterDijkstra::search(const RegionMoves& moves, Cell source, std::span<const Cell> targets,
                             const CostField* costs) {
  const CellRect region = moves.region();
  region_ = region;
  const std::size_t cells = moves.masks().size();
  if (stamp_.size() < cells) {
    stamp_.assign(cells, 0);
    target_.assign(cells, 0);
    g_.assign(cells, 0.0);
    via_.assign(cells, 0);
    unsettled_.assign(cells, 0);
    generation_ = 0;
  }
  // Stamps of earlier runs may have used a different region shape: a new generation
  // invalidates them all at once. Wrap-around clears everything.
  if (++generation_ >= (1u << 29)) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    std::fill(target_.begin(), target_.end(), 0);
    generation_ = 1;
  }
  const std::uint32_t openStamp = generation_ * 4 + 1;
  const std::uint32_t settled = settledStamp();

  std::size_t targetsLeft = 0;
  for (Cell t : targets) {
    if (!region.contains(t)) continue;
    std::uint32_t& mark = target_[local(t)];
    if (mark != generation_) {
      mark = generation_;
      ++targetsLeft;
    }
  }

  // Uniform moves: the two-cost open list, which pops what OpenList would.
  const auto push = [&](int d, double g, std::size_t cell) {
    const std::uint64_t key = OpenList::makeKey(g, g);
    if constexpr (kWeighted) {
      open_.push(key, static_cast<std::uint32_t>(cell));
    } else {
      twoCost_.push(isDiagonal(d), key, static_cast<std::uint32_t>(cell));
    }
  };
  const auto pop = [&] {
    if constexpr (kWeighted) return open_.empty() ? TwoCostOpenList::kEmpty : open_.pop();
    return twoCost_.pop();
  };
  if constexpr (kWeighted) {
    open_.clear();
  } else {
    twoCost_.clear();
  }
  // Raw pointers: the byte stores to via would otherwise make the compiler reload every
  // vector's data pointer (a char store may alias them).
  const std::uint8_t* const masks = moves.masks().data();
  std::uint32_t* const stamp = stamp_.data();
  const std::uint32_t* const target = target_.data();
  double* const g = g_.data();
  std::uint8_t* const via = via_.data();
  // The moves whose far end is not settled yet: settling a cell clears the move back to it at
  // each of its eight neighbours (no branch; the frame takes the writes beyond the block), so
  // expansions skip settled neighbours unread, instead of mispredicting on them.
  std::copy(masks, masks + cells, unsettled_.begin());
  std::uint8_t* const unsettled = unsettled_.data();
  const std::uint32_t generation = generation_;
  std::uint64_t expanded = 0;
  std::uint64_t generated = 1;  // the source
  const std::size_t start = local(source);
  start_ = start;
  stamp[start] = openStamp;
  g[start] = 0.0;
  push(0, 0.0, start);
  const int width = region.width + 2;                  // of the arrays, frame included
  std::array<std::ptrdiff_t, kDirectionCount> step{};  // local index offset of each direction
  std::array<std::uint8_t, kDirectionCount> back{};    // all but the bit of the opposite move
  for (int d = 0; d < kDirectionCount; ++d) {
    const Direction& dir = kDirections[static_cast<std::size_t>(d)];
    step[static_cast<std::size_t>(d)] = static_cast<std::ptrdiff_t>(dir.dy) * width + dir.dx;
    back[static_cast<std::size_t>(d)] = static_cast<std::uint8_t>(~(1u << oppositeDirection(d)));
  }
  for (std::uint32_t current; (current = pop()) != TwoCostOpenList::kEmpty;) {
    if (stamp[current] == settled) continue;
    stamp[current] = settled;
    ++expanded;
    if (target[current] == generation && --targetsLeft == 0 && !targets.empty()) break;
    for (std::size_t d = 0; d < kDirectionCount; ++d)
      unsettled[static_cast<std::ptrdiff_t>(current) + step[d]] &= back[d];
    const double gHere = g[current];
    Cell here{};
    if constexpr (kWeighted) {
      here = {region.x - 1 + static_cast<int>(current % static_cast<std::uint32_t>(width)),
              region.y - 1 + static_cast<int>(current / static_cast<std::uint32_t>(width))};
    }
    // Directions in increasing order, as the open list's tie-breaking expects.
    for (unsigned mask = unsettled[current]; mask != 0; mask &= mask - 1) {
      const int d = std::countr_zero(mask);
      const auto next = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(current) +
                                                 step[static_cast<std::size_t>(d)]);
      const std::uint32_t stampNext = stamp[next];
      WARPATH_INVARIANT(stampNext != settled, "cluster Dijkstra: moves must be symmetric");
      double ng = gHere;
      if constexpr (kWeighted) {
        ng += costs->moveCost(here, d);
      } else {
        ng += kDirections[static_cast<std::size_t>(d)].cost;
      }
      if (stampNext == openStamp && ng >= g[next]) continue;
      stamp[next] = openStamp;
      g[next] = ng;
      via[next] = static_cast<std::uint8_t>(d);
      push(d, ng, next);
      ++generated;
    }
  }
  expanded_ = expanded;
  generated_ = generated;
}

void ClusterDijkstra::appendSteps(Cell target, std::vector<std::uint8_t>* steps) const {
  const std::size_t first = steps->size();
  const std::ptrdiff_t width = region_.width + 2;
  for (std::size_t index = local(target); index != start_;) {
    const std::uint8_t d = via_[index];
    steps->push_back(d);
    index -= static_cast<std::size_t>(kDirections[d].dy * width + kDirections[d].dx);
  }
  std::reverse(steps->begin() + static_cast<std::ptrdiff_t>(first), steps->end());
}

void ClusterDijkstra::copyTree(std::span<float> costs, std::span<std::uint8_t> vias) const {
  const std::uint32_t settled = settledStamp();
  for (std::size_t i = 0; i < costs.size(); ++i) {
    const bool reached = stamp_[i] == settled;
    costs[i] = reached ? static_cast<float>(g_[i]) : std::numeric_limits<float>::infinity();
    vias[i] = via_[i];
  }
}

int ClusterDijkstra::smallestAlong(std::span<const std::uint8_t> steps,
                                   std::span<const std::uint8_t> values) const {
  const std::ptrdiff_t width = region_.width + 2;
  std::size_t index = start_;
  int smallest = values[index];
  for (const std::uint8_t d : steps) {
    const Direction& dir = kDirections[d];
    if (isDiagonal(d)) {
      smallest = std::min({smallest, int{values[index + static_cast<std::size_t>(dir.dx)]},
                           int{values[index + static_cast<std::size_t>(dir.dy * width)]}});
    }
    index += static_cast<std::size_t>(dir.dy * width + dir.dx);
    smallest = std::min(smallest, int{values[index]});
  }
  return smallest;
}

void RegionComponents::label(const RegionMoves& moves) {
  region_ = moves.region();
  const std::span<const std::uint8_t> masks = moves.masks();
  const std::size_t cells = masks.size();
  part_.assign(cells, 0);
  const int width = region_.width + 2;  // of the arrays, frame included
  std::uint32_t parts = 0;
  // Cardinal moves suffice: a diagonal move needs both cells beside it, so its ends are also
  // joined by two cardinal moves, inside the block's rectangle.
  for (std::size_t seed = 0; seed < cells; ++seed) {
    if (part_[seed] != 0 || masks[seed] == 0) continue;
    part_[seed] = ++parts;
    stack_.assign(1, static_cast<std::uint32_t>(seed));
    while (!stack_.empty()) {
      const std::uint32_t current = stack_.back();
      stack_.pop_back();
      for (unsigned m = masks[current] & 0xFu; m != 0; m &= m - 1) {
        const Direction& dir = kDirections[static_cast<std::size_t>(std::countr_zero(m))];
        const auto next =
            static_cast<std::size_t>(static_cast<std::ptrdiff_t>(current) +
                                     static_cast<std::ptrdiff_t>(dir.dy) * width + dir.dx);
        if (part_[next] != 0) continue;
        part_[next] = parts;
        stack_.push_back(static_cast<std::uint32_t>(next));
      }
    }
  }
}

}  // namespace warpath::pathing
