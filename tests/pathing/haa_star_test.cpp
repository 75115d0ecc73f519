// The completeness proof of HAA* and the hybrid planner: on random multi-terrain maps, for
// every agent kind of the catalogue and the MovingAI classes, they find a path exactly when
// AA* does, every path is legal, and none is cheaper than AA*'s optimum.

#include "pathing/haa_star.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/inline_maps.h"
#include "pathing/map_generator.h"
#include "pathing/map_io.h"
#include "pathing/moves.h"
#include "pathing/planner.h"
#include "support/completeness.h"
#include "support/expect_rejected.h"
#include "support/sanitized.h"

namespace warpath::pathing {
namespace {

using testing::checkCompleteness;
using testing::completenessCapabilities;
using testing::CompletenessCase;
using testing::CompletenessTally;
using testing::drawCompletenessCases;

// Map sizes divisible by none of the cluster sizes used, so edge clusters are cut short; the
// patch size and obstacle share range from open fields to dense chokepoints.
struct RandomMapCase {
  std::uint64_t seed;
  int width;
  int height;
  int maxPatch;
  int blockedPercent;
};
constexpr int kRandomMapCount = 16;

// Sizes 48..96 and patch sizes 1..10, with 10-30 % blocked; width and height are nudged off
// multiples of 8 and 10 (16 included).
constexpr RandomMapCase randomMapCase(int i) {
  const auto uneven = [](int n) { return (n % 8 == 0 || n % 10 == 0) ? n + 1 : n; };
  return {static_cast<std::uint64_t>(11 + i), uneven(48 + (i * 13) % 49),
          uneven(48 + (i * 29 + 7) % 49), 1 + (i * 7) % 10, 10 + (i * 11) % 21};
}

GridMap randomMap(const RandomMapCase& c) {
  RandomMapSpec spec;
  spec.width = c.width;
  spec.height = c.height;
  spec.seed = c.seed;
  spec.blockedPercent = c.blockedPercent;
  spec.swampPercent = 12;
  spec.treesPercent = 12;
  spec.waterPercent = 12;
  spec.maxPatch = c.maxPatch;
  return generateRandomMap(spec);
}

AbstractionSpec completenessSpec(int clusterSize, AbstractionQuality quality,
                                 bool cachePaths = true) {
  return AbstractionSpec{.clusterSize = clusterSize,
                         .maxAgentSize = 3,
                         .capabilities = completenessCapabilities(),
                         .quality = quality,
                         .cachePaths = cachePaths};
}

std::string label(const RandomMapCase& m, const AbstractionSpec& spec, const char* what) {
  std::ostringstream out;
  out << "map seed " << m.seed << " (" << m.width << "x" << m.height << "), cluster "
      << spec.clusterSize << (spec.quality == AbstractionQuality::High ? " HQ" : " LQ")
      << (spec.cachePaths ? "" : " uncached") << ", " << what;
  return out.str();
}

// Every random map (every other one under the sanitizers, support/sanitized.h).
TEST(HaaStarTest, CompleteLegalAndNeverBelowTheOptimumOnRandomMaps) {
  const int mapStep = testing::fullOrSanitized(1, 2);
  CompletenessTally tally;
  for (int i = 0; i < kRandomMapCount; i += mapStep) {
    const RandomMapCase m = randomMapCase(i);
    const AnnotatedGrid grid(randomMap(m));
    const std::vector<CompletenessCase> cases =
        drawCompletenessCases(grid, testing::completenessAgents(), m.seed, 8, 16, 2);
    for (int clusterSize : {8, 10, 16}) {
      for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
        // Uncached intra-edges are refined by search instead: check that route once per map.
        for (bool cachePaths : {true, false}) {
          if (!cachePaths && clusterSize != 10) continue;
          const AbstractionSpec spec = completenessSpec(clusterSize, quality, cachePaths);
          ASSERT_EQ(problemWith(spec), "");
          const ClusterAbstraction abstraction = ClusterAbstraction::build(grid, spec);
          HierarchicalAStar smoothed(abstraction, HaaOptions{.smooth = true});
          HierarchicalAStar raw(abstraction, HaaOptions{.smooth = false});
          checkCompleteness(grid, cases, smoothed, label(m, spec, "smoothed"), tally);
          checkCompleteness(grid, cases, raw, label(m, spec, "unsmoothed"), tally);
        }
      }
    }
  }
  EXPECT_EQ(tally.failures, 0);
  // Both outcomes must be exercised, or the test proves little.
  EXPECT_GT(tally.found, 70000 / mapStep);
  EXPECT_GT(tally.notFound, 20000 / mapStep);
}

// With the grid searches by JPS (HaaOptions::gridSearch): the same-cluster attempt, intra-edges
// refined without cached paths, and agents the graph does not serve (size 4 here).
TEST(HaaStarTest, JumpPointGridSearchesKeepItComplete) {
  CompletenessTally tally;
  std::uint64_t gridQueries = 0;
  for (int i = 0; i < kRandomMapCount; i += 3) {
    const RandomMapCase m = randomMapCase(i);
    const AnnotatedGrid grid(randomMap(m));
    const std::vector<CompletenessCase> cases =
        drawCompletenessCases(grid, testing::completenessAgents(4), m.seed + 5, 4, 10, 1);
    for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
      for (bool cachePaths : {true, false}) {
        const AbstractionSpec spec = completenessSpec(10, quality, cachePaths);
        const ClusterAbstraction abstraction = ClusterAbstraction::build(grid, spec);
        HierarchicalAStar haa(abstraction, HaaOptions{.gridSearch = GridSearch::JumpPoints});
        checkCompleteness(grid, cases, haa, label(m, spec, "grid searches by JPS"), tally);
        std::vector<Cell> path;
        for (const CompletenessCase& c : cases) {
          const PathResult r = haa.findPath(c.agent, c.query.start, c.query.goal, &path);
          gridQueries += r.metrics.usedGridSearch ? 1 : 0;
        }
      }
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 5000);
  EXPECT_GT(gridQueries, 100u);
}

// Insertion by tables (HaaOptions::insertion): the same links as the Dijkstra from each end, so
// with cached paths (where a refined path costs what its abstract path does) unsmoothed answers
// cost what the insertion by search finds (the tables keep floats: within 1e-3); smoothed ones
// stay complete, legal and never below the optimum, cached or not. (Uncached, an LQ edge is
// refined by a search that may find a cheaper way than the edge's cost for a larger agent, so
// two abstract paths of equal cost can refine to different costs, and which one is found
// depends on the last bits of the links' costs.)
TEST(HaaStarTest, InsertionTablesKeepItCompleteAndCostWhatTheSearchCosts) {
  CompletenessTally tally;
  std::uint64_t compared = 0;
  for (int i = 0; i < kRandomMapCount; i += 2) {
    const RandomMapCase m = randomMapCase(i);
    const AnnotatedGrid grid(randomMap(m));
    const std::vector<CompletenessCase> cases =
        drawCompletenessCases(grid, testing::completenessAgents(), m.seed + 9, 6, 12, 2);
    for (int clusterSize : {8, 16}) {
      for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
        const AbstractionSpec spec = completenessSpec(clusterSize, quality, clusterSize == 16);
        const ClusterAbstraction abstraction = ClusterAbstraction::build(grid, spec);
        HierarchicalAStar tabled(abstraction, HaaOptions{.insertion = InsertionMode::Tables});
        HierarchicalAStar rawTabled(
            abstraction, HaaOptions{.smooth = false, .insertion = InsertionMode::Tables});
        HierarchicalAStar rawSearched(abstraction, HaaOptions{.smooth = false});
        checkCompleteness(grid, cases, tabled, label(m, spec, "insertion tables"), tally);
        for (const CompletenessCase& c : cases) {
          if (!spec.cachePaths) break;
          const PathResult byTables =
              rawTabled.findPath(c.agent, c.query.start, c.query.goal, nullptr);
          const PathResult bySearch =
              rawSearched.findPath(c.agent, c.query.start, c.query.goal, nullptr);
          ASSERT_EQ(byTables.status, bySearch.status) << label(m, spec, "tables against search");
          if (!bySearch.found()) continue;
          EXPECT_NEAR(byTables.cost, bySearch.cost, 1e-3)
              << label(m, spec, "tables against search");
          ++compared;
        }
        EXPECT_GT(tabled.insertionTableBytes(), 0u);
      }
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 5000);
  EXPECT_GT(tally.notFound, 1000);
  EXPECT_GT(compared, 2000u);
}

// The completeness check itself must catch each kind of wrong answer.
TEST(HaaStarTest, TheCheckCatchesWrongAnswers) {
  const AnnotatedGrid grid(GridMap(6, 4, Terrain::Ground));
  const Agent agent{1, kGround};
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  const PathResult optimum = search.findPath(agent, {0, 0}, {5, 0}, &path);
  ASSERT_TRUE(optimum.found());
  const auto problem = [&](const PathResult& r, const std::vector<Cell>& p) {
    return testing::completenessProblem(grid, agent, {0, 0}, {5, 0}, optimum, r, p);
  };
  EXPECT_EQ(problem(optimum, path), "");
  PathResult wrong = optimum;
  wrong.status = PathStatus::Unreachable;
  EXPECT_NE(problem(wrong, {}), "");
  EXPECT_NE(problem(optimum, {{0, 0}, {1, 0}}), "");  // stops short of the goal
  std::vector<Cell> jump{{0, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}};
  EXPECT_NE(problem(optimum, jump), "");  // not a single move
  wrong = optimum;
  wrong.cost += 1.0;
  EXPECT_NE(problem(wrong, path), "");  // cost does not match the path
  std::vector<Cell> detour{{0, 0}, {1, 1}, {2, 1}, {3, 1}, {4, 1}, {5, 0}};
  wrong.cost = pathCost(detour);
  EXPECT_EQ(problem(wrong, detour), "");  // longer is allowed
  PathResult claimed = optimum;
  claimed.cost = optimum.cost + 0.5;
  EXPECT_NE(testing::completenessProblem(grid, agent, {0, 0}, {5, 0}, claimed, optimum, path),
            "");  // below a (claimed) optimum
  wrong = optimum;
  wrong.metrics.insertionExpanded = wrong.metrics.expanded + 1;
  EXPECT_NE(problem(wrong, path), "");
}

// For every fourth random map from `first`: its completeness cases (seeded by the map's seed
// plus `seedOffset`), the catalogue's HQ graph (clusters of 10) and, for each tau, a hybrid with
// `attempt`; calls f(map case, grid, spec, cases, hybrid, tau).
template <typename F>
void forHybridCases(int first, std::uint64_t seedOffset, std::initializer_list<std::uint64_t> taus,
                    HybridAttempt attempt, F&& f) {
  for (int i = first; i < kRandomMapCount; i += 4) {
    const RandomMapCase m = randomMapCase(i);
    const AnnotatedGrid grid(randomMap(m));
    const std::vector<CompletenessCase> cases =
        drawCompletenessCases(grid, testing::completenessAgents(), m.seed + seedOffset, 3, 6, 1);
    const AbstractionSpec spec = completenessSpec(10, AbstractionQuality::High);
    const ClusterAbstraction abstraction = ClusterAbstraction::build(grid, spec);
    for (const std::uint64_t tau : taus) {
      HybridPlanner hybrid(abstraction, HybridOptions{.tau = tau, .attempt = attempt});
      f(m, grid, spec, cases, hybrid, tau);
    }
  }
}

TEST(HaaStarTest, HybridPlannerIsCompleteAndShortQueriesGetTheOptimum) {
  CompletenessTally tally;
  int shortOptimal = 0;
  forHybridCases(
      0, 100, {16, 4096}, HybridAttempt::AStar,
      [&](const RandomMapCase& m, const AnnotatedGrid& grid, const AbstractionSpec& spec,
          const std::vector<CompletenessCase>& cases, HybridPlanner& hybrid, std::uint64_t tau) {
        checkCompleteness(grid, cases, hybrid, label(m, spec, "hybrid"), tally);
        // A short query whose AA* search fits the budget well is answered by that search.
        std::vector<Cell> path;
        for (const CompletenessCase& c : cases) {
          if (!c.optimum.found() || c.optimum.metrics.expanded * 2 > tau) continue;
          const double air =
              std::hypot(c.query.goal.x - c.query.start.x, c.query.goal.y - c.query.start.y);
          if (air > std::sqrt(static_cast<double>(tau)) / 2.0 - 0.5) continue;
          const PathResult result = hybrid.findPath(c.agent, c.query.start, c.query.goal, &path);
          EXPECT_TRUE(result.metrics.usedGridSearch);
          EXPECT_NEAR(result.cost, c.optimum.cost, 1e-9);
          ++shortOptimal;
        }
      });
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 800);
  EXPECT_GT(tally.notFound, 250);
  EXPECT_GT(shortOptimal, 300);
}

