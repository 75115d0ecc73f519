#include "pathing/aa_star.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pathing/inline_maps.h"
#include "pathing/map_generator.h"
#include "pathing/map_io.h"
#include "pathing/random.h"
#include "support/brute_force.h"

namespace warpath::pathing {
namespace {

// Every reachability verdict and optimal cost equals brute-force Dijkstra's, and every path is
// legal for the agent and costs what the search says.
TEST(AnnotatedAStarTest, AgreesWithBruteForceDijkstraOnRandomMaps) {
  int pathsChecked = 0;
  int unreachableChecked = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    RandomMapSpec spec;
    spec.width = 22 + static_cast<int>(seed % 3) * 3;
    spec.height = 18 + static_cast<int>(seed % 2) * 4;
    spec.seed = seed * 7919;
    spec.blockedPercent = 15;
    spec.swampPercent = 10;
    spec.treesPercent = 10;
    spec.waterPercent = 15;
    spec.maxPatch = 1 + static_cast<int>(seed % 4);
    const AnnotatedGrid grid(generateRandomMap(spec));
    const GridMap& map = grid.map();
    AnnotatedAStar search(grid);
    SplitMix64 rng(seed);
    std::vector<Cell> path;
    for (Capability capability : {kGround, kInfantry, kAmphibious, kWater}) {
      for (int size = 1; size <= 3; ++size) {
        const Agent agent{size, capability};
        for (int q = 0; q < 6; ++q) {
          const Cell start{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
          const std::vector<double> dist =
              testing::bruteForceDistances(map, size, capability, start);
          for (int g = 0; g < 8; ++g) {
            const Cell goal{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
            const PathResult result = search.findPath(agent, start, goal, &path);
            const bool startOk = testing::bruteForceStands(map, size, capability, start);
            const bool goalOk = testing::bruteForceStands(map, size, capability, goal);
            SCOPED_TRACE(::testing::Message()
                         << "seed " << seed << " size " << size << " cap " << capability.toString()
                         << " " << start.x << "," << start.y << " -> " << goal.x << "," << goal.y);
            if (!startOk) {
              EXPECT_EQ(result.status, PathStatus::InvalidStart);
              continue;
            }
            if (!goalOk) {
              EXPECT_EQ(result.status, PathStatus::InvalidGoal);
              continue;
            }
            const double expected = dist[map.indexOf(goal)];
            if (std::isinf(expected)) {
              EXPECT_EQ(result.status, PathStatus::Unreachable);
              EXPECT_TRUE(path.empty());
              ++unreachableChecked;
              continue;
            }
            ASSERT_EQ(result.status, PathStatus::Found);
            EXPECT_NEAR(result.cost, expected, 1e-9);
            ASSERT_FALSE(path.empty());
            EXPECT_EQ(path.front(), start);
            EXPECT_EQ(path.back(), goal);
            EXPECT_EQ(findIllegalStep(grid, agent, path), "");
            EXPECT_NEAR(pathCost(path), result.cost, 1e-9);
            EXPECT_GE(result.metrics.expanded, 1u);
            ++pathsChecked;
          }
        }
      }
    }
  }
  // The random maps must exercise both outcomes, or this test proves little.
  EXPECT_GT(pathsChecked, 300);
  EXPECT_GT(unreachableChecked, 50);
}

TEST(AnnotatedAStarTest, LargeAgentsNeedWideEnoughGaps) {
  // A wall with a 2-cell gap: size 2 passes, size 3 cannot.
  const GridMap map = mapFromRows(
      "type octile\nheight 8\nwidth 8\nmap\n"
      "........\n"
      "........\n"
      "........\n"
      "@@@..@@@\n"
      "........\n"
      "........\n"
      "........\n"
      "........\n");
  const AnnotatedGrid grid(map);
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  EXPECT_EQ(search.findPath({2, kGround}, {0, 0}, {0, 6}, &path).status, PathStatus::Found);
  EXPECT_EQ(findIllegalStep(grid, {2, kGround}, path), "");
  EXPECT_EQ(search.findPath({3, kGround}, {0, 0}, {0, 5}, &path).status, PathStatus::Unreachable);
}

TEST(AnnotatedAStarTest, NoCornerCutting) {
  const GridMap map = mapFromRows(
      "type octile\nheight 2\nwidth 2\nmap\n"
      ".@\n"
      "..\n");
  const AnnotatedGrid grid(map);
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  // (0,1) -> (1,0) is blocked; (0,0) -> (1,1) must go around via (0,1): cost 2, not sqrt 2.
  const PathResult result = search.findPath({1, kGround}, {0, 0}, {1, 1}, &path);
  ASSERT_TRUE(result.found());
  EXPECT_DOUBLE_EQ(result.cost, 2.0);
  EXPECT_EQ(path.size(), 3u);
}

TEST(AnnotatedAStarTest, TerrainCapabilityDecidesTheRoute) {
  // A river: amphibious units swim across, ground units walk around through the ford at the
  // bottom.
  const GridMap map = mapFromRows(
      "type octile\nheight 6\nwidth 7\nmap\n"
      "...W...\n"
      "...W...\n"
      "...W...\n"
      "...W...\n"
      "...W...\n"
      "...S...\n");
  const AnnotatedGrid grid(map);
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  const PathResult swim = search.findPath({1, kAmphibious}, {0, 0}, {6, 0}, &path);
  ASSERT_TRUE(swim.found());
  EXPECT_DOUBLE_EQ(swim.cost, 6.0);
  EXPECT_EQ(search.findPath({1, kGround}, {0, 0}, {6, 0}, &path).status, PathStatus::Unreachable);
  const PathResult walk = search.findPath({1, kInfantry}, {0, 0}, {6, 0}, &path);
  ASSERT_TRUE(walk.found());
  EXPECT_GT(walk.cost, swim.cost);
  EXPECT_EQ(findIllegalStep(grid, {1, kInfantry}, path), "");
}

// A jammed unit's detour: footprints to avoid are gone around where the way around costs less
// than the penalties, and crossed where it does not; the cost reported is the path's own.
TEST(AnnotatedAStarTest, AvoidedFootprintsAreGoneAroundWhenTheDetourIsCheaper) {
  const AnnotatedGrid grid(GridMap(12, 5, Terrain::Ground));  // a road 5 cells wide
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  const Agent tank{2, kGround};
  const PathResult straight = search.findPath(tank, {0, 1}, {10, 1}, &path);
  ASSERT_TRUE(straight.found());
  EXPECT_DOUBLE_EQ(straight.cost, 10.0);
  // A parked unit's 2x2 footprint on the straight line, with room to pass below it.
  const std::vector<CellRect> parked{{5, 1, 2, 2}};
  SearchLimits limits;
  limits.avoid = parked;
  limits.avoidPenalty = 10.0;
  const PathResult around = search.findPath(tank, {0, 1}, {10, 1}, &path, limits);
  ASSERT_TRUE(around.found());
  EXPECT_EQ(findIllegalStep(grid, tank, path), "");
  for (const Cell& c : path) {
    const bool overlaps = c.x < 7 && 5 < c.x + 2 && c.y < 3 && 1 < c.y + 2;
    EXPECT_FALSE(overlaps) << "anchor (" << c.x << "," << c.y << ") overlaps the parked unit";
  }
  EXPECT_GT(around.cost, straight.cost);
  EXPECT_DOUBLE_EQ(around.cost, pathCost(path));
  // The same unit filling the passage from wall to wall cannot be gone around: crossed.
  const std::vector<CellRect> wall{{5, 0, 2, 5}};
  limits.avoid = wall;
  const PathResult through = search.findPath(tank, {0, 1}, {10, 1}, &path, limits);
  ASSERT_TRUE(through.found());
  EXPECT_DOUBLE_EQ(through.cost, 10.0);
  // A detour dearer than the penalty it saves is not taken.
  limits.avoid = parked;
  limits.avoidPenalty = 0.01;
  const PathResult cheap = search.findPath(tank, {0, 1}, {10, 1}, &path, limits);
  ASSERT_TRUE(cheap.found());
  EXPECT_DOUBLE_EQ(cheap.cost, 10.0);
}

TEST(AnnotatedAStarTest, StatusForBadEndsAndTrivialQueries) {
  GridMap map(6, 6, Terrain::Ground);
  map.set({5, 5}, Terrain::Blocked);
  const AnnotatedGrid grid(map);
  AnnotatedAStar search(grid);
  std::vector<Cell> path{{9, 9}};
  EXPECT_EQ(search.findPath({1, kGround}, {-1, 0}, {1, 1}, &path).status, PathStatus::InvalidStart);
  EXPECT_TRUE(path.empty());
  EXPECT_EQ(search.findPath({1, kGround}, {0, 0}, {5, 5}, &path).status, PathStatus::InvalidGoal);
  EXPECT_EQ(search.findPath({1, kGround}, {0, 0}, {6, 0}, &path).status, PathStatus::InvalidGoal);
  // A size-2 agent anchored at (5, 0) would hang off the map.
  EXPECT_EQ(search.findPath({2, kGround}, {5, 0}, {0, 0}, &path).status, PathStatus::InvalidStart);
  EXPECT_EQ(search.findPath({0, kGround}, {0, 0}, {1, 1}, &path).status, PathStatus::InvalidStart);
  const PathResult same = search.findPath({1, kGround}, {2, 2}, {2, 2}, &path);
  ASSERT_TRUE(same.found());
  EXPECT_EQ(same.cost, 0.0);
  EXPECT_EQ(path, (std::vector<Cell>{{2, 2}}));
}

TEST(AnnotatedAStarTest, AZeroBudgetIsExhaustedAtOnce) {
  const AnnotatedGrid grid(GridMap(6, 6, Terrain::Ground));
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  SearchLimits none;
  none.maxExpanded = 0;
  PathResult r = search.findPath({1, kGround}, {0, 0}, {5, 5}, &path, none);
  EXPECT_EQ(r.status, PathStatus::BudgetExhausted);
  EXPECT_EQ(r.metrics.expanded, 0u);
  EXPECT_TRUE(path.empty());
  // The ends are checked first.
  EXPECT_EQ(search.findPath({1, kGround}, {0, 0}, {6, 6}, &path, none).status,
            PathStatus::InvalidGoal);
  SearchLimits one;
  one.maxExpanded = 1;
  r = search.findPath({1, kGround}, {0, 0}, {5, 5}, &path, one);
  EXPECT_EQ(r.status, PathStatus::BudgetExhausted);
  EXPECT_EQ(r.metrics.expanded, 1u);
}

TEST(AnnotatedAStarTest, RepeatedQueriesGiveIdenticalPaths) {
  RandomMapSpec spec;
  spec.width = 96;
  spec.height = 96;
  spec.seed = 42;
  const AnnotatedGrid grid(generateRandomMap(spec));
  AnnotatedAStar first(grid);
  AnnotatedAStar second(grid);
  std::vector<Cell> a, b;
  SplitMix64 rng(5);
  int found = 0;
  for (int i = 0; i < 50; ++i) {
    const Cell s{rng.between(0, 95), rng.between(0, 95)};
    const Cell g{rng.between(0, 95), rng.between(0, 95)};
    const PathResult ra = first.findPath({1, kInfantry}, s, g, &a);
    first.findPath({2, kGround}, g, s, nullptr);  // interleave other work on the same object
    const PathResult rb = second.findPath({1, kInfantry}, s, g, &b);
    EXPECT_EQ(ra.status, rb.status);
    EXPECT_EQ(ra.cost, rb.cost);
    EXPECT_EQ(ra.metrics.expanded, rb.metrics.expanded);
    EXPECT_EQ(a, b);
    found += ra.found();
  }
  EXPECT_GT(found, 10);
}

}  // namespace
}  // namespace warpath::pathing
