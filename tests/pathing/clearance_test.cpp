#include "pathing/clearance.h"

#include <gtest/gtest.h>

#include "pathing/map_generator.h"
#include "support/brute_force.h"

namespace warpath::pathing {
namespace {

const Capability kCapabilities[] = {
    Capability::of({Terrain::Ground}),
    Capability::of({Terrain::Ground, Terrain::Swamp}),
    Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees}),
    Capability::of({Terrain::Water}),
    Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water}),
    Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees, Terrain::Water}),
};

TEST(ClearanceTest, MatchesBruteForceSquaresOnRandomMultiTerrainMaps) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    RandomMapSpec spec;
    spec.width = 20 + static_cast<int>(seed % 3) * 7;
    spec.height = 17 + static_cast<int>(seed % 4) * 5;
    spec.seed = seed;
    spec.blockedPercent = static_cast<int>(seed % 4) * 5;
    spec.maxPatch = static_cast<int>(seed % 5) + 1;
    const GridMap map = generateRandomMap(spec);
    for (Capability capability : kCapabilities) {
      const ClearanceField field = ClearanceField::compute(map, capability);
      for (int y = 0; y < map.height(); ++y) {
        for (int x = 0; x < map.width(); ++x) {
          ASSERT_EQ(field.at({x, y}), testing::bruteForceClearance(map, capability, {x, y}))
              << "seed " << seed << " capability " << capability.toString() << " at " << x << ","
              << y;
        }
      }
    }
  }
}

TEST(ClearanceTest, OpenMapClearanceShrinksTowardTheBottomRight) {
  const GridMap map(5, 3, Terrain::Ground);
  const ClearanceField field = ClearanceField::compute(map, Capability::of({Terrain::Ground}));
  EXPECT_EQ(field.at({0, 0}), 3);
  EXPECT_EQ(field.at({3, 0}), 2);
  EXPECT_EQ(field.at({4, 0}), 1);
  EXPECT_EQ(field.at({2, 2}), 1);
  EXPECT_EQ(field.at({-1, 0}), 0);
  EXPECT_EQ(field.at({5, 0}), 0);
}

TEST(ClearanceTest, ForeignTerrainHasZeroClearance) {
  GridMap map(3, 3, Terrain::Ground);
  map.set({1, 1}, Terrain::Water);
  const ClearanceField ground = ClearanceField::compute(map, Capability::of({Terrain::Ground}));
  EXPECT_EQ(ground.at({1, 1}), 0);
  EXPECT_EQ(ground.at({0, 0}), 1);  // its 2x2 square would include the water
  const ClearanceField water = ClearanceField::compute(map, Capability::of({Terrain::Water}));
  EXPECT_EQ(water.at({1, 1}), 1);
  EXPECT_EQ(water.at({0, 0}), 0);
}

}  // namespace
}  // namespace warpath::pathing