// With the JPS+ attempt every query tries JPS+ first, whatever the distance: complete, and
// optimal whenever JPS+ answered within tau jump points; a tau too small for most sends them to
// HAA* (still complete). Under terrain costs the attempt is AA*'s (weighted_haa_test covers it).
TEST(HaaStarTest, HybridWithAJumpPointAttemptIsCompleteAndItsAttemptsOptimal) {
  CompletenessTally tally;
  int attempted = 0;
  int hierarchical = 0;
  forHybridCases(
      1, 200, {2, 4096}, HybridAttempt::JumpPoints,
      [&](const RandomMapCase& m, const AnnotatedGrid& grid, const AbstractionSpec& spec,
          const std::vector<CompletenessCase>& cases, HybridPlanner& hybrid, std::uint64_t) {
        checkCompleteness(grid, cases, hybrid, label(m, spec, "hybrid jps+"), tally);
        std::vector<Cell> path;
        for (const CompletenessCase& c : cases) {
          if (!c.optimum.found()) continue;
          const PathResult result = hybrid.findPath(c.agent, c.query.start, c.query.goal, &path);
          if (result.metrics.usedGridSearch) {
            EXPECT_NEAR(result.cost, c.optimum.cost, 1e-9);
            ++attempted;
          } else {
            ++hierarchical;
          }
        }
      });
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 800);
  EXPECT_GT(tally.notFound, 250);
  EXPECT_GT(attempted, 400);
  EXPECT_GT(hierarchical, 100);
}

