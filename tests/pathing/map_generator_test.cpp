#include "pathing/map_generator.h"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>

#include "pathing/aa_star.h"
#include "pathing/inline_maps.h"
#include "pathing/map_io.h"
#include "support/brute_force.h"
#include "support/expect_rejected.h"

namespace warpath::pathing {
namespace {

const Capability kGroundTrees = Capability::of({Terrain::Ground, Terrain::Trees});

GridMap sampleMap() {
  RandomMapSpec spec;
  spec.width = 61;
  spec.height = 47;
  spec.seed = 9;
  spec.blockedPercent = 25;
  spec.swampPercent = 5;
  spec.treesPercent = 5;
  spec.waterPercent = 5;
  return generateRandomMap(spec);
}

std::size_t countTraversable(const GridMap& map) {
  std::size_t n = 0;
  for (Terrain t : map.cells())
    n += isTraversable(t) ? 1 : 0;
  return n;
}

TEST(SoftObstaclesTest, TurnsExactlyTheShareOfTraversableCells) {
  const GridMap map = sampleMap();
  const std::size_t traversable = countTraversable(map);
  for (int percent : {0, 10, 25, 50}) {
    const GridMap derived = withSoftObstacles(map, percent, Terrain::Trees, 77);
    std::size_t changed = 0;
    for (std::uint32_t i = 0; i < map.cellCount(); ++i) {
      const Cell c = map.cellAt(i);
      if (map.at(c) == derived.at(c)) continue;
      ++changed;
      // Only traversable cells that were not trees change, and only into trees.
      EXPECT_TRUE(isTraversable(map.at(c)));
      EXPECT_NE(map.at(c), Terrain::Trees);
      EXPECT_EQ(derived.at(c), Terrain::Trees);
    }
    EXPECT_EQ(changed, (traversable * static_cast<std::size_t>(percent) + 50) / 100) << percent;
  }
  EXPECT_EQ(withSoftObstacles(map, 0, Terrain::Trees, 77), map);
}

TEST(SoftObstaclesTest, CapsAtTheCellsThatCanChange) {
  const GridMap map = sampleMap();
  const GridMap all = withSoftObstacles(map, 100, Terrain::Swamp, 3);
  for (std::uint32_t i = 0; i < map.cellCount(); ++i) {
    const Cell c = map.cellAt(i);
    EXPECT_EQ(all.at(c), isTraversable(map.at(c)) ? Terrain::Swamp : Terrain::Blocked);
  }
}

TEST(SoftObstaclesTest, DeterministicNestedAndInPatches) {
  const GridMap map = sampleMap();
  const GridMap a = withSoftObstacles(map, 20, Terrain::Trees, 5);
  EXPECT_EQ(a, withSoftObstacles(map, 20, Terrain::Trees, 5));
  EXPECT_NE(a, withSoftObstacles(map, 20, Terrain::Trees, 6));
  // With one seed, a larger share paints a superset of a smaller one.
  const GridMap b = withSoftObstacles(map, 40, Terrain::Trees, 5);
  std::size_t painted = 0, withPaintedNeighbour = 0;
  for (std::uint32_t i = 0; i < map.cellCount(); ++i) {
    const Cell c = map.cellAt(i);
    if (a.at(c) == Terrain::Trees) {
      EXPECT_EQ(b.at(c), Terrain::Trees);
    }
    if (map.at(c) == a.at(c)) continue;
    ++painted;
    bool neighbour = false;
    for (Cell n : {Cell{c.x + 1, c.y}, Cell{c.x - 1, c.y}, Cell{c.x, c.y + 1}, Cell{c.x, c.y - 1}})
      neighbour = neighbour || (map.contains(n) && map.at(n) != a.at(n));
    withPaintedNeighbour += neighbour ? 1 : 0;
  }
  // Independent cells at 20% would have a painted neighbour ~60% of the time; patches, ~90%.
  EXPECT_GT(static_cast<double>(withPaintedNeighbour), 0.8 * static_cast<double>(painted));
}

TEST(QuerySamplerTest, AnyPairsStandAndReachablePairsConnect) {
  const AnnotatedGrid grid(sampleMap());
  AnnotatedAStar search(grid);
  SplitMix64 rng(4);
  int unreachable = 0;
  for (const Agent agent : {Agent{1, kGround}, Agent{2, kGroundTrees}}) {
    const QuerySampler sampler(grid, agent);
    ASSERT_TRUE(sampler.canStandAnywhere());
    ASSERT_TRUE(sampler.hasReachablePair());
    for (int i = 0; i < 200; ++i) {
      const Query any = sampler.anyPair(rng);
      EXPECT_TRUE(testing::bruteForceStands(grid.map(), agent.size, agent.capability, any.start));
      EXPECT_TRUE(testing::bruteForceStands(grid.map(), agent.size, agent.capability, any.goal));
      unreachable +=
          search.findPath(agent, any.start, any.goal, nullptr).status == PathStatus::Unreachable;
      const Query reachable = sampler.reachablePair(rng);
      EXPECT_FALSE(reachable.start == reachable.goal);
      EXPECT_TRUE(search.findPath(agent, reachable.start, reachable.goal, nullptr).found());
    }
  }
  EXPECT_GT(unreachable, 0);  // the map has several components, so any pairs cross them

  SplitMix64 again(4);
  const QuerySampler sampler(grid, {1, kGround});
  const Query first = sampler.anyPair(again);
  SplitMix64 replay(4);
  const Query second = sampler.anyPair(replay);
  EXPECT_EQ(first.start, second.start);
  EXPECT_EQ(first.goal, second.goal);
}

TEST(QuerySamplerTest, ReachablePairsAreUniformOverPairs) {
  // Components of 1, 2 and 3 cells have 0, 2 and 6 ordered pairs of distinct cells.
  std::istringstream in(
      "type octile\nheight 1\nwidth 9\nmap\n"
      ".@..@...@\n");
  const AnnotatedGrid grid(parseMap(in, "inline").value());
  const QuerySampler sampler(grid, {1, kGround});
  SplitMix64 rng(1);
  int inPair = 0, inTriple = 0;
  for (int i = 0; i < 4000; ++i) {
    const Query q = sampler.reachablePair(rng);
    ASSERT_FALSE(q.start == q.goal);
    ASSERT_EQ(q.start.x < 4, q.goal.x < 4);  // never across a wall
    (q.start.x < 4 ? inPair : inTriple) += 1;
    EXPECT_NE(q.start.x, 0);  // the lone cell pairs with nothing
  }
  EXPECT_NEAR(inPair, 1000, 150);
  EXPECT_NEAR(inTriple, 3000, 150);

  std::istringstream lone("type octile\nheight 1\nwidth 3\nmap\n.@.\n");
  const AnnotatedGrid islands(parseMap(lone, "inline").value());
  EXPECT_TRUE(QuerySampler(islands, {1, kGround}).canStandAnywhere());
  EXPECT_FALSE(QuerySampler(islands, {1, kGround}).hasReachablePair());
  EXPECT_FALSE(QuerySampler(islands, {1, Capability::of({Terrain::Water})}).canStandAnywhere());
}

using warpath::testing::expectRejected;

TEST(RandomMapSpecTest, EveryLimitIsEnforcedWithItsMessage) {
  EXPECT_EQ(problemWith(RandomMapSpec{}), "");
  const auto check = [](RandomMapSpec spec, const std::string& message) {
    EXPECT_EQ(problemWith(spec), message);
    expectRejected([&] { generateRandomMap(spec); }, message);
  };
  check({.width = 0}, "width must be >= 1 (got 0)");
  check({.height = -4}, "height must be >= 1 (got -4)");
  check({.blockedPercent = -1}, "blockedPercent must be 0..100 (got -1)");
  check({.swampPercent = 101}, "swampPercent must be 0..100 (got 101)");
  check({.treesPercent = 200}, "treesPercent must be 0..100 (got 200)");
  check({.waterPercent = -5}, "waterPercent must be 0..100 (got -5)");
  check({.blockedPercent = 40, .swampPercent = 30, .treesPercent = 20, .waterPercent = 20},
        "blockedPercent + swampPercent + treesPercent + waterPercent must be <= 100 (got 110)");
  check({.maxPatch = 0}, "maxPatch must be >= 1 (got 0)");
  // The limits themselves are usable.
  const GridMap full = generateRandomMap({.width = 1,
                                          .height = 1,
                                          .blockedPercent = 100,
                                          .swampPercent = 0,
                                          .treesPercent = 0,
                                          .waterPercent = 0,
                                          .maxPatch = 1});
  EXPECT_EQ(full.at({0, 0}), Terrain::Blocked);
}

TEST(SoftObstaclesTest, ArgumentsOutsideTheirLimitsAreRejected) {
  const GridMap map = sampleMap();
  expectRejected([&] { withSoftObstacles(map, -1, Terrain::Trees, 1); },
                 "percent must be 0..100 (got -1)");
  expectRejected([&] { withSoftObstacles(map, 101, Terrain::Trees, 1); },
                 "percent must be 0..100 (got 101)");
  expectRejected([&] { withSoftObstacles(map, 10, Terrain::Blocked, 1); },
                 "soft must be a traversable terrain (got blocked)");
}

TEST(GridMapTest, NegativeSidesAreRejected) {
  EXPECT_EQ(GridMap(0, 5).cellCount(), 0u);
  expectRejected([] { GridMap(-1, 5); }, "width must be >= 0 (got -1)");
  expectRejected([] { GridMap(5, -2); }, "height must be >= 0 (got -2)");
}

TEST(QuerySamplerTest, DrawingWithoutCandidatesIsRejected) {
  const AnnotatedGrid walls(GridMap(8, 8, Terrain::Blocked));
  const QuerySampler nowhere(walls, {1, kGround});
  SplitMix64 rng(1);
  expectRejected([&] { nowhere.anyPair(rng); }, "anyPair: the agent can stand nowhere on the map");
  expectRejected([&] { nowhere.reachablePair(rng); },
                 "reachablePair: no two distinct cells are mutually reachable");
  GridMap single(8, 8, Terrain::Blocked);
  single.set({3, 3}, Terrain::Ground);
  const AnnotatedGrid one(single);
  const QuerySampler lonely(one, {1, kGround});
  EXPECT_EQ(lonely.anyPair(rng).start, (Cell{3, 3}));
  expectRejected([&] { lonely.reachablePair(rng); },
                 "reachablePair: no two distinct cells are mutually reachable");
}

}  // namespace
}  // namespace warpath::pathing
