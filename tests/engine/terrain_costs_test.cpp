// Terrain costs in the world (docs/terrain_costs.md): with `terrain_costs: true` each unit type
// plans the fastest route for its own speeds.

#include <gtest/gtest.h>

#include <string>

#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "pathing/planner.h"
#include "support/run_out.h"
#include "support/scenario_files.h"

namespace warpath::engine {
namespace {

bool passes(const Scenario& s, std::uint64_t seed) {
  return testing::runToEnd(s, seed).passed();
}

// Infantry go round a swamp when that is faster and meet the time bounds at every seed;
// planning in cells they wade across, and miss them.
TEST(TerrainCosts, InfantryGoRoundASwampWhenThatIsFaster) {
  Scenario s = testing::bundledScenario("swamp_detour");
  ASSERT_TRUE(s.settings.pathing.terrainCosts);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    s.settings.pathing.terrainCosts = true;
    EXPECT_TRUE(passes(s, seed)) << "seed " << seed;
    s.settings.pathing.terrainCosts = false;
    EXPECT_FALSE(passes(s, seed)) << "seed " << seed;
  }
}

// …and wade across one where the way round is longer.
TEST(TerrainCosts, InfantryWadeWhereTheWayRoundIsLonger) {
  const Scenario s = testing::bundledScenario("swamp_wade");
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
    EXPECT_TRUE(passes(s, seed)) << "seed " << seed;
}

// Every planner plans under the costs: the hierarchical ones on a weighted graph per profile.
TEST(TerrainCosts, EveryPlannerGoesRoundTheSwamp) {
  Scenario s = testing::bundledScenario("swamp_detour");
  for (pathing::Algorithm algorithm :
       {pathing::Algorithm::Hybrid, pathing::Algorithm::HaaHigh, pathing::Algorithm::HaaLow}) {
    s.settings.pathing.algorithm = algorithm;
    for (std::uint64_t seed = 1; seed <= 2; ++seed)
      EXPECT_TRUE(passes(s, seed)) << toString(algorithm) << " seed " << seed;
  }
}

// A lone unit's travel time is its plan's cost (the goal: within 10 %), for every kind
// of unit and planner, across a swamp some wade and some go round.
TEST(TerrainCosts, ALoneUnitTakesThePlannedTime) {
  for (const char* type : {"infantry", "jeep", "tank", "amphibious"}) {
    for (const char* algo : {"aa", "hybrid", "haa-lq"}) {
      const std::string text =
          std::string("map: ../assets/maps/swamp.map\n") +
          "catalogue: ../assets/units.yaml\n"
          "duration: 120\n"
          "combat: {enabled: false}\n"
          "pathing: {algo: " +
          algo +
          ", terrain_costs: true}\n"
          "teams: [blue]\n"
          "groups:\n"
          "  - {team: blue, type: " +
          type +
          ", count: 1,\n"
          "     spawn: {x: 2, y: 22, w: 3, h: 3}, goal: {x: 56, y: 30, w: 3, h: 3}}\n";
      const Result<Scenario> scenario =
          parseScenario(text, std::string(WARPATH_SOURCE_DIR) + "/scenarios/inline.yaml");
      ASSERT_TRUE(scenario.ok()) << scenario.error().describe();
      const Report report = testing::runToEnd(scenario.value(), 1);
      const std::vector<DelayStats>& delays = report.movement.delay;
      ASSERT_EQ(delays.size(), 1u);
      ASSERT_EQ(delays[0].arrived, 1) << type << " " << algo;
      EXPECT_GT(delays[0].max, 0.9) << type << " " << algo;
      EXPECT_LT(delays[0].max, 1.10) << type << " " << algo;
    }
  }
}

}  // namespace
}  // namespace warpath::engine