TEST(HaaStarTest, AgentsTheGraphDoesNotServeAreAnsweredByGridSearch) {
  const AnnotatedGrid grid(randomMap(randomMapCase(1)));
  const ClusterAbstraction abstraction = ClusterAbstraction::build(
      grid, AbstractionSpec{.clusterSize = 10, .maxAgentSize = 2, .capabilities = {kGround}});
  EXPECT_TRUE(abstraction.supports({2, kGround}));
  EXPECT_FALSE(abstraction.supports({3, kGround}));    // too large
  EXPECT_FALSE(abstraction.supports({1, kInfantry}));  // capability not built
  HierarchicalAStar search(abstraction);
  const std::vector<Agent> unserved{{3, kGround}, {1, kInfantry}, {2, kInfantry}};
  const std::vector<CompletenessCase> cases = drawCompletenessCases(grid, unserved, 7, 6, 10, 2);
  CompletenessTally tally;
  checkCompleteness(grid, cases, search, "unserved agents", tally);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 30);
  std::vector<Cell> path;
  for (const CompletenessCase& c : cases) {
    if (!c.optimum.found()) continue;
    const PathResult result = search.findPath(c.agent, c.query.start, c.query.goal, &path);
    EXPECT_TRUE(result.metrics.usedGridSearch);
    EXPECT_NEAR(result.cost, c.optimum.cost, 1e-9);  // it is AA*, so optimal
  }
}

