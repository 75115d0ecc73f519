// Extended suite (CTest label `data`) on the MovingAI maps of the shared data folder. Built only
// when the data folder exists; the maps are read from there at run time, never copied into the
// repository.
// - AA* reproduces the published optimal length of every query of every scen file.
// - The HAA* completeness proof: for sizes 1-3 and the catalogue capabilities and MovingAI
//   classes, seeded random queries (reachable and not) are answered by HAA* on the HQ and LQ
//   graphs, smoothed and not, with insertion by search and by tables, and by the hybrid planner;
//   each finds a path exactly when AA* does, a legal one, never cheaper.
// - The same under terrain costs, on a weighted graph per agent (issue 13).
// - The same after changes of terrain, on repaired graphs (issue 14).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/haa_star.h"
#include "pathing/jump_point_search.h"
#include "pathing/map_io.h"
#include "pathing/planner.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"
#include "support/completeness.h"

namespace warpath::pathing {
namespace {

namespace fs = std::filesystem;

struct MapCase {
  std::string family;
  std::string name;
  fs::path map;
  fs::path scen;
};

// Keeps CTest's test names readable (gtest would otherwise print the bytes of the struct).
void PrintTo(const MapCase& c, std::ostream* out) {
  *out << c.map.string();
}

fs::path movingAiRoot() {
  return fs::path(WARPATH_MOVINGAI_DIR);
}

// Pairs maps/<family>/X.map with scenarios/<family>/X.map.scen, sorted for a stable order.
std::vector<MapCase> discoverCases() {
  std::vector<MapCase> cases;
  const fs::path maps = movingAiRoot() / "maps";
  std::error_code ec;
  for (const auto& family : fs::directory_iterator(maps, ec)) {
    for (const auto& entry : fs::directory_iterator(family.path(), ec)) {
      if (entry.path().extension() != ".map") continue;
      const fs::path scen = movingAiRoot() / "scenarios" / family.path().filename() /
                            (entry.path().filename().string() + ".scen");
      if (!fs::exists(scen)) continue;
      cases.push_back(
          {family.path().filename().string(), entry.path().stem().string(), entry.path(), scen});
    }
  }
  std::sort(cases.begin(), cases.end(),
            [](const MapCase& a, const MapCase& b) { return a.map < b.map; });
  return cases;
}

class MovingAiMap : public ::testing::TestWithParam<MapCase> {};

TEST_P(MovingAiMap, EveryScenQueryMatchesItsOptimalLength) {
  const MapCase& c = GetParam();
  auto map = loadMap(c.map);
  ASSERT_TRUE(map) << map.error().describe();
  auto scen = loadScen(c.scen);
  ASSERT_TRUE(scen) << scen.error().describe();
  const Status fits = checkScenAgainstMap(scen.value(), map.value(), c.scen.string());
  ASSERT_TRUE(fits) << fits.error().describe();

  const AnnotatedGrid grid(std::move(map).value());
  // Every optimal planner: AA*, jump point search, and JPS+ (its tables). The jump point
  // searches answer every query; AA* every query of maps with at most kAStarQueries, and an even
  // sample of that many elsewhere: maze512-4-0's 9,730 queries took AA* about 100 s of the 130 s
  // of the suite's longest test, for nothing a sample of 2,500 across all its lengths misses.
  constexpr std::size_t kAStarQueries = 2'500;
  const std::size_t aStarEvery = (scen.value().size() + kAStarQueries - 1) / kAStarQueries;
  Planner aa(grid, Algorithm::AStar, nullptr);
  Planner jps(grid, Algorithm::Jps, nullptr);
  Planner jpsPlus(grid, Algorithm::JpsPlus, nullptr);
  std::vector<Cell> path;
  int failures = 0;
  std::size_t answers = 0;
  for (std::size_t i = 0; i < scen.value().size(); ++i) {
    const ScenQuery& q = scen.value()[i];
    // MovingAI semantics: size 1, capability = the start cell's movement class.
    const Agent agent{1, movingAiClassOf(grid.map().at(q.start))};
    for (Planner* planner : {&aa, &jps, &jpsPlus}) {
      if (planner == &aa && i % aStarEvery != 0) continue;
      ++answers;
      const PathResult result = planner->findPath(agent, q.start, q.goal, &path);
      const bool ok = result.found() && std::abs(result.cost - q.optimalLength) <= 0.01 &&
                      findIllegalStep(grid, agent, path).empty();
      if (!ok && ++failures <= 5) {
        ADD_FAILURE() << c.scen.string() << ":" << q.line << ": " << toString(planner->algorithm())
                      << " expected " << q.optimalLength << ", got " << toString(result.status)
                      << " " << result.cost;
      }
    }
  }
  EXPECT_EQ(failures, 0) << "of " << answers << " answers";
  EXPECT_FALSE(scen.value().empty());
}

TEST_P(MovingAiMap, HaaFindsAPathExactlyWhenAStarDoes) {
  const MapCase& c = GetParam();
  auto map = loadMap(c.map);
  ASSERT_TRUE(map) << map.error().describe();
  const AnnotatedGrid grid(std::move(map).value());
  // 18 agent kinds x (6 standable pairs + 24 reachable pairs): ~500 queries a map.
  const std::vector<testing::CompletenessCase> cases =
      testing::drawCompletenessCases(grid, testing::completenessAgents(), 2008, 6, 24, 0);
  testing::CompletenessTally tally;
  for (int clusterSize : {10, 16}) {
    for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
      const ClusterAbstraction abstraction = ClusterAbstraction::build(
          grid, AbstractionSpec{.clusterSize = clusterSize,
                                .maxAgentSize = 3,
                                .capabilities = testing::completenessCapabilities(),
                                .quality = quality});
      const std::string label = c.map.filename().string() + " cluster " +
                                std::to_string(clusterSize) +
                                (quality == AbstractionQuality::High ? " HQ" : " LQ");
      HierarchicalAStar smoothed(abstraction, HaaOptions{.smooth = true});
      HierarchicalAStar raw(abstraction, HaaOptions{.smooth = false});
      testing::checkCompleteness(grid, cases, smoothed, label + " smoothed", tally);
      testing::checkCompleteness(grid, cases, raw, label + " unsmoothed", tally);
      if (clusterSize == 16) {
        HierarchicalAStar tabled(abstraction, HaaOptions{.insertion = InsertionMode::Tables});
        testing::checkCompleteness(grid, cases, tabled, label + " insertion tables", tally);
      }
      if (quality == AbstractionQuality::High) {
        HybridPlanner hybrid(abstraction);
        testing::checkCompleteness(grid, cases, hybrid, label + " hybrid", tally);
        // The JPS+ attempt does not depend on the clusters: one graph is enough.
        if (clusterSize == 16) {
          HybridPlanner jumping(abstraction, HybridOptions{.attempt = HybridAttempt::JumpPoints});
          testing::checkCompleteness(grid, cases, jumping, label + " hybrid jps+", tally);
        }
      }
    }
  }
  // Level 2 (4x4 blocks of clusters of 16, HQ and LQ): complete too.
  for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
    const ClusterAbstraction abstraction = ClusterAbstraction::build(
        grid, AbstractionSpec{.clusterSize = 16,
                              .maxAgentSize = 3,
                              .capabilities = testing::completenessCapabilities(),
                              .quality = quality,
                              .levels = 2,
                              .levelTwoSize = 4});
    HierarchicalAStar haa(abstraction);
    const std::string label = c.map.filename().string() + " level 2 " +
                              std::string(kAbstractionQualityNames.name(quality));
    testing::checkCompleteness(grid, cases, haa, label, tally);
    HierarchicalAStar tabled(abstraction, HaaOptions{.insertion = InsertionMode::Tables});
    testing::checkCompleteness(grid, cases, tabled, label + " insertion tables", tally);
  }
  EXPECT_EQ(tally.failures, 0) << "of " << cases.size() << " queries";
  // Every map has ground a size-1 unit can cross, so reachable pairs exist.
  EXPECT_GT(tally.found, 100);
}

