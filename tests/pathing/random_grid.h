#pragma once
// Random maps for the pathing tests: ground with `blockedPercent` blocked (map_generator.h's
// default patches of swamp, trees and water included).

#include <cstdint>

#include "pathing/annotated_grid.h"
#include "pathing/map_generator.h"

namespace warpath::pathing {

inline GridMap randomBlockedMap(int width, int height, std::uint64_t seed, int blockedPercent) {
  RandomMapSpec spec;
  spec.width = width;
  spec.height = height;
  spec.seed = seed;
  spec.blockedPercent = blockedPercent;
  return generateRandomMap(spec);
}

inline AnnotatedGrid randomGrid(int width, int height, std::uint64_t seed, int blockedPercent) {
  return AnnotatedGrid(randomBlockedMap(width, height, seed, blockedPercent));
}

// A map of patches up to `maxPatch` cells of every terrain: 20 % swamp, 12 % trees, 12 % water,
// `blockedPercent` blocked, the rest ground.
inline GridMap randomTerrainMap(std::uint64_t seed, int width, int height, int maxPatch,
                                int blockedPercent) {
  RandomMapSpec spec;
  spec.width = width;
  spec.height = height;
  spec.seed = seed;
  spec.blockedPercent = blockedPercent;
  spec.swampPercent = 20;
  spec.treesPercent = 12;
  spec.waterPercent = 12;
  spec.maxPatch = maxPatch;
  return generateRandomMap(spec);
}

}  // namespace warpath::pathing
