// Bad scenario files are reported with file, line, column and the problem.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "support/scenario_files.h"

namespace warpath::engine {
namespace {

const std::string kTestInputFile = std::string(WARPATH_SOURCE_DIR) + "/scenarios/test_input.yaml";

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
  return testing::scenarioError(text, kTestInputFile);
}

TEST(Errors, ValidInputLoads) {
  const Result<Scenario> r = parseScenario(scenario("", kGroup), kTestInputFile);
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
  EXPECT_EQ(e.describe().rfind(kTestInputFile + ":13:1: unknown key", 0), 0u) << e.describe();
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
  EXPECT_EQ(e.describe(), kTestInputFile + ":1:6: map: /dev/zero: not a regular file");
  e = errorOf("map: ../assets\nduration: 1\nteams: [a]\ngroups: []\n");
  EXPECT_EQ(e.describe(), kTestInputFile + ":1:6: map: " + std::string(WARPATH_SOURCE_DIR) +
                              "/scenarios/../assets: is a directory");
  e = errorOf(
      "map: ../assets/maps/river.map\ncatalogue: /dev/zero\nduration: 1\nteams: [a]\n"
      "groups: []\n");
  EXPECT_EQ(e.describe(), kTestInputFile + ":2:12: catalogue: /dev/zero: not a regular file");
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

// Anchors and aliases: a small file that stands for a huge one is refused before anything big
// is built, naming the limit and the place.
std::string repeated(const std::string& alias, int times) {
  std::string out;
  for (int i = 0; i < times; ++i)
    out += ", " + alias;
  return out;
}

TEST(Errors, AliasedInlineMapIsBoundedByCells) {
  // 41 KB of text, an 8192x8192 map once expanded.
  const std::string text = "map:\n  rows: [&r '" + std::string(8192, '.') + "'" +
                           repeated("*r", 8191) +
                           "]\ncatalogue: ../assets/units.yaml\nduration: 1\nteams: [a]\n"
                           "groups: []\n";
  EXPECT_EQ(errorOf(text).describe(),
            kTestInputFile +
                ":2:9: the inline map has 8192 rows of 8192 cells, more than the 1048576 "
                "cells allowed: give a .map file");
  // Rows may still be repeated within the limit.
  const std::string small = "map:\n  rows: [&r '....'" + repeated("*r", 3) +
                            "]\ncatalogue: ../assets/units.yaml\nduration: 1\nteams: [a]\n"
                            "groups: []\n";
  EXPECT_TRUE(parseScenario(small, kTestInputFile).ok());
}

TEST(Errors, AliasedGroupsAreBoundedByUnitsAndEntries) {
  const std::string head = scenario("", "");
  const std::string group =
      "{team: blue, type: infantry, count: 1000000, spawn: {x: 0, y: 0, w: 3, h: 3}}";
  std::string text = head.substr(0, head.size() - std::string("groups:\n").size()) +
                     "groups: [&g " + group + repeated("*g", 30) + "]\n";
  Error e = errorOf(text);
  EXPECT_EQ(e.message, "the groups have more than 20000 units in all (the limit for one scenario)");
  EXPECT_EQ(e.line, 13);
  const std::string one = "{team: blue, type: infantry, count: 1, spawn: {x: 0, y: 0, w: 3, h: 3}}";
  text = head.substr(0, head.size() - std::string("groups:\n").size()) + "groups: [&g " + one +
         repeated("*g", 1500) + "]\n";
  e = errorOf(text);
  EXPECT_EQ(e.message, "'groups' has 1501 entries, more than the 1000 allowed");
  EXPECT_EQ(e.line, 13);
  EXPECT_EQ(e.column, 9);
}

TEST(Errors, AliasBombIsBoundedByNodes) {
  // Nine levels of ten aliases each: a billion nodes once expanded, 0.4 KB of text.
  std::string text = "l0: &l0 [a, a, a, a, a, a, a, a, a, a]\n";
  for (int i = 1; i < 9; ++i) {
    const std::string alias = "*l" + std::to_string(i - 1);
    text += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [" + alias +
            repeated(alias, 9) + "]\n";
  }
  const Error e = errorOf(text);
  EXPECT_EQ(e.message,
            "the file expands to more than 250000 YAML nodes (anchors and aliases repeat what they "
            "name)");
  EXPECT_EQ(e.file, kTestInputFile);
  EXPECT_GT(e.line, 0);
}

TEST(Errors, DeepNestingNamesTheLimit) {
  for (int depth : {100, 5000}) {  // past our limit; past yaml-cpp's own depth guard
    const std::string text =
        "map: x\nexpectations: " + std::string(static_cast<std::size_t>(depth), '[') +
        std::string(static_cast<std::size_t>(depth), ']') + "\n";
    const Error e = errorOf(text);
    EXPECT_EQ(e.message, "nesting deeper than 64 levels") << depth;
    EXPECT_EQ(e.line, 2) << depth;
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
  EXPECT_NE(errorOf(scenario("pathing: {insertion: cached}\n", kGroup))
                .message.find("unknown insertion 'cached' (search, tables)"),
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
      parseScenario(scenario("unit_types: {tank: {speed: 3.5}}\n", kGroup), kTestInputFile);
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
      scenario("", kGroup + "orders:\n  - {at: 1, group: group1, order: hold}\n"), kTestInputFile);
  ASSERT_TRUE(hold.ok()) << hold.error().describe();
  EXPECT_EQ(hold.value().triggers.at(0).actions.at(0).order, OrderKind::Hold);
}

// ---- every limit of the settings a scenario sets ---------------------------------------------

// "FILE:LINE:COLUMN: " of the first `needle` in `text` at or after `from`.
std::string placeOf(const std::string& text, const std::string& needle, std::size_t from) {
  const std::size_t at = text.find(needle, from);
  EXPECT_NE(at, std::string::npos) << needle;
  const std::size_t lineStart = text.rfind('\n', at);
  const auto line =
      1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
  const std::size_t column = at - (lineStart == std::string::npos ? 0 : lineStart + 1) + 1;
  return kTestInputFile + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
}

// `extra` is refused with `message`, reported at the first `needle` in it (the value or key at
// fault).
void expectRefusedAt(const std::string& extra, const std::string& needle,
                     const std::string& message) {
  const std::string text = scenario(extra, kGroup);
  EXPECT_EQ(errorOf(text).describe(), placeOf(text, needle, text.find(extra)) + message) << extra;
}

// YAML forbids a key twice in one mapping; yaml-cpp would keep the first and drop the rest.
TEST(Limits, ADuplicateKeyIsRefusedWhereItRepeats) {
  expectRefusedAt("duration: 5\n", "duration: 5", "duplicate key 'duration' (first at line 11)");
  expectRefusedAt("pathing: {budget: 10, levels: 2, budget: 20}\n", "budget: 20",
                  "duplicate key 'budget' (first at line 13)");
}

TEST(Limits, WorldSettingsAreReportedAtTheirKey) {
  expectRefusedAt("tick_rate: 0\n", "0\n", "tick_rate must be between 1 and 1000");
  expectRefusedAt("tick_rate: .nan\n", ".nan", "tick_rate must be between 1 and 1000");
  expectRefusedAt("pathing: {cluster_size: 1}\n", "1}", "cluster_size must be between 2 and 4096");
  expectRefusedAt("pathing: {cluster_size: 4097}\n", "4097",
                  "cluster_size must be between 2 and 4096");
  expectRefusedAt("pathing: {levels: 3}\n", "3}", "levels must be between 1 and 2");
  expectRefusedAt("pathing: {level_two_size: 1}\n", "1}",
                  "level_two_size must be between 2 and 256");
  expectRefusedAt("pathing: {budget: 0}\n", "0}", "budget must be between 1 and 1000000000");
  expectRefusedAt("pathing: {cache: -1}\n", "-1", "cache must be between 0 and 100000000");
  expectRefusedAt("stuck: {seconds: 0}\n", "0}", "stuck seconds must be between 0.01 and 1e+06");
  expectRefusedAt("stuck: {min_progress: -0.5}\n", "-0.5",
                  "min_progress must be between 0 and 1e+06");
  expectRefusedAt("stuck: {flag_after: 0}\n", "0}", "flag_after must be between 1 and 1000000");
  expectRefusedAt("combat: {wreck_seconds: -1}\n", "-1",
                  "wreck_seconds must be between 0 and 1e+06");
  expectRefusedAt("combat: {scan_every: 0}\n", "0}", "scan_every must be between 1 and 1000000");
}

TEST(Limits, UnitTypeLimitsAreReportedAtTheirKey) {
  const std::string hover = "unit_types:\n  hover: {size: 1, capability: [ground, water], ";
  expectRefusedAt("unit_types: {tank: {size: 0}}\n", "0}",
                  "unit type 'tank' size must be between 1 and 255");
  expectRefusedAt("unit_types: {tank: {size: 256}}\n", "256",
                  "unit type 'tank' size must be between 1 and 255");
  // Zero speed on a terrain of the capability: problemWith(UnitType), at the value.
  expectRefusedAt(hover + "speed: {ground: 2, water: 0}}\n", "0}}",
                  "unit type 'hover': speed on water must be positive");
  expectRefusedAt(hover + "speed: 0}\n", "0}",
                  "unit type 'hover': speed on ground must be positive");
  expectRefusedAt(hover + "speed: {ground: 2}}\n", "{ground: 2}",
                  "unit type 'hover': speed on water must be positive");
  expectRefusedAt("unit_types: {tank: {speed: 51}}\n", "51",
                  "unit type 'tank' speed must be between 0 and 50");
  expectRefusedAt("unit_types: {tank: {acceleration: 0}}\n", "0}",
                  "unit type 'tank': acceleration must be positive");
  expectRefusedAt("unit_types: {tank: {turn_rate: 0}}\n", "0}",
                  "unit type 'tank': turn_rate must be positive");
  expectRefusedAt("unit_types: {infantry: {radius: 0}}\n", "0}",
                  "unit type 'infantry': radius must be positive and at most size/2");
  expectRefusedAt("unit_types: {infantry: {radius: 0.6}}\n", "0.6",
                  "unit type 'infantry': radius must be positive and at most size/2");
  // The radius comes from the catalogue and the size from the file: the type's fields together.
  expectRefusedAt("unit_types: {tank: {size: 2}}\n", "{size: 2}",
                  "unit type 'tank': radius must be positive and at most size/2");
  expectRefusedAt("unit_types: {tank: {hp: 0}}\n", "0}",
                  "unit type 'tank' hp must be between 1 and 1000000");
}

TEST(Limits, WeaponLimitsAreReportedAtTheirKey) {
  const auto weapon = [](const std::string& fields) {
    return "unit_types: {tank: {weapon: {" + fields + "}}}\n";
  };
  expectRefusedAt(weapon("damage: -1"), "-1",
                  "unit type 'tank' weapon damage must be between 0 and 1000000");
  expectRefusedAt(weapon("range: 0"), "0}", "unit type 'tank' weapon range must be greater than 0");
  expectRefusedAt(weapon("range: 5000"), "5000",
                  "unit type 'tank' weapon range must be between 0 and 4096");
  expectRefusedAt(weapon("cooldown: 0"), "0}",
                  "unit type 'tank' weapon cooldown must be greater than 0");
  expectRefusedAt(weapon("projectile_speed: -1"), "-1",
                  "unit type 'tank' weapon projectile_speed must be between 0 and 1e+06");
  expectRefusedAt(weapon("targets: []"), "[]",
                  "unit type 'tank' weapon targets must name at least one armour class");
  expectRefusedAt(weapon("priority: {heavy: 256}"), "256",
                  "unit type 'tank' weapon priority rank must be between 0 and 255");
}

// Every setting at the edge of its range loads, and the world takes it: the loader's ranges lie
// within the limits World and PathService enforce (their constructors would throw otherwise).
TEST(Limits, SettingsAtTheEdgesOfTheirRangesAreUsable) {
  for (const std::string extra :
       {"tick_rate: 1\npathing: {cluster_size: 2, levels: 1, level_two_size: 2, budget: 1, "
        "cache: 0}\n"
        "stuck: {seconds: 0.01, min_progress: 0, flag_after: 1}\n"
        "combat: {wreck_seconds: 0, scan_every: 1, sight_through_trees: -1}\n",
        "tick_rate: 1000\npathing: {algo: haa-lq, cluster_size: 4096, levels: 2, "
        "level_two_size: 256, budget: 1000000000, cache: 100000000}\nstuck: {seconds: 1000000, "
        "min_progress: 1000000, flag_after: "
        "1000000}\ncombat: {wreck_seconds: 1000000, scan_every: 1000000}\n"}) {
    const Result<Scenario> r = parseScenario(scenario(extra, kGroup), kTestInputFile);
    ASSERT_TRUE(r.ok()) << r.error().describe();
    EXPECT_EQ(problemWith(r.value().settings), "");
    ScenarioRun run(r.value());
    run.step();
    EXPECT_EQ(run.world().tick(), 1);
  }
}

}  // namespace
}  // namespace warpath::engine
