#include "pathing/grid_map.h"

#include <algorithm>
#include <array>

#include "limit_messages.h"

namespace warpath::pathing {
namespace {

// The cell count, once the sides are checked: a negative side would wrap to an enormous
// allocation.
std::size_t checkedCellCount(int width, int height) {
  if (width < 0) throw std::invalid_argument(limits::atLeast("width", 0, width));
  if (height < 0) throw std::invalid_argument(limits::atLeast("height", 0, height));
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

}  // namespace

GridMap::GridMap(int width, int height, Terrain fill)
    : width_(width), height_(height), cells_(checkedCellCount(width, height), fill) {}

Capability GridMap::terrainsIn(CellRect area) const {
  area = clip(area);
  Capability in;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x)
      in = in | Capability::of({at({x, y})});
  }
  return in;
}

Capability GridMap::terrainsPresent() const {
  std::array<bool, 256> seen{};
  for (Terrain t : cells_)
    seen[static_cast<std::uint8_t>(t)] = true;
  Capability present;
  for (int t = 0; t < kTraversableTerrainSlots; ++t) {
    if (seen[static_cast<std::size_t>(t)]) {
      present = present | Capability::of({static_cast<Terrain>(t)});
    }
  }
  return present;
}

}  // namespace warpath::pathing
