#pragma once
// Terrain costs (issue 13): cost = time. What a cell of each terrain costs an agent is the
// time it takes to cross it, 1 / its speed there [Unit: s per cell]; the uniform model (every
// passable terrain costs 1 [Unit: cells]) is what MovingAI's published optimal lengths assume.
//   - A size-s agent anchored at a cell pays the slowest terrain under its s×s footprint there
//     (the simulation moves it at that speed, so a plan's cost is its predicted travel time).
//   - A cardinal move costs the mean of its two anchors' costs; a diagonal move √2 times the
//     mean of the four anchors of its 2×2 square (all four passable, as the move rules ask).

#include <array>
#include <cstdint>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/moves.h"

namespace warpath::pathing {

struct TerrainCosts {
  // [Unit: s per cell, or cells in the uniform model] per traversable terrain slot; <= 0 or
  // not finite: the agent does not enter that terrain.
  std::array<double, kTraversableTerrainSlots> perCell{};

  // 1 on each terrain of `capability`, none elsewhere.
  static TerrainCosts uniform(Capability capability);
  // The terrains with a cost: the capability of an agent that moves by these costs.
  Capability capability() const;
  bool operator==(const TerrainCosts&) const = default;
};

// The costs one agent kind pays on one map: per anchor, the slowest terrain under its
// footprint (+inf where it cannot stand, or a terrain under it has no cost).
class CostField {
 public:
  CostField(const AnnotatedGrid& grid, Agent agent, const TerrainCosts& costs);

  // After the terrain of `area` changed (AnnotatedGrid::setTerrain): the anchors whose
  // footprint covers a changed cell. The cheapest cost only falls (a lower one stays a lower
  // bound, so the heuristic stays admissible).
  void update(const AnnotatedGrid& grid, CellRect area);

  double at(std::uint32_t anchorIndex) const { return anchor_[anchorIndex]; }
  // The cheapest anchor cost on the map: octile distance times it is an admissible heuristic.
  double cheapest() const { return cheapest_; }
  // The cost of the single move from `from` in direction `d` (legal for the agent). Inline:
  // it is the inner loop of every weighted search.
  double moveCost(Cell from, int d) const {
    const Direction& dir = kDirections[static_cast<std::size_t>(d)];
    const std::size_t w = static_cast<std::size_t>(width_);
    const std::size_t here =
        static_cast<std::size_t>(from.y) * w + static_cast<std::size_t>(from.x);
    const std::size_t across = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(here) + dir.dx);
    const std::size_t below =
        static_cast<std::size_t>(static_cast<std::ptrdiff_t>(here) + dir.dy * width_);
    const std::size_t there =
        static_cast<std::size_t>(static_cast<std::ptrdiff_t>(across) + dir.dy * width_);
    if (!isDiagonal(d)) return 0.5 * (anchor_[here] + anchor_[there]);
    return kSqrt2 * 0.25 * (anchor_[here] + anchor_[there] + anchor_[across] + anchor_[below]);
  }
  // Sum of the move costs along a path of legal single moves.
  double pathCost(std::span<const Cell> path) const;

 private:
  // Fills the anchors of `region` (clipped to the map).
  void fill(const AnnotatedGrid& grid, CellRect region);

  Agent agent_;
  TerrainCosts costs_;
  int width_;
  std::vector<double> anchor_;
  double cheapest_;
};

}  // namespace warpath::pathing
