#pragma once
// Deterministic synthetic maps for tests, benchmarks and samples: terrain patches of random
// size scattered over a ground map, so maps have corridors, chokepoints and open areas
// rather than salt-and-pepper noise. Same spec => same map on every platform.

#include <cstdint>

#include "pathing/grid_map.h"

namespace warpath::pathing {

struct RandomMapSpec {
  int width = 64;   // [Unit: cells] [Limit: >= 1]
  int height = 64;  // [Unit: cells] [Limit: >= 1]
  std::uint64_t seed = 1;
  // Target share of cells per terrain, in percent; ground fills the rest. Patches overlap, so
  // the shares are approximate. [Limit: sum <= 100]
  int blockedPercent = 20;
  int swampPercent = 10;
  int treesPercent = 10;
  int waterPercent = 10;
  int maxPatch = 6;  // [Unit: cells] largest patch side; 1 gives independent cells
};

GridMap generateRandomMap(const RandomMapSpec& spec);

}  // namespace warpath::pathing
