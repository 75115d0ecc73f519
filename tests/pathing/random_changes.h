#pragma once
// Random terrain changes for the repair tests: rectangles (partly off the map at times) set to
// a random terrain, obstacles placed, and obstacles placed earlier cleared.

#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/random.h"

namespace warpath::pathing {

inline constexpr Terrain kTerrains[] = {Terrain::Ground, Terrain::Swamp, Terrain::Trees,
                                        Terrain::Water, Terrain::Blocked};

// A random change: a rectangle up to `maxSide` a side, partly off the map at times, set to a
// random terrain; or an obstacle placed, or one placed earlier cleared.
struct RandomChanges {
  SplitMix64 rng;
  int maxSide;
  std::vector<CellRect> obstacles;

  TerrainChange apply(AnnotatedGrid& grid) {
    const GridMap& map = grid.map();
    const int kind = rng.between(0, 9);
    if (kind == 0 && !obstacles.empty()) {
      const CellRect area = obstacles.back();
      obstacles.pop_back();
      return grid.clearObstacle(area);
    }
    const CellRect area{rng.between(-2, map.width() - 1), rng.between(-2, map.height() - 1),
                        rng.between(1, maxSide), rng.between(1, maxSide)};
    if (kind == 1) {
      obstacles.push_back(area);
      return grid.placeObstacle(area);
    }
    return grid.setTerrain(area, kTerrains[rng.between(0, 4)]);
  }
};

}  // namespace warpath::pathing
