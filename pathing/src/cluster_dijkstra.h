#pragma once
// Dijkstra over one block of cells for one agent kind: the building block of the abstraction
// (one search from a transition reaches every other transition of its cluster) and of HAA*
// insertion (one search from the start reaches every node of its cluster at once, instead of
// one A* per node). Owns its scratch memory, sized by the largest block seen.

#include <cstdint>
#include <span>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/moves.h"
#include "pathing/open_list.h"
#include "pathing/terrain_costs.h"

namespace warpath::pathing {

class ClusterDijkstra {
 public:
  // Settles cells of `region` reachable from `source` (inside it) in cost order, and stops
  // early once every cell of `targets` that lies in the region is settled. Moves cost their
  // length, or with `costs` (built for the layer's agent) their travel time.
  // [Limit: region inside the map, source in region]
  void run(const GridMap& map, const AgentLayer& layer, CellRect region, Cell source,
           std::span<const Cell> targets, const CostField* costs = nullptr);

  bool reached(Cell c) const { return region_.contains(c) && stamp_[local(c)] == settledStamp(); }
  // [Limit: reached(c)]
  double cost(Cell c) const { return g_[local(c)]; }
  // Directions of the moves from the source to `target`, in order. [Limit: reached(target)]
  void appendSteps(Cell target, std::vector<std::uint8_t>* steps) const;
  std::uint64_t expanded() const { return expanded_; }
  std::uint64_t generated() const { return generated_; }

 private:
  // run() for one model of move costs, so the uniform one's inner loop has no branch on it.
  template <class MoveCost>
  void search(const GridMap& map, const AgentLayer& layer, CellRect region, Cell source,
              std::span<const Cell> targets, MoveCost moveCost);

  std::size_t local(Cell c) const {
    return static_cast<std::size_t>(c.y - region_.y) * static_cast<std::size_t>(region_.width) +
           static_cast<std::size_t>(c.x - region_.x);
  }
  std::uint32_t settledStamp() const { return generation_ * 4 + 2; }

  CellRect region_;
  std::vector<std::uint32_t> stamp_;  // generation*4 + {1 open, 2 settled}, +3 target marker
  std::vector<std::uint32_t> target_;
  std::vector<double> g_;
  std::vector<std::uint8_t> via_;  // direction of the move that reached the cell
  OpenList open_;
  std::uint32_t generation_ = 0;
  std::uint64_t expanded_ = 0;
  std::uint64_t generated_ = 0;
};

// The connected parts of one block of cells for one agent kind, moving inside the block only:
// cells of different parts cannot reach each other by a path inside it, so a search inside the
// block need not look for them. Owns its scratch memory.
class RegionComponents {
 public:
  // [Limit: region inside the map]
  void label(const GridMap& map, const AgentLayer& layer, CellRect region);
  // 0 where the agent has no move (cannot stand, or stands walled in); equal non-zero parts
  // <=> joined inside the region.
  // [Limit: c in the labelled region]
  std::uint32_t partOf(Cell c) const {
    return part_[static_cast<std::size_t>(c.y - region_.y) *
                     static_cast<std::size_t>(region_.width) +
                 static_cast<std::size_t>(c.x - region_.x)];
  }

 private:
  CellRect region_;
  std::vector<std::uint32_t> part_;
  std::vector<std::uint32_t> stack_;
};

}  // namespace warpath::pathing
