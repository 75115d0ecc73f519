#include "pathing/jump_point_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "pathing/aa_star.h"
#include "pathing/inline_maps.h"
#include "pathing/planner.h"
#include "pathing/random.h"
#include "random_grid.h"

namespace warpath::pathing {
namespace {

// One query of JPS against AA* (optimal): the same status, the same cost, and a legal path
// from start to goal that costs what JPS says. Returns whether a path was found.
bool expectSameAsAStar(const AnnotatedGrid& grid, JumpPointSearch& jps, Agent agent, Cell start,
                       Cell goal, const SearchLimits& limits = {}) {
  AnnotatedAStar aa(grid);
  std::vector<Cell> optimal;
  std::vector<Cell> path;
  const PathResult expected = aa.findPath(agent, start, goal, &optimal, limits);
  const PathResult result = jps.findPath(agent, start, goal, &path, limits);
  SCOPED_TRACE(::testing::Message()
               << "size " << agent.size << " cap " << agent.capability.toString() << " " << start.x
               << "," << start.y << " -> " << goal.x << "," << goal.y);
  EXPECT_EQ(result.status, expected.status);
  if (!expected.found() || !result.found()) {
    EXPECT_TRUE(path.empty());
    return false;
  }
  EXPECT_NEAR(result.cost, expected.cost, 1e-9);
  EXPECT_EQ(path.front(), start);
  EXPECT_EQ(path.back(), goal);
  EXPECT_EQ(findIllegalStep(grid, agent, path), "");
  EXPECT_NEAR(pathCost(path), result.cost, 1e-9);
  if (limits.region) {
    for (Cell c : path)
      EXPECT_TRUE(limits.region->contains(c));
  }
  return true;
}

// A random start and goal where `agent` can stand. [Limit: the grid has such cells]
std::pair<Cell, Cell> standingEnds(const AnnotatedGrid& grid, Agent agent, SplitMix64& rng) {
  const GridMap& map = grid.map();
  for (;;) {
    const Cell start{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
    const Cell goal{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
    if (grid.canStand(agent, start) && grid.canStand(agent, goal)) return {start, goal};
  }
}

// Random queries inside `region` (agents from agentFor(query number)), each checked against
// AA* kept to the same region; returns how many found a path.
template <typename AgentFor>
int regionQueriesAsAStar(const AnnotatedGrid& grid, JumpPointSearch& jps, CellRect region,
                         SplitMix64& rng, int queries, AgentFor agentFor) {
  int found = 0;
  for (int q = 0; q < queries; ++q) {
    const Cell start{rng.between(region.x, region.x + region.width - 1),
                     rng.between(region.y, region.y + region.height - 1)};
    const Cell goal{rng.between(region.x, region.x + region.width - 1),
                    rng.between(region.y, region.y + region.height - 1)};
    const Agent agent = agentFor(q);
    if (!grid.canStand(agent, start) || !grid.canStand(agent, goal)) continue;
    found += expectSameAsAStar(grid, jps, agent, start, goal, limitsOf(UINT64_MAX, region)) ? 1 : 0;
  }
  return found;
}

// Optimal for every size and capability: random multi-terrain maps, sparse and cluttered,
// small patches and large ones.
TEST(JumpPointSearch, FindsPathsAsShortAsAStarForEverySizeAndCapability) {
  int found = 0;
  int unreachable = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    // Sides across 64 and 128: the jumps read 64 cells a word, carrying between words.
    const int side = 40 + static_cast<int>(seed % 3) * 44;
    const AnnotatedGrid grid(randomTerrainMap(seed * 104729, side, side - 6,
                                              1 + static_cast<int>(seed % 5) * 2,
                                              5 + static_cast<int>(seed % 4) * 8));
    const GridMap& map = grid.map();
    JumpPointSearch jps(grid);
    SplitMix64 rng(seed);
    for (Capability capability : {kGround, kInfantry, kAmphibious}) {
      for (int size = 1; size <= 3; ++size) {
        for (int q = 0; q < 25; ++q) {
          const Cell start{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
          const Cell goal{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
          if (!grid.canStand({size, capability}, start) || !grid.canStand({size, capability}, goal))
            continue;
          (expectSameAsAStar(grid, jps, {size, capability}, start, goal) ? found : unreachable) +=
              1;
        }
      }
    }
  }
  // Both outcomes must be exercised, or this proves little.
  EXPECT_GT(found, 400);
  EXPECT_GT(unreachable, 20);
}

// The bit maps follow the grid: after its terrain changes, answers are those of the new map.
TEST(JumpPointSearch, AnswersOnTheChangedMapAfterTerrainChanges) {
  AnnotatedGrid grid(randomTerrainMap(41, 90, 70, 3, 10));
  JumpPointSearch jps(grid);
  const Agent agent{2, kInfantry};
  SplitMix64 rng(9);
  int found = 0;
  for (int round = 0; round < 6; ++round) {
    for (int q = 0; q < 40; ++q) {
      const Cell start{rng.between(0, 89), rng.between(0, 69)};
      const Cell goal{rng.between(0, 89), rng.between(0, 69)};
      if (!grid.canStand(agent, start) || !grid.canStand(agent, goal)) continue;
      // The first query builds the bit maps, the others reuse them until the next change.
      found += expectSameAsAStar(grid, jps, agent, start, goal) ? 1 : 0;
    }
    EXPECT_GT(jps.bitmapBytes(), 0u);
    // A wall across most of the map, then a gap in it.
    const int x = rng.between(10, 79);
    (void)grid.setTerrain({x, 0, 2, 60}, Terrain::Blocked);
    (void)grid.setTerrain({x, rng.between(5, 50), 2, 4}, Terrain::Ground);
  }
  EXPECT_GT(found, 60);
}

// Inside a region the anchor never leaves it, as with AA*.
TEST(JumpPointSearch, KeepsToARegionAsAStarDoes) {
  const AnnotatedGrid grid(randomTerrainMap(77, 48, 42, 3, 15));
  SplitMix64 rng(5);
  const CellRect region{8, 6, 20, 16};
  JumpPointSearch jps(grid);
  EXPECT_GT(regionQueriesAsAStar(grid, jps, region, rng, 300,
                                 [](int q) {
                                   return Agent{1 + q % 2, kInfantry};
                                 }),
            50);
}

// On open ground the jumps skip the symmetric cells: far fewer expansions than AA*.
TEST(JumpPointSearch, ExpandsFewNodesOnOpenGround) {
  GridMap map(64, 64);
  for (int y = 10; y < 50; ++y)
    map.set({30, y}, Terrain::Blocked);  // one wall to walk around
  const AnnotatedGrid grid(map);
  const Agent agent{2, kGround};
  AnnotatedAStar aa(grid);
  JumpPointSearch jps(grid);
  const PathResult a = aa.findPath(agent, {2, 30}, {60, 31}, nullptr);
  const PathResult j = jps.findPath(agent, {2, 30}, {60, 31}, nullptr);
  ASSERT_TRUE(j.found());
  EXPECT_NEAR(j.cost, a.cost, 1e-9);
  EXPECT_LT(j.metrics.expanded * 5, a.metrics.expanded);
}

TEST(JumpPointSearch, StatusForBadEndsBudgetsAndTrivialQueries) {
  GridMap map(12, 8);
  map.set({5, 3}, Terrain::Blocked);
  const AnnotatedGrid grid(map);
  JumpPointSearch jps(grid);
  std::vector<Cell> path;
  const Agent agent{1, kGround};
  EXPECT_EQ(jps.findPath(agent, {5, 3}, {1, 1}, &path).status, PathStatus::InvalidStart);
  EXPECT_EQ(jps.findPath(agent, {1, 1}, {5, 3}, &path).status, PathStatus::InvalidGoal);
  EXPECT_EQ(jps.findPath(agent, {1, 1}, {20, 1}, &path).status, PathStatus::InvalidGoal);
  const PathResult same = jps.findPath(agent, {2, 2}, {2, 2}, &path);
  ASSERT_TRUE(same.found());
  EXPECT_EQ(same.cost, 0.0);
  EXPECT_EQ(path, (std::vector<Cell>{{2, 2}}));
  EXPECT_EQ(jps.findPath(agent, {0, 0}, {11, 7}, &path, limitsOf(0, std::nullopt)).status,
            PathStatus::BudgetExhausted);
  EXPECT_TRUE(path.empty());
}

// Through the planner by name; terrain costs are refused, since the jumps assume uniform ones.
TEST(JumpPointSearch, ThePlannerOffersItByNameOnUniformCostsOnly) {
  EXPECT_EQ(algorithmFromName("jps"), Algorithm::Jps);
  const AnnotatedGrid grid(randomTerrainMap(3, 30, 24, 2, 10));
  Planner planner(grid, Algorithm::Jps, nullptr);
  EXPECT_FALSE(abstractionQualityFor(Algorithm::Jps));
  TerrainCosts costs = TerrainCosts::uniform(kGround);
  const CostField field(grid, {1, kGround}, costs);
  EXPECT_THROW(Planner(grid, Algorithm::Jps, nullptr, {}, {}, &field), std::invalid_argument);
  EXPECT_EQ(algorithmFromName("jps+"), Algorithm::JpsPlus);
  EXPECT_FALSE(abstractionQualityFor(Algorithm::JpsPlus));
  EXPECT_THROW(Planner(grid, Algorithm::JpsPlus, nullptr, {}, {}, &field), std::invalid_argument);
  EXPECT_TRUE(Planner(grid, Algorithm::AStar, nullptr).layerBytes().empty());
}

// JPS+ reads its jumps from precomputed tables and, as JPS2, never pushes a diagonal jump point
// (it reaches that point's successors at once): optimal, as the scanning search is, with fewer
// expansions. Every size and capability, maps sparse and cluttered, sides across one and two
// 64-cell words; goals on a jump's line, on the row or column of a diagonal run and at a
// diagonal's end are all met among random queries (half of the goals are drawn near the start,
// where such cases are common).
TEST(JumpPointSearch, PrecomputedJumpsFindPathsAsShortAsTheScanningSearchWithFewerExpansions) {
  int found = 0;
  int unreachable = 0;
  std::uint64_t scannedExpansions = 0;
  std::uint64_t tabledExpansions = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const int side = 30 + static_cast<int>(seed % 4) * 37;
    AnnotatedGrid grid(randomTerrainMap(seed * 7919, side + 5, side,
                                        1 + static_cast<int>(seed % 4) * 3,
                                        3 + static_cast<int>(seed % 5) * 7));
    const GridMap& map = grid.map();
    JumpPointSearch scanning(grid);
    JumpPointSearch tabled(grid, JumpDistances::Precomputed);
    SplitMix64 rng(seed + 100);
    for (int round = 0; round < 2; ++round) {
      for (Capability capability : {kGround, kInfantry, kAmphibious}) {
        for (int size = 1; size <= 3; ++size) {
          const Agent agent{size, capability};
          for (int q = 0; q < 60; ++q) {
            const Cell start{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
            const Cell goal =
                q % 2 == 0 ? Cell{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)}
                           : Cell{std::clamp(start.x + rng.between(-8, 8), 0, map.width() - 1),
                                  std::clamp(start.y + rng.between(-8, 8), 0, map.height() - 1)};
            std::vector<Cell> expectedPath;
            std::vector<Cell> path;
            const PathResult expected = scanning.findPath(agent, start, goal, &expectedPath);
            const PathResult result = tabled.findPath(agent, start, goal, &path);
            SCOPED_TRACE(::testing::Message()
                         << "seed " << seed << " size " << size << " cap " << capability.toString()
                         << " " << start.x << "," << start.y << " -> " << goal.x << "," << goal.y);
            ASSERT_EQ(result.status, expected.status);
            EXPECT_NEAR(result.cost, expected.cost, 1e-9);
            if (result.found()) {
              EXPECT_EQ(path.front(), start);
              EXPECT_EQ(path.back(), goal);
              EXPECT_EQ(findIllegalStep(grid, agent, path), "");
              EXPECT_NEAR(pathCost(path), result.cost, 1e-9);
            }
            scannedExpansions += expected.metrics.expanded;
            tabledExpansions += result.metrics.expanded;
            if (expected.found()) ++found;
            if (expected.status == PathStatus::Unreachable) ++unreachable;
          }
        }
      }
      // The tables follow the grid: a wall across the map with a gap, then the same queries'
      // kind again on the changed map.
      const int x = rng.between(5, map.width() - 8);
      (void)grid.setTerrain({x, 0, 2, map.height() - 4}, Terrain::Blocked);
      (void)grid.setTerrain({x, rng.between(2, map.height() - 10), 2, 3}, Terrain::Ground);
    }
  }
  EXPECT_GT(found, 2500);
  EXPECT_GT(unreachable, 100);
  EXPECT_LT(tabledExpansions * 10, scannedExpansions * 8);
}

// Both successor rules are optimal, with and without tables; taking only the forced turns of a
// straight jump point (and, with tables, the goal alone once in sight) expands fewer.
TEST(JumpPointSearch, TakingOnlyForcedTurnsFindsPathsAsShortExpandingFewer) {
  std::uint64_t everySide = 0;
  std::uint64_t forcedOnly = 0;
  int found = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const int side = 40 + static_cast<int>(seed % 3) * 30;
    const AnnotatedGrid grid(randomTerrainMap(seed * 104729, side, side + 7,
                                              2 + static_cast<int>(seed % 3) * 4,
                                              5 + static_cast<int>(seed % 4) * 6));
    const GridMap& map = grid.map();
    for (const JumpDistances distances : {JumpDistances::Scanned, JumpDistances::Precomputed}) {
      JumpPointSearch all(grid, distances, kDefaultJumpTableBudget, JumpSuccessors::EverySide);
      JumpPointSearch forced(grid, distances);
      SplitMix64 rng(seed);
      for (int q = 0; q < 150; ++q) {
        const Agent agent{1 + q % 3, q % 2 == 0 ? kInfantry : kAmphibious};
        const Cell start{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
        const Cell goal{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
        if (!grid.canStand(agent, start) || !grid.canStand(agent, goal)) continue;
        const bool reached = expectSameAsAStar(grid, forced, agent, start, goal);
        expectSameAsAStar(grid, all, agent, start, goal);
        if (!reached) continue;
        ++found;
        forcedOnly += forced.findPath(agent, start, goal, nullptr).metrics.expanded;
        everySide += all.findPath(agent, start, goal, nullptr).metrics.expanded;
      }
    }
  }
  EXPECT_GT(found, 800);
  EXPECT_LT(forcedOnly * 10, everySide * 9);
}

// JPS+ pushes the goal alone from a jump point that has it in sight, however many jump points
// lie on the diagonal run toward it: here the start, whose diagonal passes a jump point at
// (12, 12) (a straight jump east from it stops beside a gap), and the goal.
TEST(JumpPointSearch, PrecomputedJumpsGoStraightToAGoalInSight) {
  GridMap map(48, 40);
  map.set({16, 11}, Terrain::Blocked);  // row 12 opens north of (17, 12) after it
  const AnnotatedGrid grid(map);
  const Agent agent{1, kGround};
  JumpPointSearch forced(grid, JumpDistances::Precomputed);
  JumpPointSearch all(grid, JumpDistances::Precomputed, kDefaultJumpTableBudget,
                      JumpSuccessors::EverySide);
  std::vector<Cell> path;
  const PathResult direct = forced.findPath(agent, {10, 10}, {40, 30}, &path);
  ASSERT_TRUE(direct.found());
  EXPECT_NEAR(direct.cost, 20 * std::sqrt(2.0) + 10, 1e-9);
  EXPECT_EQ(findIllegalStep(grid, agent, path), "");
  EXPECT_EQ(direct.metrics.expanded, 2u);
  EXPECT_EQ(direct.metrics.generated, 2u);
  const PathResult searched = all.findPath(agent, {10, 10}, {40, 30}, nullptr);
  EXPECT_NEAR(searched.cost, direct.cost, 1e-9);
  EXPECT_GT(searched.metrics.generated, direct.metrics.generated);
}

// A region query scans (the tables are of the whole map), with the same answers as AA*; the
// memory of each layer is reported: its bit maps and, once a whole-map query built it, its
// table of 8 16-bit distances a cell.
TEST(JumpPointSearch, PrecomputedJumpsKeepToARegionAndReportTheirMemoryPerLayer) {
  const AnnotatedGrid grid(randomTerrainMap(77, 48, 42, 3, 15));
  JumpPointSearch jps(grid, JumpDistances::Precomputed);
  SplitMix64 rng(5);
  const CellRect region{8, 6, 20, 16};
  const Agent agent{1, kInfantry};
  EXPECT_GT(regionQueriesAsAStar(grid, jps, region, rng, 200, [&](int) { return agent; }), 50);
  ASSERT_EQ(jps.layerBytes().size(), 1u);
  const std::size_t bitmaps = jps.layerBytes()[0].bytes;
  EXPECT_EQ(bitmaps, jps.bitmapBytes());
  const auto [start, goal] = standingEnds(grid, agent, rng);
  expectSameAsAStar(grid, jps, agent, start, goal);
  ASSERT_EQ(jps.layerBytes().size(), 1u);
  EXPECT_EQ(jps.layerBytes()[0].agent, agent);
  // 8 16-bit entries a cell, and the layer's framed byte map the table repairs start from.
  EXPECT_EQ(jps.layerBytes()[0].bytes,
            bitmaps + 48u * 42u * 8u * sizeof(std::int16_t) + (48u + 2u) * (42u + 2u));
}

// prepare() builds a layer's table before any query (the benchmarks time queries without it):
// the first query then builds nothing, and the planner offers the same for jps+ and the hybrid
// with the JPS+ attempt.
TEST(JumpPointSearch, PrepareBuildsALayersTableBeforeItsFirstQuery) {
  const AnnotatedGrid grid(randomTerrainMap(19, 40, 36, 3, 10));
  const Agent agent{2, kAmphibious};
  JumpPointSearch jps(grid, JumpDistances::Precomputed);
  jps.prepare(agent);
  EXPECT_EQ(jps.tableCounts().builds, 1u);
  ASSERT_EQ(jps.layerBytes().size(), 1u);
  EXPECT_GT(jps.layerBytes()[0].bytes, jps.bitmapBytes());
  SplitMix64 rng(3);
  const auto [start, goal] = standingEnds(grid, agent, rng);
  expectSameAsAStar(grid, jps, agent, start, goal);
  EXPECT_EQ(jps.tableCounts().builds, 1u);

  Planner planner(grid, Algorithm::JpsPlus, nullptr);
  EXPECT_TRUE(planner.layerBytes().empty());
  planner.prepare(agent);
  ASSERT_EQ(planner.layerBytes().size(), 1u);
  EXPECT_EQ(planner.layerBytes()[0].bytes, jps.layerBytes()[0].bytes);
}

// The tables' budget: a layer whose table would pass it is scanned (its answers are the
// scanning search's, bit for bit); the layer already tabled keeps its table (its answers are
// an unbounded JPS+'s).
TEST(JumpPointSearch, LayersPastTheTableBudgetAreScanned) {
  const AnnotatedGrid grid(randomTerrainMap(31, 60, 50, 3, 12));
  const std::size_t oneTable = 60u * 50u * 8u * sizeof(std::int16_t) + 62u * 52u;
  JumpPointSearch budgeted(grid, JumpDistances::Precomputed, oneTable);
  JumpPointSearch unbounded(grid, JumpDistances::Precomputed);
  JumpPointSearch scanning(grid);
  const Agent first{1, kInfantry};
  const Agent second{2, kInfantry};
  SplitMix64 rng(8);
  std::vector<Cell> a;
  std::vector<Cell> b;
  int found = 0;
  for (int i = 0; i < 80; ++i) {
    const Agent agent = i % 2 == 0 ? first : second;
    const QuerySampler sampler(grid, agent);
    const Query q = sampler.reachablePair(rng);
    const PathResult ra = budgeted.findPath(agent, q.start, q.goal, &a);
    JumpPointSearch& same = agent == first ? unbounded : scanning;
    const PathResult rb = same.findPath(agent, q.start, q.goal, &b);
    EXPECT_EQ(ra.status, rb.status);
    EXPECT_EQ(ra.cost, rb.cost);
    EXPECT_EQ(ra.metrics.expanded, rb.metrics.expanded);
    EXPECT_EQ(a, b);
    found += ra.found() ? 1 : 0;
  }
  EXPECT_GT(found, 60);
  EXPECT_EQ(budgeted.tableCounts().builds, 1u);
  EXPECT_EQ(budgeted.tableCounts().overBudget, 40u);
  // The first layer's table, the second's bit maps only.
  std::size_t bytes = 0;
  for (const LayerBytes& layer : budgeted.layerBytes())
    bytes += layer.bytes;
  EXPECT_EQ(bytes, budgeted.bitmapBytes() + oneTable);
}

// After terrain changes a table is repaired around the cells where the agent's standing changed
// (or built whole when they spread far): entry for entry the table built from scratch on the
// changed map, and the search answers as one with such tables (also after more changes than
// the grid keeps a record of). Open maps (long diagonal runs,
// whose entries change far from a change) and cluttered ones; walls, gaps, single cells, water
// and clearings, near the borders too; sizes 1-3.
TEST(JumpPointSearch, RepairedTablesAreTheTablesBuiltOnTheChangedMap) {
  int found = 0;
  for (const int obstacles : {2, 12}) {
    AnnotatedGrid grid(randomTerrainMap(4242 + obstacles, 100, 76, 3, obstacles));
    const GridMap& map = grid.map();
    JumpPointSearch repaired(grid, JumpDistances::Precomputed);
    SplitMix64 rng(17 + static_cast<std::uint64_t>(obstacles));
    for (int change = 0; change < 30; ++change) {
      JumpPointSearch fresh(grid, JumpDistances::Precomputed);
      for (int size = 1; size <= 3; ++size) {
        for (Capability capability : {kInfantry, kAmphibious}) {
          const Agent agent{size, capability};
          ASSERT_EQ(repaired.jumpDistances(agent), fresh.jumpDistances(agent))
              << "change " << change << " size " << size << " " << capability.toString();
        }
      }
      for (int q = 0; q < 30; ++q) {
        const Agent agent{1 + q % 3, q % 2 == 0 ? kInfantry : kAmphibious};
        const Cell start{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
        const Cell goal{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
        std::vector<Cell> expectedPath;
        std::vector<Cell> path;
        const PathResult expected = fresh.findPath(agent, start, goal, &expectedPath);
        const PathResult result = repaired.findPath(agent, start, goal, &path);
        ASSERT_EQ(result.status, expected.status);
        EXPECT_EQ(result.cost, expected.cost);
        EXPECT_EQ(path, expectedPath);
        found += result.found() ? 1 : 0;
      }
      const int w = rng.between(1, change % 5 == 0 ? 70 : 8);
      const int h = rng.between(1, change % 5 == 0 ? 50 : 8);
      const CellRect area{rng.between(-2, map.width() - 2), rng.between(-2, map.height() - 2), w,
                          h};
      const Terrain terrains[] = {Terrain::Blocked, Terrain::Ground, Terrain::Water,
                                  Terrain::Trees};
      (void)grid.setTerrain(area, terrains[rng.between(0, 3)]);
      // Once, more changes than the grid keeps: the repair must find what changed itself.
      for (int more = change == 15 ? 0 : 1000; more < 80; ++more) {
        (void)grid.setTerrain(
            {rng.between(0, map.width() - 1), rng.between(0, map.height() - 1), 1, 1},
            terrains[more % 4]);
      }
    }
    // Most changes were repaired; the large ones (and each layer's first query) built whole.
    EXPECT_GT(repaired.tableCounts().repairs, 60u);
    EXPECT_GT(repaired.tableCounts().builds, 6u);
  }
  EXPECT_GT(found, 400);
}

}  // namespace
}  // namespace warpath::pathing
