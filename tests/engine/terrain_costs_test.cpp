// Terrain costs in the world (docs/terrain_costs.md): with `terrain_costs: true` each unit type
// plans the fastest route for its own speeds.

#include <gtest/gtest.h>

#include <string>

#include "engine/scenario.h"
#include "engine/scenario_run.h"

namespace warpath::engine {
namespace {

Scenario load(const std::string& name) {
  Result<Scenario> r = loadScenario(std::string(WARPATH_SOURCE_DIR) + "/scenarios/" + name);
  EXPECT_TRUE(r.ok()) << r.error().describe();
  return std::move(r).value();
}

bool passes(const Scenario& s, std::uint64_t seed) {
  ScenarioRun run(s, seed);
  while (!run.done())
    run.step();
  return run.report().passed();
}

// Infantry go round a swamp when that is faster and meet the time bounds at every seed;
// planning in cells they wade across, and miss them.
TEST(TerrainCosts, InfantryGoRoundASwampWhenThatIsFaster) {
  Scenario s = load("swamp_detour.yaml");
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
  const Scenario s = load("swamp_wade.yaml");
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
    EXPECT_TRUE(passes(s, seed)) << "seed " << seed;
}

TEST(TerrainCosts, NeedTheGridPlannerForNow) {
  const std::string text =
      "map: {rows: ['....', '....']}\n"
      "catalogue: ../assets/units.yaml\n"
      "duration: 1\n"
      "pathing: {algo: hybrid, terrain_costs: true}\n"
      "teams: [blue]\n"
      "groups:\n"
      "  - {team: blue, type: infantry, count: 1, spawn: {x: 0, y: 0, w: 1, h: 1},\n"
      "     goal: {x: 3, y: 1, w: 1, h: 1}}\n";
  const Result<Scenario> r =
      parseScenario(text, std::string(WARPATH_SOURCE_DIR) + "/scenarios/inline.yaml");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 4);
  EXPECT_NE(r.error().message.find("terrain_costs: true needs algo: aa"), std::string::npos)
      << r.error().describe();
}

}  // namespace
}  // namespace warpath::engine