TEST(HaaStarTest, LongQueriesOnAnOpenMapUseTheGraph) {
  const AnnotatedGrid grid(GridMap(70, 45, Terrain::Ground));
  for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
    const ClusterAbstraction abstraction = ClusterAbstraction::build(
        grid,
        AbstractionSpec{
            .clusterSize = 8, .maxAgentSize = 3, .capabilities = {kGround}, .quality = quality});
    HierarchicalAStar search(abstraction);
    std::vector<Cell> path;
    const PathResult result = search.findPath({2, kGround}, {1, 2}, {66, 40}, &path);
    ASSERT_TRUE(result.found());
    EXPECT_FALSE(result.metrics.usedGridSearch);
    EXPECT_GT(result.metrics.abstractExpanded, 0u);
    EXPECT_EQ(findIllegalStep(grid, {2, kGround}, path), "");
    // Smoothing straightens an open map's path to the octile optimum or close to it.
    EXPECT_GE(result.cost, octileDistance(65, 38) - 1e-9);
    EXPECT_LE(result.cost, octileDistance(65, 38) * 1.1);
  }
}

TEST(HaaStarTest, InvalidEndsGetTheirStatus) {
  GridMap map(30, 30, Terrain::Ground);
  map.set({5, 5}, Terrain::Blocked);
  map.set({20, 20}, Terrain::Water);
  const AnnotatedGrid grid(map);
  for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
    const ClusterAbstraction abstraction =
        ClusterAbstraction::build(grid, completenessSpec(8, quality));
    HierarchicalAStar haa(abstraction);
    HybridPlanner hybrid(abstraction);
    std::vector<Cell> path;
    const auto checkEnds = [&](auto& planner, Agent agent) {
      const auto status = [&](Cell s, Cell g) {
        return planner.findPath(agent, s, g, &path).status;
      };
      EXPECT_EQ(status({5, 5}, {25, 25}), PathStatus::InvalidStart);
      EXPECT_EQ(status({-1, 3}, {25, 25}), PathStatus::InvalidStart);
      EXPECT_EQ(status({25, 25}, {5, 5}), PathStatus::InvalidGoal);
      EXPECT_EQ(status({25, 25}, {30, 2}), PathStatus::InvalidGoal);
      EXPECT_EQ(status({25, 25}, {20, 20}), PathStatus::InvalidGoal);  // water
      // A size-2 agent anchored in the last column would hang off the map.
      EXPECT_EQ(status({29, 0}, {1, 1}),
                agent.size == 2 ? PathStatus::InvalidStart : PathStatus::Found);
    };
    for (const Agent agent : {Agent{1, kGround}, Agent{2, kGround}, Agent{1, kInfantry}}) {
      checkEnds(haa, agent);
      checkEnds(hybrid, agent);
    }
    EXPECT_EQ(haa.findPath({0, kGround}, {1, 1}, {2, 2}, &path).status, PathStatus::InvalidStart);
  }
}

TEST(HaaStarTest, SameClusterQueries) {
  // Cluster 0 is columns 0-15, rows 0-15. The wall splits it: from (2,2) to (12,2) the route
  // leaves the cluster below the wall's end and comes back.
  std::string rows;
  for (int y = 0; y < 32; ++y) {
    std::string row(32, '.');
    if (y < 18) row[8] = '@';
    rows += row + "\n";
  }
  const AnnotatedGrid grid(mapFromRows("type octile\nheight 32\nwidth 32\nmap\n" + rows));
  AnnotatedAStar optimal(grid);
  for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
    const ClusterAbstraction abstraction = ClusterAbstraction::build(
        grid,
        AbstractionSpec{
            .clusterSize = 16, .maxAgentSize = 2, .capabilities = {kGround}, .quality = quality});
    ASSERT_EQ(abstraction.clusterOf({2, 2}), abstraction.clusterOf({12, 2}));
    HierarchicalAStar search(abstraction);
    std::vector<Cell> path;
    for (const Agent agent : {Agent{1, kGround}, Agent{2, kGround}}) {
      // Open inside the cluster: the in-cluster search is the optimum.
      PathResult result = search.findPath(agent, {10, 1}, {14, 12}, &path);
      ASSERT_TRUE(result.found());
      EXPECT_NEAR(result.cost, octileDistance(4, 11), 1e-9);
      EXPECT_EQ(findIllegalStep(grid, agent, path), "");
      // Split inside the cluster: the path must leave it.
      const PathResult best = optimal.findPath(agent, {2, 2}, {12, 2}, nullptr);
      ASSERT_TRUE(best.found());
      result = search.findPath(agent, {2, 2}, {12, 2}, &path);
      EXPECT_EQ(testing::completenessProblem(grid, agent, {2, 2}, {12, 2}, best, result, path), "");
      const bool leftCluster = std::any_of(path.begin(), path.end(), [&](Cell c) {
        return abstraction.clusterOf(c) != abstraction.clusterOf({2, 2});
      });
      EXPECT_TRUE(leftCluster);
      // Same start and goal.
      result = search.findPath(agent, {3, 3}, {3, 3}, &path);
      ASSERT_TRUE(result.found());
      EXPECT_EQ(result.cost, 0.0);
      EXPECT_EQ(path, (std::vector<Cell>{{3, 3}}));
    }
  }
}