// Under terrain costs (infantry speeds: 1.5 cells/s on ground, 0.8 in swamp, 1 in trees) a
// weighted graph per agent finds a path exactly when weighted AA* does, never cheaper.
TEST_P(MovingAiMap, WeightedHaaFindsAPathExactlyWhenWeightedAStarDoes) {
  const MapCase& c = GetParam();
  auto map = loadMap(c.map);
  ASSERT_TRUE(map) << map.error().describe();
  const AnnotatedGrid grid(std::move(map).value());
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  costs.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  testing::CompletenessTally tally;
  for (int size = 1; size <= 3; ++size) {
    const Agent agent{size, costs.capability()};
    const CostField field(grid, agent, costs);
    const std::vector<testing::CompletenessCase> cases =
        testing::drawCompletenessCases(grid, {agent}, 2013, 6, 24, 0, &field);
    for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
      const ClusterAbstraction abstraction =
          ClusterAbstraction::build(grid, weightedAbstractionSpec(agent, costs, 16, quality));
      const std::string label = c.map.filename().string() + " size " + std::to_string(size) +
                                (quality == AbstractionQuality::High ? " HQ" : " LQ");
      HierarchicalAStar haa(abstraction);
      testing::checkCompleteness(grid, cases, haa, label, tally);
      HybridPlanner hybrid(abstraction);
      testing::checkCompleteness(grid, cases, hybrid, label + " hybrid", tally);
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 50);
}

