#pragma once
// Who holds which cells at the end of their move. Two layers over the map, one unit (or none)
// per cell each: goal claims (the footprint an order handed a unit, so that the goals of
// different orders do not overlap while an area has room) and parking (the footprint a unit
// stands on after it reached its goal, or holds). The first holder of a cell keeps it until it
// lets go. A digest of every (layer, cell, holder) is kept up to date, order-independent, so
// the state hash covers the board without walking the map every tick.

#include <cstdint>
#include <vector>

#include "engine/handle.h"
#include "pathing/grid_map.h"

namespace warpath::engine {

enum class GoalLayer : std::uint8_t { Claimed, Parked };

class GoalBoard {
 public:
  GoalBoard() = default;
  explicit GoalBoard(const pathing::GridMap& map);

  // Takes every cell of the size×size footprint at `anchor` that is free in `layer`.
  void take(GoalLayer layer, pathing::Cell anchor, int size, UnitId unit);
  // Takes every cell of the footprint, whoever held it (a unit that parks displaces nobody's
  // body, only the record of who is there).
  void overwrite(GoalLayer layer, pathing::Cell anchor, int size, UnitId unit);
  // Lets go of the cells of the footprint that `unit` holds in `layer`.
  void release(GoalLayer layer, pathing::Cell anchor, int size, UnitId unit);

  // Holder of a cell in `layer`; invalid when none. [Limit: the cell is on the map]
  UnitId holder(GoalLayer layer, pathing::Cell cell) const;
  // True when no other unit than `self` (pass an invalid id for "nobody") holds a cell of the
  // footprint in `layer`.
  bool freeFor(GoalLayer layer, pathing::Cell anchor, int size, UnitId self) const;

  // Order-independent digest of every held cell: equal boards have equal digests.
  std::uint64_t digest() const { return digest_; }
  // The same over the blocks of kBlock x kBlock cells that meet `area` (clipped to the map):
  // equal wherever those blocks hold the same, so a search of an area can tell whether
  // anything in it changed since (World's rules, FullGoalAreas).
  std::uint64_t digestAround(pathing::CellRect area) const;
  static constexpr int kBlock = 8;

 private:
  void set(GoalLayer layer, std::size_t cell, std::uint32_t holder);
  std::vector<std::uint32_t>& cells(GoalLayer layer) {
    return layer == GoalLayer::Claimed ? claimed_ : parked_;
  }
  const std::vector<std::uint32_t>& cells(GoalLayer layer) const {
    return layer == GoalLayer::Claimed ? claimed_ : parked_;
  }

  int width_ = 0;
  int height_ = 0;
  // Unit index + 1 of the holder of each cell, 0 where none.
  std::vector<std::uint32_t> claimed_;
  std::vector<std::uint32_t> parked_;
  std::uint64_t digest_ = 0;
  int blockColumns_ = 0;
  std::vector<std::uint64_t> blockDigests_;  // by block, row by row
};

}  // namespace warpath::engine
