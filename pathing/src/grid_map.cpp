#include "pathing/grid_map.h"

#include <array>

namespace warpath::pathing {

GridMap::GridMap(int width, int height, Terrain fill)
    : width_(width),
      height_(height),
      cells_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill) {}

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
