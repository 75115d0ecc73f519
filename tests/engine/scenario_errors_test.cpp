// Bad scenario files are reported with file, line, column and the problem.

#include <gtest/gtest.h>

#include <string>

#include "engine/scenario.h"

namespace warpath::engine {
namespace {

const std::string kFile = std::string(WARPATH_SOURCE_DIR) + "/scenarios/test_input.yaml";

// A valid scenario on an inline map: a wall with a gap 2 cells wide (rows 2-3) and a pond.
std::string scenario(const std::string& extra, const std::string& group) {
  return "map:\n"
         "  rows:\n"
         "    - '..........@.........'\n"
         "    - '..........@.........'\n"
         "    - '....................'\n"
         "    - '....................'\n"
         "    - '..........@.........'\n"
         "    - '..WW......@.........'\n"
         "    - '..WW......@.........'\n"
         "catalogue: ../assets/units.yaml\n"
         "duration: 10\n"
         "teams: [blue]\n" +
         extra + "groups:\n" + group;
}

const std::string kGroup =
    "  - {team: blue, type: infantry, count: 2, spawn: {x: 0, y: 0, w: 3, h: 3},"
    " goal: {x: 15, y: 0, w: 3, h: 3}}\n";

Error errorOf(const std::string& text) {
  const Result<Scenario> r = parseScenario(text, kFile);
  EXPECT_FALSE(r.ok()) << text;
  return r.ok() ? Error{} : r.error();
}

TEST(Errors, ValidInputLoads) {
  const Result<Scenario> r = parseScenario(scenario("", kGroup), kFile);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_EQ(r.value().groups.size(), 1u);
  EXPECT_EQ(r.value().catalogue.size(), 4u);
  EXPECT_EQ(r.value().grid->map().width(), 20);
}

TEST(Errors, UnknownKeyNamesLineAndColumn) {
  const Error e = errorOf(scenario("speeed: 3\n", kGroup));
  EXPECT_EQ(e.line, 13);
  EXPECT_EQ(e.column, 1);
  EXPECT_NE(e.message.find("unknown key 'speeed'"), std::string::npos) << e.message;
  EXPECT_EQ(e.describe().rfind(kFile + ":13:1: unknown key", 0), 0u) << e.describe();
}

TEST(Errors, UnknownUnitType) {
  const Error e = errorOf(scenario(
      "", "  - {team: blue, type: zeppelin, count: 1, spawn: {x: 0, y: 0, w: 3, h: 3}}\n"));
  EXPECT_EQ(e.line, 14);
  EXPECT_EQ(e.column, 24);
  EXPECT_NE(e.message.find("unknown unit type 'zeppelin'"), std::string::npos) << e.message;
}

TEST(Errors, SpawnOnTerrainTheUnitCannotStandOn) {
  // Tanks cannot stand in the pond (or anywhere in a 2x2 area around it).
  const Error e = errorOf(
      scenario("", "  - {team: blue, type: tank, count: 1, spawn: {x: 2, y: 5, w: 2, h: 2}}\n"));
  EXPECT_EQ(e.line, 14);
  EXPECT_NE(e.message.find("room for only 0 of 1 tank"), std::string::npos) << e.message;
}

TEST(Errors, GoalUnreachableForTheType) {
  // Tanks (3 wide) cannot pass the 2-cell gap; infantry can.
  const Error e =
      errorOf(scenario("",
                       "  - {team: blue, type: tank, count: 1, spawn: {x: 0, y: 0, w: 4, h: 4},"
                       " goal: {x: 15, y: 0, w: 4, h: 4}}\n"));
  EXPECT_EQ(e.line, 14);
  EXPECT_NE(e.message.find("unreachable for tank"), std::string::npos) << e.message;
}

TEST(Errors, MissingMapFile) {
  const Error e = errorOf("map: ../assets/maps/no_such.map\nduration: 1\nteams: [a]\ngroups: []\n");
  EXPECT_EQ(e.line, 1);
  EXPECT_EQ(e.column, 6);
  EXPECT_NE(e.message.find("not found"), std::string::npos) << e.message;
}

TEST(Errors, MapThatIsNotAFileSaysWhatItIs) {
  // Not "not found": the path exists but cannot be a map.
  Error e = errorOf("map: /dev/zero\nduration: 1\nteams: [a]\ngroups: []\n");
  EXPECT_EQ(e.describe(), kFile + ":1:6: map: /dev/zero: not a regular file");
  e = errorOf("map: ../assets\nduration: 1\nteams: [a]\ngroups: []\n");
  EXPECT_EQ(e.describe(), kFile + ":1:6: map: " + std::string(WARPATH_SOURCE_DIR) +
                              "/scenarios/../assets: is a directory");
  e = errorOf(
      "map: ../assets/maps/river.map\ncatalogue: /dev/zero\nduration: 1\nteams: [a]\n"
      "groups: []\n");
  EXPECT_EQ(e.describe(), kFile + ":2:12: catalogue: /dev/zero: not a regular file");
}

TEST(Errors, ScenarioFileThatIsNotAFile) {
  for (const auto& [file, problem] :
       {std::pair{std::string("/dev/zero"), "not a regular file"},
        std::pair{std::string(WARPATH_SOURCE_DIR) + "/scenarios", "is a directory"},
        std::pair{std::string(WARPATH_SOURCE_DIR) + "/scenarios/no_such.yaml", "no such file"}}) {
    const Result<Scenario> r = loadScenario(file);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().describe(), file + ": " + problem);
  }
}

TEST(Errors, YamlSyntaxError) {
  const Error e = errorOf("map: [unclosed\nduration: 1\n");
  EXPECT_GT(e.line, 0);
  EXPECT_FALSE(e.message.empty());
}

TEST(Errors, BadValuesAndExpectations) {
  EXPECT_NE(errorOf(scenario("tick_rate: fast\n", kGroup)).message.find("cannot read 'fast'"),
            std::string::npos);
  EXPECT_NE(errorOf(scenario("pathing: {algo: dijkstra}\n", kGroup)).message.find("unknown algo"),
            std::string::npos);
  EXPECT_NE(errorOf(scenario("expectations: [{arrivals: 3}]\n", kGroup))
                .message.find("unknown expectation"),
            std::string::npos);
  const Error area = errorOf(scenario(
      "", "  - {team: blue, type: infantry, count: 1, spawn: {x: 0, y: 0, w: 30, h: 3}}\n"));
  EXPECT_NE(area.message.find("spawn w must be between"), std::string::npos) << area.message;
}

TEST(Errors, UnitTypeOverridesAreChecked) {
  const Result<Scenario> ok =
      parseScenario(scenario("unit_types: {tank: {speed: 3.5}}\n", kGroup), kFile);
  ASSERT_TRUE(ok.ok()) << ok.error().describe();
  EXPECT_EQ(ok.value().catalogue[2].name, "tank");
  EXPECT_EQ(ok.value().catalogue[2].maxSpeed(), 3.5);
  EXPECT_EQ(ok.value().catalogue[2].size, 3);  // the rest from the catalogue
  const Error e = errorOf(scenario("unit_types: {hover: {size: 1}}\n", kGroup));
  EXPECT_NE(e.message.find("needs 'capability'"), std::string::npos) << e.message;
  const Error r = errorOf(scenario("unit_types: {tank: {radius: 2}}\n", kGroup));
  EXPECT_NE(r.message.find("radius"), std::string::npos) << r.message;
}

TEST(Errors, OrdersNeedWhatTheirKindTakes) {
  // Orders are moves unless told otherwise; a move needs somewhere to go.
  const Error e = errorOf(scenario("", kGroup + "orders:\n  - {at: 1, group: group1}\n"));
  EXPECT_EQ(e.line, 16);
  EXPECT_NE(e.message.find("order 'move' needs 'move_to'"), std::string::npos) << e.message;
  const Error k = errorOf(scenario("", kGroup + "orders:\n  - {at: 1, group: group1, "
                                                "order: retreat}\n"));
  EXPECT_NE(k.message.find("unknown order 'retreat'"), std::string::npos) << k.message;
  const Result<Scenario> hold = parseScenario(
      scenario("", kGroup + "orders:\n  - {at: 1, group: group1, order: hold}\n"), kFile);
  ASSERT_TRUE(hold.ok()) << hold.error().describe();
  EXPECT_EQ(hold.value().triggers.at(0).actions.at(0).order, OrderKind::Hold);
}

}  // namespace
}  // namespace warpath::engine
