#pragma once
// True clearance (Harabor & Botea 2008): for each cell, the side of the largest square
// anchored at the cell's upper-left corner whose cells all have terrains in a capability.
// A size-s agent of that capability may stand on a cell exactly when its clearance >= s.

#include <cstdint>
#include <span>
#include <vector>

#include "pathing/grid_map.h"

namespace warpath::pathing {

class ClearanceField {
 public:
  using Value = std::uint16_t;  // saturates at 65535; maps are far smaller

  // O(cells): cv = 1 + min(east, south, south-east) on cells in the capability, else 0,
  // filled from the bottom-right corner; cells beyond the map count as 0.
  static ClearanceField compute(const GridMap& map, Capability capability);

  // After the terrain of the cells in `area` changed: recomputes the cells whose clearance can
  // depend on them (up and left of the area, as far as values change). Returns the bounding
  // box of the cells whose value changed (width 0 when none).
  CellRect update(const GridMap& map, CellRect area);

  Capability capability() const { return capability_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // [Unit: cells] 0 on cells outside the capability and outside the map.
  Value at(Cell c) const {
    if (c.x < 0 || c.y < 0 || c.x >= width_ || c.y >= height_) return 0;
    return values_[static_cast<std::size_t>(c.y) * static_cast<std::size_t>(width_) +
                   static_cast<std::size_t>(c.x)];
  }
  std::span<const Value> values() const { return values_; }

 private:
  Capability capability_;
  int width_ = 0;
  int height_ = 0;
  std::vector<Value> values_;
};

}  // namespace warpath::pathing
