#pragma once
// Random maps for the pathing tests: ground with `blockedPercent` blocked (map_generator.h's
// default patches of swamp, trees and water included).

#include <cstdint>

#include "pathing/annotated_grid.h"
#include "pathing/map_generator.h"

namespace warpath::pathing {

inline AnnotatedGrid randomGrid(int width, int height, std::uint64_t seed, int blockedPercent) {
  RandomMapSpec spec;
  spec.width = width;
  spec.height = height;
  spec.seed = seed;
  spec.blockedPercent = blockedPercent;
  return AnnotatedGrid(generateRandomMap(spec));
}

}  // namespace warpath::pathing
