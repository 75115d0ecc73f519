// `rts run` and `rts test` end to end: exit codes, error messages, the report.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/rts_process.h"
#include "support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using warpath::testing::rts;
using warpath::testing::RtsResult;

class RunCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = warpath::testing::freshTestDir("warpath_run_cli_"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& expectations,
                    const std::string& extra = "") {
    const fs::path file = dir_ / name;
    std::ofstream(file) << "map: {rows: ['..........', '..........', '..........']}\n"
                           "catalogue: " WARPATH_SOURCE_DIR
                           "/assets/units.yaml\n"
                           "duration: 20\n"
                           "teams: [blue]\n"
                        << extra
                        << "groups:\n"
                           "  - {name: g, team: blue, type: infantry, count: 3,"
                           " spawn: {x: 0, y: 0, w: 2, h: 3}, goal: {x: 7, y: 0, w: 3, h: 3}}\n"
                           "expectations:\n"
                        << expectations;
    return file.string();
  }
  fs::path dir_;
};

TEST_F(RunCli, PassingScenarioExitsZeroAndWritesTheReport) {
  const std::string file =
      write("ok.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 20}\n");
  const std::string report = (dir_ / "report.json").string();
  const RtsResult r = rts("run " + file + " --report " + report);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("PASS"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
  for (const char* key : {"scenario", "seed", "ticks", "sim_seconds", "wall_seconds", "state_hash",
                          "arrivals", "deaths", "stuck_units", "pathing", "expectations", "timing"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["ticks"], 600);
  EXPECT_EQ(j["arrivals"][0]["arrived"], 3);
  EXPECT_EQ(j["expectations"][0]["pass"], true);
  EXPECT_EQ(j["expectations"][0]["actual"], 1.0);
  EXPECT_GE(j["pathing"]["requests"].get<int>(), 3);
}

TEST_F(RunCli, FailingExpectationExitsOne) {
  const std::string file =
      write("slow.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 1}\n");
  const std::string report = (dir_ / "report.json").string();
  const RtsResult r = rts("run " + file + " --report " + report);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL (0)"), std::string::npos) << r.out;
  // The units it counts against, each with where it got to: here all three, arrived later.
  for (const char* unit : {"0", "1", "2"})
    EXPECT_NE(r.out.find(std::string("\n  unit ") + unit + " (blue infantry): arrived at "),
              std::string::npos)
        << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(j["expectations"][0]["units"], nlohmann::json::array({0, 1, 2}));
  // Stopped before any arrived, each is named with its place and distance from its goal area.
  const RtsResult early = rts("run " + file + " --until 30");
  EXPECT_EQ(early.status, 1) << early.out;
  EXPECT_NE(early.out.find("\n  unit 0 (blue infantry): not arrived, at ("), std::string::npos)
      << early.out;
  EXPECT_NE(early.out.find(" cells from its goal area\n"), std::string::npos) << early.out;
}

TEST_F(RunCli, UntilStopsEarlyWithAPartialReport) {
  const std::string file = write("ok.yaml", "  - max_stuck: 0\n");
  const std::string report = (dir_ / "report.json").string();
  const RtsResult r = rts("run " + file + " --until 15 --quiet --report " + report);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "");
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(j["ticks"], 15);
  EXPECT_EQ(j["complete"], false);
}

TEST_F(RunCli, ReportFolderIsCreatedOrRefusedBeforeTheRun) {
  const std::string file = write("ok.yaml", "  - max_stuck: 0\n");
  const fs::path nested = dir_ / "out" / "demo" / "report.json";
  EXPECT_EQ(rts("run " + file + " --quiet --report " + nested.string()).status, 0);
  EXPECT_TRUE(fs::exists(nested));
  // A folder that cannot be made (a file stands in the way) is bad input, found up front.
  std::ofstream(dir_ / "plain") << "x";
  const RtsResult r = rts("run " + file + " --report " + (dir_ / "plain" / "r.json").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out.find("tick"), std::string::npos) << "the run started: " << r.out;
}

// --trace: a CSV row per traced unit every N ticks, from tick 0, with the header naming the
// columns; the units move east toward their goal between rows.
TEST_F(RunCli, TraceWritesTheChosenUnitsStateEveryNTicks) {
  const std::string file = write("ok.yaml", "  - max_stuck: 0\n");
  const fs::path trace = dir_ / "traces" / "t.csv";
  const RtsResult r = rts("run " + file + " --quiet --until 60 --trace " + trace.string() +
                          " --trace-every 30 --trace-units 0,2");
  EXPECT_EQ(r.status, 0) << r.out;
  std::ifstream in(trace);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line.rfind("tick,unit,team,type,x,y,vx,vy,state,waypoint,path_cells,", 0), 0u) << line;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::size_t from = 0;
    for (std::size_t comma; (comma = line.find(',', from)) != std::string::npos; from = comma + 1)
      cells.push_back(line.substr(from, comma - from));
    cells.push_back(line.substr(from));
    EXPECT_EQ(cells.size(), 24u) << line;
    rows.push_back(std::move(cells));
  }
  ASSERT_EQ(rows.size(), 6u);  // ticks 0, 30 and 60, units 0 and 2
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][0], std::to_string(30 * (i / 2)));
    EXPECT_EQ(rows[i][1], i % 2 == 0 ? "0" : "2");
    EXPECT_EQ(rows[i][2], "blue");
    EXPECT_EQ(rows[i][3], "infantry");
  }
  EXPECT_EQ(rows[0][8], "idle");  // before its first tick the order waits for a path
  EXPECT_EQ(rows[4][8], "moving");
  EXPECT_GT(std::stod(rows[4][4]), std::stod(rows[0][4]));  // x grew: it went east
  // Its waypoint (columns 22, 23) lies ahead of it, east, within a few cells; none before a path.
  EXPECT_EQ(rows[0][22], "nan");
  EXPECT_GT(std::stod(rows[4][22]), std::stod(rows[4][4]) - 0.5);
  EXPECT_LT(std::stod(rows[4][22]), std::stod(rows[4][4]) + 3.0);
  // A trace every 0 ticks is refused before the run.
  EXPECT_EQ(rts("run " + file + " --quiet --trace " + trace.string() + " --trace-every 0").status,
            2);
}