// A wall across the map with two gaps: a surcharge on the edges through the near gap (the
// engine's wait at a crowded bridge) sends the route through the far one; a zero surcharge
// changes nothing.
TEST(HaaStarTest, ASurchargeOnEdgesSendsTheRouteAnotherWay) {
  std::string rows;
  for (int y = 0; y < 48; ++y) {
    std::string row(64, '.');
    if (y >= 22 && y <= 25) {
      for (int x = 0; x < 64; ++x)
        if (!((x >= 10 && x <= 12) || (x >= 50 && x <= 52))) row[static_cast<std::size_t>(x)] = '@';
    }
    rows += row + "\n";
  }
  const AnnotatedGrid grid(mapFromRows("type octile\nheight 48\nwidth 64\nmap\n" + rows));
  const Agent agent{1, kGround};
  const ClusterAbstraction abstraction = ClusterAbstraction::build(
      grid, AbstractionSpec{.clusterSize = 16, .maxAgentSize = 1, .capabilities = {kGround}});
  const auto throughNearGap = [](const std::vector<Cell>& path) {
    return std::any_of(path.begin(), path.end(), [](Cell c) { return c.y == 23 && c.x < 32; });
  };
  struct Flat final : EdgeSurcharge {
    double amount = 0.0;
    bool nearGapOnly = false;
    mutable int calls = 0;
    double on(const ClusterAbstraction& graph, std::uint32_t from, const AbstractEdge& edge,
              double g) const override {
      EXPECT_GE(g, 0.0);
      ++calls;
      std::vector<Cell> cells{graph.nodeCell(from)};
      graph.appendEdgeCells(from, edge, &cells);
      const bool near = std::any_of(cells.begin(), cells.end(),
                                    [](Cell c) { return c.y >= 22 && c.y <= 25 && c.x < 32; });
      return !nearGapOnly || near ? amount : 0.0;
    }
  };
  for (const bool hybrid : {false, true}) {
    Planner planner(grid, hybrid ? Algorithm::Hybrid : Algorithm::HaaHigh, &abstraction);
    std::vector<Cell> plain, zero, detour;
    const PathResult base = planner.findPath(agent, {11, 3}, {11, 44}, &plain);
    ASSERT_TRUE(base.found());
    EXPECT_TRUE(throughNearGap(plain));
    Flat none;
    const PathResult same = planner.findPath(agent, {11, 3}, {11, 44}, &zero, &none);
    EXPECT_GT(none.calls, 0);
    EXPECT_EQ(zero, plain);
    EXPECT_EQ(same.cost, base.cost);
    EXPECT_EQ(same.metrics.expanded, base.metrics.expanded);
    Flat crowded;
    crowded.amount = 500.0;
    crowded.nearGapOnly = true;
    const PathResult around = planner.findPath(agent, {11, 3}, {11, 44}, &detour, &crowded);
    ASSERT_TRUE(around.found());
    EXPECT_FALSE(throughNearGap(detour));
    EXPECT_EQ(findIllegalStep(grid, agent, detour), "");
    // The cost is the path's own, without the surcharge: the detour's length.
    EXPECT_GT(around.cost, base.cost + 40.0);
    EXPECT_LT(around.cost, 500.0);
  }
}

