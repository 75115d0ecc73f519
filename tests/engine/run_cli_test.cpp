// `rts run` and `rts test` end to end: exit codes, error messages, the report.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/rts_process.h"
#include "support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using Result = warpath::testing::RtsResult;
using warpath::testing::rts;

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
  const Result r = rts("run " + file + " --report " + report);
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
  const Result r = rts("run " + file);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL (0)"), std::string::npos) << r.out;
}

TEST_F(RunCli, UntilStopsEarlyWithAPartialReport) {
  const std::string file = write("ok.yaml", "  - max_stuck: 0\n");
  const std::string report = (dir_ / "report.json").string();
  const Result r = rts("run " + file + " --until 15 --quiet --report " + report);
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
  const Result r = rts("run " + file + " --report " + (dir_ / "plain" / "r.json").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out.find("tick"), std::string::npos) << "the run started: " << r.out;
}

TEST_F(RunCli, BadInputExitsTwoNamingFileLineColumn) {
  const std::string file =
      write("bad.yaml", "  - arrival_rate: {team: green, type: infantry, at_least: 1, by: 1}\n");
  const Result r = rts("run " + file);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(file + ":8:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("unknown team 'green'"), std::string::npos) << r.out;
  EXPECT_EQ(rts("run " + (dir_ / "missing.yaml").string()).status, 2);
}

TEST_F(RunCli, TestCommandCountsPassesAndFailures) {
  write("a.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 20}\n");
  write("b.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 1}\n");
  const Result r = rts("test " + dir_.string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("PASS " + (dir_ / "a.yaml").string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL " + (dir_ / "b.yaml").string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 passed, 1 failed\n"), std::string::npos) << r.out;
}

}  // namespace
