// End-to-end checks of the `rts` program: exit codes, error messages, output contracts.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

const fs::path kFixtures = WARPATH_FIXTURES_DIR;

struct CommandRun {
  int exitCode = -1;
  std::string out;
  std::string err;
};

std::string readFile(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `rts` with a shell-quoted argument string; stdout and stderr are captured separately.
CommandRun rts(const std::string& args) {
  const fs::path dir = fs::temp_directory_path() / ("rts_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string command = std::string("'") + RTS_BINARY + "' " + args + " >'" +
                              (dir / "out").string() + "' 2>'" + (dir / "err").string() + "'";
  CommandRun run;
  const int status = std::system(command.c_str());
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = readFile(dir / "out");
  run.err = readFile(dir / "err");
  return run;
}

std::string fixture(const std::string& name) {
  return "'" + (kFixtures / name).string() + "'";
}

TEST(RtsCliTest, HelpExitsZeroAndListsSubcommands) {
  const CommandRun run = rts("--help");
  EXPECT_EQ(run.exitCode, 0);
  EXPECT_NE(run.out.find("path"), std::string::npos);
  EXPECT_NE(run.out.find("bench"), std::string::npos);
}

TEST(RtsCliTest, PathPrintsJsonWithLengthAndMetrics) {
  const CommandRun run = rts("path " + fixture("small.map") + " --from 0,0 --to 5,3 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["status"], "found");
  EXPECT_EQ(json["path"].front(), nlohmann::json::array({0, 0}));
  EXPECT_EQ(json["path"].back(), nlohmann::json::array({5, 3}));
  EXPECT_GT(json["length"].get<double>(), 5.0);
  EXPECT_GE(json["metrics"]["expanded"].get<int>(), 1);
}

TEST(RtsCliTest, PathWithoutRouteExitsOne) {
  // Water-only agent from ground: cannot stand at the start.
  const CommandRun run =
      rts("path " + fixture("small.map") + " --capability water --from 0,0 --to 5,0");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.out.find("invalid-start"), std::string::npos);
}

TEST(RtsCliTest, BadInputExitsTwoWithFileLineAndProblem) {
  CommandRun run = rts("path " + fixture("bad_row_length.map") + " --from 0,0 --to 1,1");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("bad_row_length.map:7: row y=2 has 5 characters, expected 6"),
            std::string::npos)
      << run.err;

  run = rts("path " + fixture("small.map") + " --from 0,0 --to 9,1");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("--to 9,1 is outside the map"), std::string::npos) << run.err;

  run = rts("path " + fixture("small.map") + " --from '0;0' --to 1,1");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("--from: expected X,Y"), std::string::npos) << run.err;

  run = rts("path " + fixture("small.map") + " --capability lava --from 0,0 --to 1,1");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("'lava' is not a traversable terrain"), std::string::npos) << run.err;

  run = rts("path " + fixture("missing.map") + " --from 0,0 --to 1,1");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("missing.map: cannot open file"), std::string::npos) << run.err;

  run = rts("path " + fixture("small.map") + " --size 0 --from 0,0 --to 1,1");
  EXPECT_EQ(run.exitCode, 2);

  run = rts("frobnicate");
  EXPECT_EQ(run.exitCode, 2);
}

TEST(RtsCliTest, BenchScenReportsTheContractKeys) {
  const CommandRun run = rts("bench scen " + fixture("small.map") + " " +
                             fixture("small.map.scen") + " --algo aa --json --check-optimal");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  for (const char* key : {"queries", "solved", "unreachable", "optimal_matches", "max_abs_error",
                          "mean_suboptimality_pct", "max_suboptimality_pct", "median_us", "p95_us",
                          "mean_expanded", "preprocess_ms", "abstract_nodes", "abstract_edges"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["queries"], 3);
  EXPECT_EQ(json["optimal_matches"], 3);
  EXPECT_EQ(json["unreachable"], 0);
}

TEST(RtsCliTest, BenchScenCheckOptimalFailsOnAWrongLength) {
  const fs::path scen = fs::temp_directory_path() / "rts_cli_wrong_length.scen";
  std::ofstream(scen) << "version 1\n0\tsmall.map\t6\t4\t0\t0\t1\t0\t1.5\n";
  const CommandRun run =
      rts("bench scen " + fixture("small.map") + " '" + scen.string() + "' --check-optimal");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find(":2: 0,0 -> 1,0: expected 1.5000, got found 1.0000"), std::string::npos)
      << run.err;
}

TEST(RtsCliTest, BenchScenRejectsAScenForAnotherMap) {
  CommandRun run = rts("bench scen " + fixture("small.map") + " " + fixture("wrong_size.map.scen"));
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("wrong_size.map.scen:3:"), std::string::npos) << run.err;

  run = rts("bench scen " + fixture("small.map") + " " + fixture("bad_coordinate.scen"));
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("bad_coordinate.scen:3:"), std::string::npos) << run.err;

  run = rts("bench scen " + fixture("small.map") + " " + fixture("small.map.scen") +
            " --algo dijkstra");
  EXPECT_EQ(run.exitCode, 2);
}

}  // namespace
