#include "pathing/map_generator.h"

#include <algorithm>
#include <array>

#include "pathing/random.h"

namespace warpath::pathing {

GridMap generateRandomMap(const RandomMapSpec& spec) {
  GridMap map(spec.width, spec.height, Terrain::Ground);
  SplitMix64 rng(spec.seed);
  const std::array<std::pair<Terrain, int>, 4> shares{{{Terrain::Blocked, spec.blockedPercent},
                                                       {Terrain::Swamp, spec.swampPercent},
                                                       {Terrain::Trees, spec.treesPercent},
                                                       {Terrain::Water, spec.waterPercent}}};
  const long long cells = static_cast<long long>(spec.width) * spec.height;
  const int maxPatch = std::max(1, spec.maxPatch);
  for (const auto& [terrain, percent] : shares) {
    // Paint patches until roughly `percent` of the map has been painted with this terrain.
    long long budget = cells * std::clamp(percent, 0, 100) / 100;
    while (budget > 0) {
      const int w = rng.between(1, maxPatch);
      const int h = rng.between(1, maxPatch);
      const int x0 = rng.between(0, spec.width - 1);
      const int y0 = rng.between(0, spec.height - 1);
      for (int y = y0; y < std::min(spec.height, y0 + h); ++y) {
        for (int x = x0; x < std::min(spec.width, x0 + w); ++x)
          map.set({x, y}, terrain);
      }
      budget -= static_cast<long long>(w) * h;
    }
  }
  return map;
}

}  // namespace warpath::pathing
