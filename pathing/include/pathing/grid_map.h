#pragma once
// A rectangular grid of terrain bytes. x is the column, y the row, (0, 0) the top-left,
// as in the MovingAI benchmark. The map knows nothing of searches or agents.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "pathing/terrain.h"

namespace warpath::pathing {

struct Cell {
  int x = 0;  // [Unit: cells] column
  int y = 0;  // [Unit: cells] row
  constexpr bool operator==(const Cell&) const = default;
};

// An axis-aligned block of cells.
struct CellRect {
  int x = 0;       // [Unit: cells] left column
  int y = 0;       // [Unit: cells] top row
  int width = 0;   // [Unit: cells]
  int height = 0;  // [Unit: cells]
  constexpr bool contains(Cell c) const {
    return c.x >= x && c.y >= y && c.x < x + width && c.y < y + height;
  }
  // Shares a cell with `other`.
  constexpr bool overlaps(const CellRect& other) const {
    return x < other.x + other.width && other.x < x + width && y < other.y + other.height &&
           other.y < y + height;
  }
  // The smallest block holding both.
  constexpr CellRect joinedWith(const CellRect& other) const {
    const int x0 = std::min(x, other.x);
    const int y0 = std::min(y, other.y);
    return {x0, y0, std::max(x + width, other.x + other.width) - x0,
            std::max(y + height, other.y + other.height) - y0};
  }
  constexpr bool operator==(const CellRect&) const = default;
};

class GridMap {
 public:
  GridMap() = default;
  // [Limit: width, height >= 0, else std::invalid_argument ("width must be >= 0 (got -1)")]
  GridMap(int width, int height, Terrain fill = Terrain::Ground);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t cellCount() const { return cells_.size(); }

  bool contains(Cell c) const { return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_; }
  std::uint32_t indexOf(Cell c) const {
    return static_cast<std::uint32_t>(c.y) * static_cast<std::uint32_t>(width_) +
           static_cast<std::uint32_t>(c.x);
  }
  Cell cellAt(std::uint32_t index) const {
    return {static_cast<int>(index % static_cast<std::uint32_t>(width_)),
            static_cast<int>(index / static_cast<std::uint32_t>(width_))};
  }

  // Out-of-bounds cells read as Blocked.
  Terrain at(Cell c) const { return contains(c) ? cells_[indexOf(c)] : Terrain::Blocked; }
  void set(Cell c, Terrain t) { cells_[indexOf(c)] = t; }

  std::span<const Terrain> cells() const { return cells_; }
  // The traversable terrains that occur on the map.
  Capability terrainsPresent() const;
  // The traversable terrains of the cells of `area` (clipped to the map).
  Capability terrainsIn(CellRect area) const;
  // The part of `area` on the map (width or height 0 when none). Inline: a window search
  // clips a footprint for each move.
  CellRect clip(CellRect area) const {
    const int x0 = std::max(0, area.x);
    const int y0 = std::max(0, area.y);
    const int x1 = std::min(width_, area.x + area.width);
    const int y1 = std::min(height_, area.y + area.height);
    return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
  }

  bool operator==(const GridMap&) const = default;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Terrain> cells_;
};

}  // namespace warpath::pathing
