// Level 2 of the cluster hierarchy (AbstractionSpec::levels, issue 15): a query crossing
// level-2 clusters by level-2 edges finds a path exactly when level 1 alone does (and so AA*),
// at the same abstract cost, on built and repaired graphs, sliced or not.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "pathing/cluster_abstraction.h"
#include "pathing/haa_star.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"
#include "random_changes.h"
#include "random_grid.h"
#include "support/completeness.h"
#include "support/sanitized.h"

namespace warpath::pathing {
namespace {

using testing::checkCompleteness;
using testing::completenessAgents;
using testing::completenessCapabilities;
using testing::CompletenessCase;
using testing::CompletenessTally;
using testing::drawCompletenessCases;

AbstractionSpec spec(int clusterSize, AbstractionQuality quality, int levels, int levelTwoSize,
                     bool cachePaths = true) {
  return AbstractionSpec{.clusterSize = clusterSize,
                         .maxAgentSize = 3,
                         .capabilities = completenessCapabilities(),
                         .quality = quality,
                         .cachePaths = cachePaths,
                         .levels = levels,
                         .levelTwoSize = levelTwoSize};
}

// Level 2's answers against level 1's on the same level-1 graph: the same status and, unsmoothed,
// the same cost (level-2 edges are exact over level 1); adds each's abstract expansions. Without
// cached paths an edge is refined by AA* for the agent at hand, which may beat the edge's cost,
// so two abstract paths of one cost may refine to different costs: only statuses compare.
struct LevelTally {
  int compared = 0;
  int mismatches = 0;
  std::uint64_t levelOneExpanded = 0;
  std::uint64_t levelTwoExpanded = 0;
};

void compareLevels(const ClusterAbstraction& one, const ClusterAbstraction& two,
                   const std::vector<CompletenessCase>& cases, const std::string& label,
                   LevelTally& tally) {
  HierarchicalAStar first(one, HaaOptions{.smooth = false});
  HierarchicalAStar second(two, HaaOptions{.smooth = false});
  std::vector<Cell> path;
  for (const CompletenessCase& c : cases) {
    const PathResult a = first.findPath(c.agent, c.query.start, c.query.goal, &path);
    const PathResult b = second.findPath(c.agent, c.query.start, c.query.goal, &path);
    ++tally.compared;
    tally.levelOneExpanded += a.metrics.abstractExpanded;
    tally.levelTwoExpanded += b.metrics.abstractExpanded;
    const bool exact = one.spec().cachePaths;
    if (a.status != b.status || (exact && a.found() && std::abs(a.cost - b.cost) > 1e-6)) {
      ++tally.mismatches;
      ADD_FAILURE() << label << ": " << testing::describeQuery(c.agent, c.query.start, c.query.goal)
                    << ": level 1 " << toString(a.status) << " " << a.cost << ", level 2 "
                    << toString(b.status) << " " << b.cost;
    }
  }
}

std::string label(std::uint64_t seed, const AbstractionSpec& s) {
  std::ostringstream out;
  out << "map seed " << seed << ", cluster " << s.clusterSize << " level two " << s.levelTwoSize
      << " " << kAbstractionQualityNames.name(s.quality) << (s.cachePaths ? "" : " uncached");
  return out.str();
}

TEST(LevelTwo, FindsWhatLevelOneFindsAtTheSameCostOnRandomMaps) {
  CompletenessTally tally;
  LevelTally levels;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const int width = 70 + 9 * static_cast<int>(seed);
    const int height = 61 + 7 * static_cast<int>(seed);
    const AnnotatedGrid grid(randomTerrainMap(seed * 7, width, height,
                                              1 + static_cast<int>(seed * 3 % 8),
                                              10 + static_cast<int>(seed * 4)));
    const auto cases = drawCompletenessCases(grid, completenessAgents(), seed, 4, 10, 1);
    for (const int clusterSize : {5, 8}) {
      for (const AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
        const int levelTwoSize = clusterSize == 5 ? 3 : 2;
        const bool cachePaths = !(seed == 3 && clusterSize == 8);
        const ClusterAbstraction one =
            ClusterAbstraction::build(grid, spec(clusterSize, quality, 1, 2, cachePaths));
        const AbstractionSpec s = spec(clusterSize, quality, 2, levelTwoSize, cachePaths);
        ASSERT_EQ(problemWith(s), "");
        const ClusterAbstraction two = ClusterAbstraction::build(grid, s);
        EXPECT_GT(two.stats().levelTwoEdges, 0u) << label(seed, s);
        EXPECT_EQ(one.stats().levelTwoEdges, 0u);
        compareLevels(one, two, cases, label(seed, s), levels);
        HierarchicalAStar smoothed(two);
        checkCompleteness(grid, cases, smoothed, label(seed, s), tally);
      }
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_EQ(levels.mismatches, 0);
  EXPECT_GT(tally.found, 3000);
  EXPECT_GT(tally.notFound, 500);
  // Level 2 is in use: crossing level-2 clusters by their edges expands fewer nodes.
  EXPECT_LT(levels.levelTwoExpanded * 10, levels.levelOneExpanded * 8)
      << levels.levelTwoExpanded << " against " << levels.levelOneExpanded;
}

// Seeds 1-3 (seed 1 under the sanitizers, support/sanitized.h).
TEST(LevelTwo, RepairedGraphsStayExactAfterTerrainChanges) {
  const std::uint64_t lastSeed = testing::fullOrSanitized(3, 1);
  CompletenessTally tally;
  LevelTally levels;
  int repairs = 0;
  // A repair's effort counts its level-2 searches too (the path service budgets repairs by it).
  std::uint64_t levelOneEffort = 0;
  std::uint64_t levelTwoEffort = 0;
  for (std::uint64_t seed = 1; seed <= lastSeed; ++seed) {
    for (const AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
      AnnotatedGrid grid(randomTerrainMap(seed * 31, 90, 77, 4, 12));
      ClusterAbstraction one = ClusterAbstraction::build(grid, spec(6, quality, 1, 2));
      ClusterAbstraction two = ClusterAbstraction::build(grid, spec(6, quality, 2, 3));
      HierarchicalAStar haa(two);
      RandomChanges changes{SplitMix64(seed * 977), 12, {}};
      for (int step = 0; step < 10; ++step) {
        const TerrainChange change = changes.apply(grid);
        levelOneEffort += one.repair(change).expanded;
        levelTwoEffort += two.repair(change).expanded;
        repairs += change.changed ? 1 : 0;
        const AnnotatedGrid fresh(grid.map());
        const auto cases = drawCompletenessCases(
            fresh, completenessAgents(), seed * 100 + static_cast<std::uint64_t>(step), 1, 3, 0);
        std::ostringstream what;
        what << "seed " << seed << " " << kAbstractionQualityNames.name(quality) << " step "
             << step;
        compareLevels(one, two, cases, what.str(), levels);
        checkCompleteness(fresh, cases, haa, what.str(), tally);
        // A whole build on the changed map has the same level-2 nodes.
        const ClusterAbstraction built = ClusterAbstraction::build(grid, spec(6, quality, 2, 3));
        EXPECT_EQ(two.stats().levelTwoNodes, built.stats().levelTwoNodes) << what.str();
        // The repaired statistics count the level-2 edges the graph holds.
        std::size_t edges = 0;
        for (std::uint32_t n = 0; n < two.nodeCount(); ++n)
          edges += two.levelTwoEdgesOf(n).size();
        EXPECT_EQ(two.stats().levelTwoEdges, edges) << what.str();
      }
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_EQ(levels.mismatches, 0);
  // 20 steps a seed: most change the map, and a few hundred queries are found.
  EXPECT_GT(repairs * 3, 40 * static_cast<int>(lastSeed));
  EXPECT_GT(levelTwoEffort, levelOneEffort);
  EXPECT_GT(tally.found * 3, 600 * static_cast<int>(lastSeed));
}

// A weighted graph (one agent, moving by terrain costs) gets level 2 the same way: exact over
// its level 1 under the costs.
TEST(LevelTwo, WeightedGraphsGetExactLevelTwoEdges) {
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  costs.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  const Capability infantry = Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees});
  LevelTally levels;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const AnnotatedGrid grid(randomTerrainMap(seed * 17, 96, 84, 4, 12));
    for (const int size : {1, 2}) {
      const Agent agent{size, infantry};
      AbstractionSpec s = weightedAbstractionSpec(agent, costs, 6, AbstractionQuality::High);
      const ClusterAbstraction one = ClusterAbstraction::build(grid, s);
      s.levels = 2;
      s.levelTwoSize = 3;
      const ClusterAbstraction two = ClusterAbstraction::build(grid, s);
      EXPECT_GT(two.stats().levelTwoEdges, 0u);
      const auto cases = drawCompletenessCases(grid, {agent}, seed, 0, 20, 0);
      compareLevels(one, two, cases, "weighted seed " + std::to_string(seed), levels);
    }
  }
  EXPECT_EQ(levels.mismatches, 0);
  EXPECT_GT(levels.compared, 100);
  EXPECT_LT(levels.levelTwoExpanded, levels.levelOneExpanded);
}

TEST(LevelTwo, SlicedReturnsExactlyWhatOneShotReturns) {
  const AnnotatedGrid grid(randomTerrainMap(5, 120, 100, 3, 15));
  const ClusterAbstraction two =
      ClusterAbstraction::build(grid, spec(6, AbstractionQuality::High, 2, 3));
  const auto cases = drawCompletenessCases(grid, completenessAgents(2), 9, 2, 6, 0);
  HierarchicalAStar whole(two);
  HierarchicalAStar sliced(two);
  std::vector<Cell> wholePath;
  std::vector<Cell> slicedPath;
  int found = 0;
  for (const CompletenessCase& c : cases) {
    const PathResult a = whole.findPath(c.agent, c.query.start, c.query.goal, &wholePath);
    PathStatus status = sliced.beginPath(c.agent, c.query.start, c.query.goal);
    while (status == PathStatus::Pending)
      status = sliced.updatePath(7);
    const PathResult b = sliced.finalizePath(&slicedPath);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.cost, b.cost);
    EXPECT_EQ(a.metrics.expanded, b.metrics.expanded);
    EXPECT_EQ(wholePath, slicedPath);
    found += a.found() ? 1 : 0;
  }
  EXPECT_GT(found, 50);
}

// Surcharges price level-1 edges one by one: such queries search level 1 in every level-2
// cluster the surcharge does not declare free (EdgeSurcharge::freeWithin), and answer exactly
// what a graph without level 2 answers; in the free ones they take level-2 edges.
TEST(LevelTwo, SurchargedQueriesSearchLevelOneWhereCharged) {
  class EveryCrossing : public EdgeSurcharge {
   public:
    double on(const ClusterAbstraction&, std::uint32_t, const AbstractEdge& edge,
              double) const override {
      return edge.intra ? 0.0 : 2.5;
    }
  };
  // Charges nothing, and says so of every other level-2 cluster.
  class NothingEvenFree : public EdgeSurcharge {
   public:
    double on(const ClusterAbstraction&, std::uint32_t, const AbstractEdge&,
              double) const override {
      return 0.0;
    }
    bool freeWithin(const ClusterAbstraction&, int levelTwoCluster) const override {
      return levelTwoCluster % 2 == 0;
    }
  };
  const EveryCrossing everyCrossing;
  const NothingEvenFree nothing;
  const AnnotatedGrid grid(randomTerrainMap(8, 100, 90, 2, 10));
  const ClusterAbstraction one =
      ClusterAbstraction::build(grid, spec(6, AbstractionQuality::High, 1, 2));
  const ClusterAbstraction two =
      ClusterAbstraction::build(grid, spec(6, AbstractionQuality::High, 2, 3));
  HierarchicalAStar first(one, HaaOptions{.smooth = false});
  HierarchicalAStar second(two, HaaOptions{.smooth = false});
  std::vector<Cell> a;
  std::vector<Cell> b;
  int found = 0;
  std::uint64_t allLevelOne = 0;
  std::uint64_t mixed = 0;
  for (const CompletenessCase& c : drawCompletenessCases(grid, completenessAgents(1), 4, 0, 8, 0)) {
    PathResult ra = first.findPath(c.agent, c.query.start, c.query.goal, &a, &everyCrossing);
    PathResult rb = second.findPath(c.agent, c.query.start, c.query.goal, &b, &everyCrossing);
    EXPECT_EQ(ra.metrics.abstractExpanded, rb.metrics.abstractExpanded);
    EXPECT_EQ(a, b);
    found += ra.found() ? 1 : 0;
    ra = first.findPath(c.agent, c.query.start, c.query.goal, &a, &nothing);
    rb = second.findPath(c.agent, c.query.start, c.query.goal, &b, &nothing);
    EXPECT_EQ(ra.status, rb.status);
    EXPECT_NEAR(ra.cost, rb.cost, 1e-6);
    allLevelOne += ra.metrics.abstractExpanded;
    mixed += rb.metrics.abstractExpanded;
  }
  EXPECT_GT(found, 20);
  EXPECT_LT(mixed, allLevelOne);
}

TEST(LevelTwo, SpecsAreValidated) {
  AbstractionSpec s = spec(8, AbstractionQuality::High, 3, 4);
  EXPECT_EQ(problemWith(s), "levels must be 1..2 (got 3)");
  s.levels = 0;
  EXPECT_EQ(problemWith(s), "levels must be 1..2 (got 0)");
  s.levels = 2;
  s.levelTwoSize = 1;
  EXPECT_EQ(problemWith(s), "levelTwoSize must be 2..256 (got 1)");
  s.levelTwoSize = 257;
  EXPECT_EQ(problemWith(s), "levelTwoSize must be 2..256 (got 257)");
  s.levelTwoSize = 256;
  EXPECT_EQ(problemWith(s), "");
  // One level ignores the level-2 side.
  s.levels = 1;
  s.levelTwoSize = 0;
  EXPECT_EQ(problemWith(s), "");
}

}  // namespace
}  // namespace warpath::pathing