TEST(HaaStarTest, ResultsAndGraphsAreDeterministic) {
  const AnnotatedGrid grid(randomMap(randomMapCase(2)));
  const AbstractionSpec spec = completenessSpec(10, AbstractionQuality::Low);
  const ClusterAbstraction a = ClusterAbstraction::build(grid, spec);
  const ClusterAbstraction b = ClusterAbstraction::build(grid, spec);
  EXPECT_EQ(a.stats().nodes, b.stats().nodes);
  EXPECT_EQ(a.stats().interEdges, b.stats().interEdges);
  EXPECT_EQ(a.stats().intraEdges, b.stats().intraEdges);
  EXPECT_EQ(a.stats().pathBytes, b.stats().pathBytes);
  ASSERT_EQ(a.nodeCount(), b.nodeCount());
  for (std::uint32_t n = 0; n < a.nodeCount(); ++n)
    EXPECT_EQ(a.nodeCell(n), b.nodeCell(n));

  HierarchicalAStar first(a);
  HierarchicalAStar second(b);
  const std::vector<CompletenessCase> cases =
      drawCompletenessCases(grid, testing::completenessAgents(2), 3, 0, 4, 0);
  std::vector<Cell> p1, p2, p3;
  int found = 0;
  for (const CompletenessCase& c : cases) {
    const PathResult r1 = first.findPath(c.agent, c.query.start, c.query.goal, &p1);
    first.findPath({1, kInfantry}, c.query.goal, c.query.start, nullptr);  // interleave other work
    const PathResult r2 = first.findPath(c.agent, c.query.start, c.query.goal, &p2);
    const PathResult r3 = second.findPath(c.agent, c.query.start, c.query.goal, &p3);
    EXPECT_EQ(r1.status, r2.status);
    EXPECT_EQ(r1.status, r3.status);
    EXPECT_EQ(r1.cost, r2.cost);
    EXPECT_EQ(r1.cost, r3.cost);
    EXPECT_EQ(r1.metrics.expanded, r2.metrics.expanded);
    EXPECT_EQ(p1, p2);
    EXPECT_EQ(p1, p3);
    found += r1.found();
  }
  EXPECT_GT(found, 20);
}

TEST(HaaStarTest, GraphStatistics) {
  const AnnotatedGrid grid(randomMap(randomMapCase(3)));
  const ClusterAbstraction hq =
      ClusterAbstraction::build(grid, completenessSpec(10, AbstractionQuality::High));
  const ClusterAbstraction lq =
      ClusterAbstraction::build(grid, completenessSpec(10, AbstractionQuality::Low));
  const ClusterAbstraction bare =
      ClusterAbstraction::build(grid, completenessSpec(10, AbstractionQuality::High, false));
  // 87x93 in clusters of 10: the last column and row are short.
  ASSERT_EQ(grid.map().width(), 87);
  ASSERT_EQ(grid.map().height(), 93);
  EXPECT_EQ(hq.clusterCount(), 9 * 10);
  EXPECT_EQ(hq.clusterBounds(hq.clusterCount() - 1).width, 7);
  EXPECT_EQ(hq.clusterBounds(hq.clusterCount() - 1).height, 3);
  EXPECT_GT(hq.stats().nodes, 0u);
  EXPECT_EQ(hq.stats().nodes, hq.nodeCount());
  EXPECT_GT(hq.stats().interEdges, 0u);
  EXPECT_GT(hq.stats().intraEdges, 0u);
  EXPECT_GT(hq.stats().graphBytes, 0u);
  EXPECT_GT(hq.stats().pathBytes, 0u);
  EXPECT_EQ(bare.stats().pathBytes, 0u);
  EXPECT_EQ(bare.stats().nodes, hq.stats().nodes);
  // The LQ graph keeps a subset of what the HQ graph needs.
  EXPECT_LE(lq.stats().nodes, hq.stats().nodes);
  EXPECT_LE(lq.stats().interEdges + lq.stats().intraEdges,
            hq.stats().interEdges + hq.stats().intraEdges);
  // Every node lies in the cluster that lists it, and every edge's annotation is sane.
  std::size_t directedEdges = 0;
  for (int cluster = 0; cluster < hq.clusterCount(); ++cluster) {
    for (std::uint32_t n : hq.nodesInCluster(cluster)) {
      EXPECT_TRUE(hq.clusterBounds(cluster).contains(hq.nodeCell(n)));
      EXPECT_EQ(hq.clusterOf(hq.nodeCell(n)), cluster);
    }
  }
  for (std::uint32_t n = 0; n < hq.nodeCount(); ++n) {
    for (const AbstractEdge& e : hq.edgesOf(n)) {
      ++directedEdges;
      EXPECT_LT(e.target, hq.nodeCount());
      EXPECT_GE(e.clearance, 1);
      EXPECT_FALSE(e.capability.empty());
      EXPECT_GE(e.cost, 1.0 - 1e-9);
    }
  }
  EXPECT_EQ(directedEdges, 2 * (hq.stats().interEdges + hq.stats().intraEdges));
}

