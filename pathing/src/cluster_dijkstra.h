#pragma once
// Dijkstra over one block of cells for one agent kind: the building block of the abstraction
// (one search from a transition reaches every other transition of its cluster) and of HAA*
// insertion (one search from the start reaches every node of its cluster at once, instead of
// one A* per node). Owns its scratch memory, sized by the largest block seen.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/invariant.h"
#include "pathing/moves.h"
#include "pathing/open_list.h"
#include "pathing/terrain_costs.h"

namespace warpath::pathing {

// The index of cell c in the per-cell arrays over block r: row by row, in a frame one cell wide
// around the block, so that every cell of the block has all eight neighbours in the arrays.
// [Limit: c in r]
inline std::size_t regionIndex(CellRect r, Cell c) {
  return static_cast<std::size_t>(c.y - r.y + 1) * static_cast<std::size_t>(r.width + 2) +
         static_cast<std::size_t>(c.x - r.x + 1);
}
// How many entries the arrays over block `r` and its frame hold (regionIndex's range).
inline std::size_t regionCells(CellRect r) {
  return static_cast<std::size_t>(r.width + 2) * static_cast<std::size_t>(r.height + 2);
}

// The moves of one agent kind inside one block of cells, copied once into an array over the
// block and its frame (bit d set when the move in direction d is legal and stays inside the
// block; none from the frame), so that the searches over the block, one per transition, read
// them by index without testing the block's edges on every expansion.
class RegionMoves {
 public:
  // [Limit: region inside the map]
  void load(const GridMap& map, const AgentLayer& layer, CellRect region);

  CellRect region() const { return region_; }
  std::span<const std::uint8_t> masks() const { return masks_; }

 private:
  CellRect region_;
  std::vector<std::uint8_t> masks_;
};

class ClusterDijkstra {
 public:
  // Settles cells of `region` reachable from `source` (inside it) in cost order, and stops
  // early once every cell of `targets` that lies in the region is settled. Moves cost their
  // length, or with `costs` (built for the layer's agent) their travel time.
  // [Limit: region inside the map, source in region]
  void run(const GridMap& map, const AgentLayer& layer, CellRect region, Cell source,
           std::span<const Cell> targets, const CostField* costs = nullptr);
  // The same over moves loaded beforehand, for several searches over one block.
  // [Limit: source in moves.region()]
  void run(const RegionMoves& moves, Cell source, std::span<const Cell> targets,
           const CostField* costs = nullptr);

  bool reached(Cell c) const { return region_.contains(c) && stamp_[local(c)] == settledStamp(); }
  // [Limit: reached(c)]
  double cost(Cell c) const { return g_[local(c)]; }
  // Directions of the moves from the source to `target`, in order. [Limit: reached(target)]
  void appendSteps(Cell target, std::vector<std::uint8_t>* steps) const;
  // The smallest of `values` (one per cell, indexed by regionIndex) along `steps` from the
  // source: on the cells they walk, source included, and for each diagonal on the two cells
  // beside it (no corner cutting). With clearances, the largest agent the path admits. Walks
  // the steps appendSteps gave, not the search tree again: no chain of dependent loads.
  // [Limit: steps from appendSteps]
  int smallestAlong(std::span<const std::uint8_t> steps,
                    std::span<const std::uint8_t> values) const;
  // The whole search tree, per cell of the region's arrays (regionIndex): the cost to each cell
  // (infinity where not settled) and the direction of the move that reached it.
  // [Limit: both spans as long as the region's arrays]
  void copyTree(std::span<float> costs, std::span<std::uint8_t> vias) const;
  std::uint64_t expanded() const { return expanded_; }
  std::uint64_t generated() const { return generated_; }

 private:
  // run() for one model of move costs, so the uniform one's inner loop has no branch on it.
  template <bool kWeighted>
  void search(const RegionMoves& moves, Cell source, std::span<const Cell> targets,
              const CostField* costs);

  std::size_t local(Cell c) const { return regionIndex(region_, c); }
  std::uint32_t settledStamp() const { return generation_ * 4 + 2; }

  RegionMoves ownMoves_;  // for run() on a layer
  CellRect region_;
  std::size_t start_ = 0;             // the source's index
  std::vector<std::uint32_t> stamp_;  // generation*4 + {1 open, 2 settled}, +3 target marker
  std::vector<std::uint32_t> target_;
  std::vector<double> g_;
  std::vector<std::uint8_t> via_;        // direction of the move that reached the cell
  std::vector<std::uint8_t> unsettled_;  // moves to cells not settled yet
  OpenList open_;                        // weighted searches
  TwoCostOpenList twoCost_;              // uniform ones
  std::uint32_t generation_ = 0;
  std::uint64_t expanded_ = 0;
  std::uint64_t generated_ = 0;
};

// The connected parts of one block of cells for one agent kind, moving inside the block only:
// cells of different parts cannot reach each other by a path inside it, so a search inside the
// block need not look for them. Owns its scratch memory.
class RegionComponents {
 public:
  void label(const RegionMoves& moves);
  // 0 where the agent has no move inside the region (cannot stand, or stands walled in);
  // equal non-zero parts <=> joined inside the region.
  // [Limit: c in the labelled region]
  std::uint32_t partOf(Cell c) const { return part_[regionIndex(region_, c)]; }

 private:
  CellRect region_;
  std::vector<std::uint32_t> part_;
  std::vector<std::uint32_t> stack_;
};

}  // namespace warpath::pathing
