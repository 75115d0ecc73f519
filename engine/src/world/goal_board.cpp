#include "engine/goal_board.h"

#include "pathing/invariant.h"

namespace warpath::engine {

namespace {

// A strong 64-bit mix (SplitMix64's finaliser) of one held cell, so that XOR-ing entries in
// and out gives a digest of the set regardless of the order of changes.
std::uint64_t entryDigest(GoalLayer layer, std::size_t cell, std::uint32_t holder) {
  std::uint64_t z = (static_cast<std::uint64_t>(cell) << 33) ^
                    (static_cast<std::uint64_t>(holder) << 1) ^ static_cast<std::uint64_t>(layer);
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

template <class F>
void forFootprint(pathing::Cell anchor, int size, int width, int height, F f) {
  for (int y = anchor.y; y < anchor.y + size; ++y) {
    for (int x = anchor.x; x < anchor.x + size; ++x) {
      WARPATH_INVARIANT(x >= 0 && y >= 0 && x < width && y < height, "footprint off the map");
      f(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
        static_cast<std::size_t>(x));
    }
  }
}

}  // namespace

GoalBoard::GoalBoard(const pathing::GridMap& map)
    : width_(map.width()),
      height_(map.height()),
      claimed_(map.cellCount(), 0),
      parked_(map.cellCount(), 0) {}

void GoalBoard::set(GoalLayer layer, std::size_t cell, std::uint32_t holder) {
  std::uint32_t& slot = cells(layer)[cell];
  if (slot == holder) return;
  if (slot != 0) digest_ ^= entryDigest(layer, cell, slot);
  if (holder != 0) digest_ ^= entryDigest(layer, cell, holder);
  slot = holder;
}

void GoalBoard::take(GoalLayer layer, pathing::Cell anchor, int size, UnitId unit) {
  forFootprint(anchor, size, width_, height_, [&](std::size_t c) {
    if (cells(layer)[c] == 0) set(layer, c, unit.index + 1);
  });
}

void GoalBoard::overwrite(GoalLayer layer, pathing::Cell anchor, int size, UnitId unit) {
  forFootprint(anchor, size, width_, height_,
               [&](std::size_t c) { set(layer, c, unit.index + 1); });
}

void GoalBoard::release(GoalLayer layer, pathing::Cell anchor, int size, UnitId unit) {
  forFootprint(anchor, size, width_, height_, [&](std::size_t c) {
    if (cells(layer)[c] == unit.index + 1) set(layer, c, 0);
  });
}

UnitId GoalBoard::holder(GoalLayer layer, pathing::Cell cell) const {
  const std::uint32_t h =
      cells(layer)[static_cast<std::size_t>(cell.y) * static_cast<std::size_t>(width_) +
                   static_cast<std::size_t>(cell.x)];
  return h == 0 ? UnitId{} : UnitId{h - 1, 0};
}

bool GoalBoard::freeFor(GoalLayer layer, pathing::Cell anchor, int size, UnitId self) const {
  bool free = true;
  const std::uint32_t own = self.valid() ? self.index + 1 : 0;
  forFootprint(anchor, size, width_, height_, [&](std::size_t c) {
    const std::uint32_t h = cells(layer)[c];
    free = free && (h == 0 || h == own);
  });
  return free;
}

}  // namespace warpath::engine
