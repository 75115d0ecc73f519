#include "engine/goal_board.h"

#include <algorithm>

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
      parked_(map.cellCount(), 0),
      blockColumns_((map.width() + kBlock - 1) / kBlock),
      blockDigests_(static_cast<std::size_t>(blockColumns_) *
                        static_cast<std::size_t>((map.height() + kBlock - 1) / kBlock),
                    0) {}

void GoalBoard::set(GoalLayer layer, std::size_t cell, std::uint32_t holder) {
  std::uint32_t& slot = cells(layer)[cell];
  if (slot == holder) return;
  const auto x = static_cast<int>(cell % static_cast<std::size_t>(width_));
  const auto y = static_cast<int>(cell / static_cast<std::size_t>(width_));
  std::uint64_t& block =
      blockDigests_[static_cast<std::size_t>(y / kBlock) * static_cast<std::size_t>(blockColumns_) +
                    static_cast<std::size_t>(x / kBlock)];
  std::uint64_t change = 0;
  if (slot != 0) change ^= entryDigest(layer, cell, slot);
  if (holder != 0) change ^= entryDigest(layer, cell, holder);
  digest_ ^= change;
  block ^= change;
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

std::uint64_t GoalBoard::digestAround(pathing::CellRect area) const {
  const int x0 = std::max(area.x, 0);
  const int y0 = std::max(area.y, 0);
  const int x1 = std::min(area.x + area.width, width_);
  const int y1 = std::min(area.y + area.height, height_);
  std::uint64_t d = 0;
  if (x1 <= x0 || y1 <= y0) return d;
  for (int by = y0 / kBlock; by <= (y1 - 1) / kBlock; ++by) {
    for (int bx = x0 / kBlock; bx <= (x1 - 1) / kBlock; ++bx)
      d ^= blockDigests_[static_cast<std::size_t>(by) * static_cast<std::size_t>(blockColumns_) +
                         static_cast<std::size_t>(bx)];
  }
  return d;
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
