// Level 2 of the HAA* graph in the engine (issue 15, `pathing: {levels: 2, level_two_size: N}`):
// the keys, congestion surcharges that let searches cross queue-free level-2 clusters by
// level-2 edges, and bundled scenarios that keep their arrivals with it.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "engine/congestion.h"
#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/map_io.h"
#include "support/one_unit_scenario.h"
#include "support/run_out.h"
#include "support/wall_with_gaps.h"

namespace warpath::engine {
namespace {

using pathing::Cell;
using pathing::Terrain;

TEST(Levels, TheScenarioKeysParse) {
  Result<Scenario> plain = testing::parseOneUnitScenario("");
  ASSERT_TRUE(plain.ok()) << plain.error().describe();
  EXPECT_EQ(plain.value().settings.pathing.levels, 1);
  EXPECT_EQ(plain.value().settings.pathing.levelTwoSize, 4);
  Result<Scenario> two = testing::parseOneUnitScenario("pathing: {levels: 2, level_two_size: 3}\n");
  ASSERT_TRUE(two.ok()) << two.error().describe();
  EXPECT_EQ(two.value().settings.pathing.levels, 2);
  EXPECT_EQ(two.value().settings.pathing.levelTwoSize, 3);
}

// A surcharge says a level-2 cluster is free only when its every edge is charged nothing.
TEST(Levels, CongestionFreesTheLevelTwoClustersWithoutAQueue) {
  const pathing::AnnotatedGrid grid(testing::wallWithTwoGaps(64, 32, 38, 20));
  const pathing::Capability ground = pathing::Capability::of({Terrain::Ground});
  const pathing::Agent infantry{1, ground};
  const pathing::ClusterAbstraction graph =
      pathing::ClusterAbstraction::build(grid, {.clusterSize = 8,
                                                .maxAgentSize = 1,
                                                .capabilities = {ground},
                                                .levels = 2,
                                                .levelTwoSize = 2});
  Congestion congestion(grid, 8);
  std::vector<Cell> row6;
  for (int x = 2; x <= 61; ++x)
    row6.push_back({x, 6});
  for (std::uint32_t i = 0; i < 10; ++i)
    congestion.book(UnitId{i, 0}, infantry, 1.5, row6, 0.0);
  ASSERT_EQ(congestion.queuesAt(0.0), 1u);
  const auto blockOf = [&](Cell c) { return graph.levelTwoClusterOf(c); };
  for (const double now : {0.0, 30.0}) {
    const Congestion::Surcharge surcharge(congestion, infantry, 1.5, now, false);
    // The queue at the narrow gap (row 6, columns 38-41) while it lasts; the wide gap has none.
    EXPECT_EQ(surcharge.freeWithin(graph, blockOf({39, 6})), now > 0.0) << now;
    EXPECT_TRUE(surcharge.freeWithin(graph, blockOf({39, 21}))) << now;
    EXPECT_TRUE(surcharge.freeWithin(graph, blockOf({3, 3}))) << now;
    // Free means no edge inside is charged, at any cost so far.
    int checked = 0;
    for (int block = 0; block < graph.levelTwoClusterCount(); ++block) {
      if (!surcharge.freeWithin(graph, block)) continue;
      for (std::uint32_t n = 0; n < graph.nodeCount(); ++n) {
        if (graph.levelTwoClusterOfNode(n) != block) continue;
        for (const pathing::AbstractEdge& e : graph.edgesOf(n)) {
          if (graph.levelTwoClusterOfNode(e.target) != block) continue;
          for (const double g : {0.0, 7.0, 40.0})
            EXPECT_EQ(surcharge.on(graph, n, e, g), 0.0);
          ++checked;
        }
      }
    }
    EXPECT_GT(checked, 50);
  }
}

// Bundled scenarios keep their expectations with level 2 (bridge_demolition repairs it as the
// bridge goes), and runs stay deterministic; their long searches cross level-2 clusters by
// level-2 edges (congestion surcharges allowing).
TEST(Levels, BundledScenariosPassWithLevelTwo) {
  std::uint64_t levelOne = 0;
  std::uint64_t levelTwo = 0;
  for (const char* file :
       {"demo.yaml", "river_crossing.yaml", "swamp_detour.yaml", "bridge_demolition.yaml"}) {
    Result<Scenario> loaded = loadScenario(std::string(WARPATH_SOURCE_DIR) + "/scenarios/" + file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
    Scenario s = std::move(loaded).value();
    s.settings.pathing.levels = 2;
    s.settings.pathing.levelTwoSize = 2;
    const Report a = testing::runToEnd(s, 1);
    const Report b = testing::runToEnd(s, 1);
    EXPECT_TRUE(a.passed()) << file;
    EXPECT_EQ(a.stateHash, b.stateHash) << file;
    EXPECT_GT(a.pathing.searches, 0u) << file;
    s.settings.pathing.levels = 1;
    levelOne += testing::runToEnd(s, 1).pathing.expanded;
    levelTwo += a.pathing.expanded;
  }
  EXPECT_LT(levelTwo, levelOne);
}

// `pathing: {insertion: tables}` (HAA* insertion by lookup, docs/haa.md): the key parses, and
// bundled scenarios keep their expectations with it, terrain changes included
// (bridge_demolition destroys a bridge; forest_battle leaves wrecks that block planning), stay
// deterministic, and their searches expand fewer nodes.
TEST(Levels, BundledScenariosPassWithInsertionTables) {
  Result<Scenario> keyed = testing::parseOneUnitScenario("pathing: {insertion: tables}\n");
  ASSERT_TRUE(keyed.ok()) << keyed.error().describe();
  EXPECT_EQ(keyed.value().settings.pathing.insertion, pathing::InsertionMode::Tables);
  EXPECT_EQ(testing::parseOneUnitScenario("").value().settings.pathing.insertion,
            pathing::InsertionMode::Search);
  std::uint64_t searched = 0;
  std::uint64_t looked = 0;
  for (const char* file : {"demo.yaml", "river_crossing.yaml", "swamp_detour.yaml",
                           "bridge_demolition.yaml", "forest_battle.yaml"}) {
    Result<Scenario> loaded = loadScenario(std::string(WARPATH_SOURCE_DIR) + "/scenarios/" + file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
    Scenario s = std::move(loaded).value();
    s.settings.pathing.insertion = pathing::InsertionMode::Tables;
    const Report a = testing::runToEnd(s, 1);
    const Report b = testing::runToEnd(s, 1);
    EXPECT_TRUE(a.passed()) << file;
    EXPECT_EQ(a.stateHash, b.stateHash) << file;
    s.settings.pathing.insertion = pathing::InsertionMode::Search;
    searched += testing::runToEnd(s, 1).pathing.expanded;
    looked += a.pathing.expanded;
  }
  EXPECT_LT(looked, searched);
}

}  // namespace
}  // namespace warpath::engine