// Refinement trusts the graph: an abstract edge an agent may use must turn into grid moves
// that agent may make (HierarchicalAStar asserts it as an invariant in debug and sanitizer
// builds). Checked here for every edge and every agent kind that may use it: an inter-edge is
// one legal step; a cached intra-edge path is legal, ends at the target and costs what the
// edge says; an uncached one is re-planned inside its cluster at no greater cost.
TEST(HaaStarTest, EveryAbstractEdgeRefinesForEveryAgentThatMayUseIt) {
  std::size_t refined = 0;
  for (int i : {0, 5, 9}) {
    const AnnotatedGrid grid(randomMap(randomMapCase(i)));
    AnnotatedAStar search(grid);
    for (int clusterSize : {8, 10}) {
      for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
        for (bool cachePaths : {true, false}) {
          if (!cachePaths && clusterSize != 10) continue;
          const ClusterAbstraction graph =
              ClusterAbstraction::build(grid, completenessSpec(clusterSize, quality, cachePaths));
          std::vector<Cell> cells;
          for (std::uint32_t n = 0; n < graph.nodeCount(); ++n) {
            const Cell from = graph.nodeCell(n);
            for (const AbstractEdge& e : graph.edgesOf(n)) {
              const Cell to = graph.nodeCell(e.target);
              for (const Agent agent : testing::completenessAgents()) {
                if (!e.usableBy(agent)) continue;
                SCOPED_TRACE(testing::describeQuery(agent, from, to) + ", " +
                             (e.intra ? "intra" : "inter") + ", map " + std::to_string(i) +
                             ", cluster " + std::to_string(clusterSize));
                ++refined;
                if (!e.intra || e.path != AbstractEdge::kNoPath) {
                  cells.assign(1, from);
                  graph.appendEdgeCells(n, e, &cells);
                  ASSERT_EQ(findIllegalStep(grid, agent, cells), "");
                  ASSERT_EQ(cells.back(), to);
                  ASSERT_NEAR(pathCost(cells), e.cost, 1e-9);
                } else {
                  SearchLimits inCluster;
                  inCluster.region = graph.clusterBounds(graph.clusterOf(from));
                  const PathResult r = search.findPath(agent, from, to, &cells, inCluster);
                  ASSERT_TRUE(r.found());
                  ASSERT_LE(r.cost, e.cost + 1e-9);
                }
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(refined, 300000u);
}

using warpath::testing::expectRejected;

TEST(HaaStarTest, SpecsAreValidated) {
  const AnnotatedGrid grid(GridMap(20, 20));
  EXPECT_EQ(problemWith(completenessSpec(8, AbstractionQuality::High)), "");
  const auto check = [&](const AbstractionSpec& spec, const std::string& message) {
    EXPECT_EQ(problemWith(spec), message);
    expectRejected([&] { ClusterAbstraction::build(grid, spec); }, message);
  };
  AbstractionSpec spec = completenessSpec(8, AbstractionQuality::High);
  spec.clusterSize = 1;
  check(spec, "clusterSize must be 2..4096 (got 1)");
  spec.clusterSize = kMaxClusterSize + 1;
  check(spec, "clusterSize must be 2..4096 (got 4097)");
  spec.clusterSize = kMaxClusterSize;  // the largest allowed: one cluster holds the map
  EXPECT_EQ(ClusterAbstraction::build(grid, spec).clusterCount(), 1);
  spec = completenessSpec(8, AbstractionQuality::High);
  spec.maxAgentSize = 0;
  check(spec, "maxAgentSize must be 1..255 (got 0)");
  spec.maxAgentSize = 256;
  check(spec, "maxAgentSize must be 1..255 (got 256)");
  spec = completenessSpec(8, AbstractionQuality::High);
  spec.capabilities.clear();
  check(spec, "capabilities must not be empty (got none)");
  spec.capabilities = {kGround, Capability{}};
  check(spec, "capabilities[1] must allow at least one terrain (got none)");
  spec = completenessSpec(8, AbstractionQuality::High);
  spec.threads = 0;
  check(spec, "threads must be 1..256 (got 0)");
  spec.threads = kMaxBuildThreads + 1;
  check(spec, "threads must be 1..256 (got 257)");
}

TEST(HaaStarTest, HybridOptionsAndPlannerArgumentsAreValidated) {
  const AnnotatedGrid grid(GridMap(20, 20));
  const AnnotatedGrid other(GridMap(20, 20));
  const ClusterAbstraction hq =
      ClusterAbstraction::build(grid, completenessSpec(8, AbstractionQuality::High));
  const ClusterAbstraction lq =
      ClusterAbstraction::build(grid, completenessSpec(8, AbstractionQuality::Low));
  EXPECT_EQ(problemWith(HybridOptions{}), "");
  EXPECT_EQ(problemWith(HybridOptions{.tau = 1}), "");
  EXPECT_EQ(problemWith(HybridOptions{.tau = 0}), "tau must be >= 1 (got 0)");
  expectRejected([&] { HybridPlanner(hq, HybridOptions{.tau = 0}); }, "tau must be >= 1 (got 0)");
  expectRejected([&] { Planner(grid, Algorithm::Hybrid, &hq, HybridOptions{.tau = 0}); },
                 "tau must be >= 1 (got 0)");

  EXPECT_EQ(problemWith(grid, Algorithm::AStar, nullptr), "");
  EXPECT_EQ(problemWith(grid, Algorithm::HaaHigh, &hq), "");
  EXPECT_EQ(problemWith(grid, Algorithm::HaaLow, &lq), "");
  EXPECT_EQ(problemWith(grid, Algorithm::Hybrid, &hq), "");
  const auto check = [&](Algorithm algorithm, const ClusterAbstraction* abstraction,
                         const AnnotatedGrid& on, const std::string& message) {
    EXPECT_EQ(problemWith(on, algorithm, abstraction), message);
    expectRejected([&] { Planner(on, algorithm, abstraction); }, message);
  };
  check(Algorithm::HaaHigh, nullptr, grid, "abstraction must be given for haa-hq (got none)");
  check(Algorithm::Hybrid, nullptr, grid, "abstraction must be given for hybrid (got none)");
  check(Algorithm::HaaLow, &hq, grid, "abstraction must be of quality LQ for haa-lq (got HQ)");
  check(Algorithm::HaaHigh, &lq, grid, "abstraction must be of quality HQ for haa-hq (got LQ)");
  check(Algorithm::HaaHigh, &hq, other, "abstraction must be built on the planner's grid");
}

// Query-time arguments never throw: every entry point answers bad ends, agent sizes below 1
// and empty capabilities with a status.
TEST(HaaStarTest, EveryEntryPointAnswersBadQueryArgumentsWithAStatus) {
  const AnnotatedGrid grid(GridMap(30, 30));
  const ClusterAbstraction hq =
      ClusterAbstraction::build(grid, completenessSpec(8, AbstractionQuality::High));
  const ClusterAbstraction lq =
      ClusterAbstraction::build(grid, completenessSpec(8, AbstractionQuality::Low));
  AnnotatedAStar aa(grid);
  HierarchicalAStar haa(hq);
  HybridPlanner hybrid(hq);
  Planner viaAa(grid, Algorithm::AStar, nullptr);
  Planner viaHq(grid, Algorithm::HaaHigh, &hq);
  Planner viaLq(grid, Algorithm::HaaLow, &lq);
  Planner viaHybrid(grid, Algorithm::Hybrid, &hq);
  std::vector<Cell> path{{7, 7}};
  const auto checkAll = [&](Agent agent, Cell start, Cell goal, PathStatus expected) {
    SCOPED_TRACE(testing::describeQuery(agent, start, goal));
    EXPECT_EQ(aa.findPath(agent, start, goal, &path).status, expected);
    EXPECT_TRUE(path.empty());
    EXPECT_EQ(haa.findPath(agent, start, goal, &path).status, expected);
    EXPECT_EQ(hybrid.findPath(agent, start, goal, &path).status, expected);
    for (Planner* p : {&viaAa, &viaHq, &viaLq, &viaHybrid})
      EXPECT_EQ(p->findPath(agent, start, goal, &path).status, expected);
    EXPECT_TRUE(path.empty());
  };
  const Capability none;
  checkAll({0, kGround}, {1, 1}, {20, 20}, PathStatus::InvalidStart);
  checkAll({-3, kGround}, {1, 1}, {20, 20}, PathStatus::InvalidStart);
  checkAll({1, none}, {1, 1}, {20, 20}, PathStatus::InvalidStart);
  checkAll({1, kGround}, {-1, 1}, {20, 20}, PathStatus::InvalidStart);
  checkAll({1, kGround}, {1, 30}, {20, 20}, PathStatus::InvalidStart);
  checkAll({1, kGround}, {1, 1}, {30, 20}, PathStatus::InvalidGoal);
  checkAll({1, kGround}, {1, 1}, {20, -7}, PathStatus::InvalidGoal);
  checkAll({31, kGround}, {0, 0}, {0, 0}, PathStatus::InvalidStart);  // larger than the map
  checkAll({1000, kGround}, {0, 0}, {1, 1}, PathStatus::InvalidStart);
}

TEST(HaaStarTest, PlannerFacadeRunsEveryAlgorithm) {
  for (const char* name : {"aa", "haa-hq", "haa-lq", "hybrid"}) {
    const auto algorithm = algorithmFromName(name);
    ASSERT_TRUE(algorithm) << name;
    EXPECT_EQ(toString(*algorithm), name);
  }
  EXPECT_FALSE(algorithmFromName("dijkstra"));
  EXPECT_FALSE(abstractionQualityFor(Algorithm::AStar));
  EXPECT_EQ(abstractionQualityFor(Algorithm::HaaHigh), AbstractionQuality::High);
  EXPECT_EQ(abstractionQualityFor(Algorithm::HaaLow), AbstractionQuality::Low);
  EXPECT_EQ(abstractionQualityFor(Algorithm::Hybrid), AbstractionQuality::High);

  const AnnotatedGrid grid(randomMap(randomMapCase(0)));
  const std::vector<CompletenessCase> cases =
      drawCompletenessCases(grid, testing::completenessAgents(), 21, 2, 3, 1);
  CompletenessTally tally;
  for (Algorithm algorithm :
       {Algorithm::AStar, Algorithm::HaaHigh, Algorithm::HaaLow, Algorithm::Hybrid}) {
    std::optional<ClusterAbstraction> abstraction;
    if (const auto quality = abstractionQualityFor(algorithm)) {
      abstraction.emplace(ClusterAbstraction::build(grid, completenessSpec(8, *quality)));
    }
    Planner planner(grid, algorithm, abstraction ? &*abstraction : nullptr);
    EXPECT_EQ(planner.algorithm(), algorithm);
    checkCompleteness(grid, cases, planner, std::string(toString(algorithm)), tally);
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 200);
}

}  // namespace
}  // namespace warpath::pathing