TEST_F(RunCli, BadInputExitsTwoNamingFileLineColumn) {
  const std::string file =
      write("bad.yaml", "  - arrival_rate: {team: green, type: infantry, at_least: 1, by: 1}\n");
  const RtsResult r = rts("run " + file);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(file + ":8:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("unknown team 'green'"), std::string::npos) << r.out;
  EXPECT_EQ(rts("run " + (dir_ / "missing.yaml").string()).status, 2);
}

TEST_F(RunCli, TestCommandCountsPassesAndFailures) {
  write("a.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 20}\n");
  write("b.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 1}\n");
  const RtsResult r = rts("test " + dir_.string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("PASS " + (dir_ / "a.yaml").string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL " + (dir_ / "b.yaml").string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("failed: actual 0 (units 0, 1, 2)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 passed, 1 failed\n"), std::string::npos) << r.out;
  // Each failed case ends with the command that traces the units it counts against; at the
  // file's own seed without --seed, at a seed of --seeds with it.
  EXPECT_NE(r.out.find("  trace: rts run "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("b.yaml --quiet --trace trace.csv --trace-units 0,1,2\n"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("a.yaml --quiet --trace"), std::string::npos) << r.out;
  const RtsResult seeded = rts("test " + (dir_ / "b.yaml").string() + " --seeds 5");
  EXPECT_NE(seeded.out.find("b.yaml --seed 5 --quiet --trace trace.csv --trace-units 0,1,2\n"),
            std::string::npos)
      << seeded.out;
}

// A battle: the run ends when the victory condition is met; the report holds the statistics
// per (team, type), the winner, the condition, the tick and the triggers fired; the console
// names the winner and each team's losses.
TEST_F(RunCli, ABattleEndsAtItsVictoryAndReportsTheOutcome) {
  const fs::path file = dir_ / "duel.yaml";
  std::ofstream(file) << "map: {rows: ['............', '............', '............']}\n"
                         "unit_types:\n"
                         "  vet: {size: 1, capability: [ground], speed: 2, hp: 40,\n"
                         "        weapon: {kind: rifle, damage: 10, range: 5, cooldown: 1}}\n"
                         "  recruit: {size: 1, capability: [ground], speed: 2, hp: 30,\n"
                         "            weapon: {kind: rifle, damage: 10, range: 5, cooldown: 1}}\n"
                         "duration: 20\n"
                         "teams: [blue, red]\n"
                         "groups:\n"
                         "  - {name: b, team: blue, type: vet, count: 1,"
                         " spawn: {x: 2, y: 1, w: 1, h: 1}}\n"
                         "  - {name: r, team: red, type: recruit, count: 1,"
                         " spawn: {x: 5, y: 1, w: 1, h: 1}}\n"
                         "triggers:\n"
                         "  - {name: dig in, when: {at: 1}, do: [{order: hold, group: b}]}\n"
                         "victory:\n  - eliminate: blue\n"
                         "expectations:\n"
                         "  - winner: blue\n"
                         "  - losses: {team: blue, at_most: 0}\n";
  const std::string report = (dir_ / "report.json").string();
  const RtsResult r = rts("run " + file.string() + " --report " + report);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("winner: blue (blue eliminates the others) at tick 91 (3.0 s)\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  blue: lost 0 of 1; 1 kills, 3 shots, 3 hits\n"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  red: lost 1 of 1 (recruit 1); 0 kills, 3 shots, 3 hits\n"),
            std::string::npos)
      << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(j["ticks"], 91);
  EXPECT_EQ(j["complete"], true);
  EXPECT_EQ(j["winner"], "blue");
  EXPECT_EQ(j["victory"], "blue eliminates the others");
  EXPECT_EQ(j["end_tick"], 91);
  EXPECT_EQ(j["triggers_fired"], nlohmann::json::array({"dig in"}));
  ASSERT_EQ(j["battle"].size(), 2u);
  const nlohmann::json& vet = j["battle"][0];
  EXPECT_EQ(vet["team"], "blue");
  EXPECT_EQ(vet["type"], "vet");
  for (const auto& [key, value] : std::vector<std::pair<std::string, int>>{{"units", 1},
                                                                           {"alive", 1},
                                                                           {"losses", 0},
                                                                           {"kills", 1},
                                                                           {"shots_fired", 3},
                                                                           {"hits", 3},
                                                                           {"damage_dealt", 30},
                                                                           {"damage_taken", 30}})
    EXPECT_EQ(vet[key], value) << key;
  EXPECT_EQ(j["battle"][1]["losses"], 1);
  EXPECT_EQ(j["expectations"][0]["actual"], 0);  // the winner's team index
  EXPECT_EQ(j["expectations"][1]["pass"], true);
  EXPECT_TRUE(j["timing"].contains("combat_ms"));

  // Stopped before the end: a partial report, no winner yet.
  const RtsResult early = rts("run " + file.string() + " --until 40 --quiet --report " + report);
  EXPECT_EQ(early.status, 1) << early.out;  // winner == blue does not hold yet
  const nlohmann::json p = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(p["ticks"], 40);
  EXPECT_EQ(p["complete"], false);
  EXPECT_TRUE(p["winner"].is_null());
  EXPECT_TRUE(p["victory"].is_null());
  EXPECT_TRUE(p["end_tick"].is_null());
  EXPECT_EQ(p["triggers_fired"], nlohmann::json::array({"dig in"}));  // at tick 30
  EXPECT_EQ(p["battle"][0]["shots_fired"], 1);

  // rts test names the winner.
  const RtsResult t = rts("test " + dir_.string());
  EXPECT_NE(t.out.find("PASS " + file.string() + " (2 units, 91 ticks, winner blue,"),
            std::string::npos)
      << t.out;
}

// A travel-only run (one team) prints no battle summary; its report has no winner.
TEST_F(RunCli, ATravelRunHasNoBattleSummary) {
  const std::string file = write("ok.yaml", "  - max_stuck: 0\n");
  const std::string report = (dir_ / "report.json").string();
  const RtsResult r = rts("run " + file + " --report " + report);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("winner:"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
  EXPECT_TRUE(j["winner"].is_null());
  EXPECT_TRUE(j["end_tick"].is_null());
  EXPECT_EQ(j["ticks"], 600);
  ASSERT_EQ(j["battle"].size(), 1u);
  EXPECT_EQ(j["battle"][0]["units"], 3);
  EXPECT_EQ(j["battle"][0]["alive"], 3);
}

// Bad input of every kind: exit 2 with the file and the problem, quickly (before, a directory
// aborted with exit 134, an alias bomb built an 8192x8192 map, `--until -1` printed a 300-digit
// range and `--until 99999999999999999999` was accepted).
TEST_F(RunCli, BadInputIsRefusedQuicklyNamingFileAndProblem) {
  const std::string ok = write("ok.yaml", "  - max_stuck: 0\n");
  std::string bomb = "map:\n  rows: [&r '" + std::string(8192, '.') + "'";
  for (int i = 0; i < 8191; ++i)
    bomb += ", *r";
  std::ofstream(dir_ / "bomb.yaml") << bomb << "]\nduration: 1\nteams: [a]\ngroups: []\n";
  std::ofstream(dir_ / "deep.yaml")
      << "expectations: " << std::string(5000, '[') << std::string(5000, ']') << "\n";
  std::ofstream(dir_ / "zero_map.yaml") << "map: /dev/zero\nduration: 1\nteams: [a]\n";
  const std::string bombFile = (dir_ / "bomb.yaml").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run /dev/zero", "rts: error: /dev/zero: not a regular file"},
      {"run " + dir_.string(), "rts: error: " + dir_.string() + ": is a directory"},
      {"run " + bombFile,
       "rts: error: " + bombFile +
           ":2:9: the inline map has 8192 rows of 8192 cells, more than the 1048576 cells "
           "allowed: give a .map file"},
      {"run " + (dir_ / "deep.yaml").string(),
       (dir_ / "deep.yaml").string() + ":1:"},  // then the column and the problem
      {"run " + (dir_ / "deep.yaml").string(), ": nesting deeper than 64 levels"},
      {"run " + (dir_ / "zero_map.yaml").string(),
       (dir_ / "zero_map.yaml").string() + ":1:6: map: /dev/zero: not a regular file"},
      {"run " + ok + " --until -1", "--until: must be a whole number between 0 and 1000000000"},
      {"run " + ok + " --until 99999999999999999999",
       "--until: must be a whole number between 0 and 1000000000, got '99999999999999999999'"},
      {"run " + ok + " --until 601",
       "--until: must be between 0 and 600 (the scenario's duration in ticks), got 601"},
      {"run " + ok + " --replay-every 0",
       "--replay-every: must be a whole number between 1 and 1000000000, got '0'"},
      {"run " + ok + " --frame-every 0", "--frame-every: must be a whole number between 1"},
      {"test /dev/zero", "/dev/zero"},
  };
  for (const auto& [args, message] : cases) {
    const auto began = std::chrono::steady_clock::now();
    const RtsResult r = rts(args);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << args << "\n" << r.out;
    EXPECT_EQ(r.out.find("179769313486231570814527423731704356798070567525844996598917476803157"),
              std::string::npos)
        << r.out;
    EXPECT_LT(seconds, 5.0) << args;  // in practice well under 0.1 s
  }
  // --until at the duration is fine.
  EXPECT_EQ(rts("run " + ok + " --until 600 --quiet").status, 0);
}

}  // namespace