// Terrain that changes (issue 14): after a sequence of changes on the real map (obstacles
// placed and cleared, terrain set, up to 24 cells a side), the repaired HQ and LQ graphs find a
// path exactly when AA* on a grid built afresh from the changed map does.
TEST_P(MovingAiMap, RepairedHaaFindsAPathExactlyWhenAStarDoes) {
  const MapCase& c = GetParam();
  auto map = loadMap(c.map);
  ASSERT_TRUE(map) << map.error().describe();
  AnnotatedGrid grid(std::move(map).value());
  std::vector<ClusterAbstraction> graphs;
  for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
    graphs.push_back(ClusterAbstraction::build(
        grid, AbstractionSpec{.clusterSize = 16,
                              .maxAgentSize = 3,
                              .capabilities = testing::completenessCapabilities(),
                              .quality = quality}));
  }
  SplitMix64 rng(1914);
  std::vector<CellRect> obstacles;
  constexpr Terrain kSet[] = {Terrain::Ground, Terrain::Blocked, Terrain::Swamp, Terrain::Water};
  testing::CompletenessTally tally;
  const GridMap& changing = grid.map();
  for (int step = 0; step < 6; ++step) {
    const CellRect area{rng.between(0, changing.width() - 1), rng.between(0, changing.height() - 1),
                        rng.between(2, 24), rng.between(2, 24)};
    TerrainChange change;
    if (step % 3 == 2 && !obstacles.empty()) {
      change = grid.clearObstacle(obstacles.back());
      obstacles.pop_back();
    } else if (step % 3 == 1) {
      obstacles.push_back(area);
      change = grid.placeObstacle(area);
    } else {
      change = grid.setTerrain(area, kSet[rng.between(0, 3)]);
    }
    for (ClusterAbstraction& graph : graphs)
      graph.repair(change);
    const AnnotatedGrid fresh(grid.map());
    const std::vector<testing::CompletenessCase> cases = testing::drawCompletenessCases(
        fresh, testing::completenessAgents(), 2014 + static_cast<std::uint64_t>(step), 2, 6, 0);
    for (ClusterAbstraction& graph : graphs) {
      HierarchicalAStar haa(graph);
      testing::checkCompleteness(
          fresh, cases, haa,
          c.map.filename().string() + " step " + std::to_string(step) + " " +
              std::string(kAbstractionQualityNames.name(graph.spec().quality)),
          tally);
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 100);
}

INSTANTIATE_TEST_SUITE_P(Data, MovingAiMap, ::testing::ValuesIn(discoverCases()),
                         [](const ::testing::TestParamInfo<MapCase>& param) {
                           std::string name = param.param.family + "_" + param.param.name;
                           for (char& ch : name) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace warpath::pathing
