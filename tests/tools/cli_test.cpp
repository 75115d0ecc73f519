// End-to-end checks of the `rts` program: exit codes, error messages, output contracts.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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

// Runs `rts args` and checks that it is refused as bad input: exit 2, `message` on stderr.
void expectBadInput(const std::string& args, const std::string& message) {
  const CommandRun run = rts(args);
  EXPECT_EQ(run.exitCode, 2) << args;
  EXPECT_NE(run.err.find(message), std::string::npos) << args << "\n" << run.err;
}

// The keys DESIGN.md §5 promises in every bench report.
const char* const kContractKeys[] = {"queries",
                                     "solved",
                                     "unreachable",
                                     "optimal_matches",
                                     "max_abs_error",
                                     "mean_suboptimality_pct",
                                     "max_suboptimality_pct",
                                     "median_us",
                                     "p95_us",
                                     "mean_expanded",
                                     "preprocess_ms",
                                     "abstract_nodes",
                                     "abstract_edges"};

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

TEST(RtsCliTest, PathUnderTerrainCosts) {
  // Ground costs 2 a cell and nothing else is passable: the same route, twice the length.
  const CommandRun run =
      rts("path " + fixture("small.map") + " --from 0,0 --to 5,3 --json --costs " +
          fixture("costs_ground_2.txt"));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_DOUBLE_EQ(json["length"].get<double>(), 16.0);
  EXPECT_EQ(json["agent"]["capability"], "ground");
  expectBadInput(
      "path " + fixture("small.map") + " --from 0,0 --to 5,3 --costs " + fixture("small.map"),
      "small.map:1: expected one map character then its cost");
}

TEST(RtsCliTest, PathUnderTerrainCostsWithEveryPlanner) {
  // Ground at 2 a cell: every planner finds the ground route at twice its uniform length 8.
  for (const std::string algo : {"haa-hq", "haa-lq", "hybrid"}) {
    const CommandRun run =
        rts("path " + fixture("small.map") + " --from 0,0 --to 5,3 --json --cluster-size 4 " +
            "--algo " + algo + " --costs " + fixture("costs_ground_2.txt"));
    ASSERT_EQ(run.exitCode, 0) << algo << ": " << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_DOUBLE_EQ(json["length"].get<double>(), 16.0) << algo;
    EXPECT_GT(json["abstraction"]["abstract_nodes"].get<int>(), 0) << algo;
  }
  // Infantry's speeds on a map of every terrain: the hierarchical planners' paths cost at
  // least AA*'s optimum, in the same unit; --unit infantry plans the same as its cost table.
  for (const std::string size : {"1", "2"}) {
    const std::string query = "path " + fixture("terrain.map") + " --size " + size +
                              " --from 0,0 --to 46,38 --cluster-size 8 --json";
    const std::string costs = " --costs " + fixture("costs_infantry.txt");
    const CommandRun aa = rts(query + costs);
    ASSERT_EQ(aa.exitCode, 0) << aa.err;
    const double optimum = nlohmann::json::parse(aa.out)["length"].get<double>();
    for (const std::string algo : {"haa-hq", "haa-lq", "hybrid"}) {
      const CommandRun run = rts(query + costs + " --algo " + algo);
      ASSERT_EQ(run.exitCode, 0) << algo << ": " << run.err;
      const auto json = nlohmann::json::parse(run.out);
      EXPECT_EQ(json["status"], "found");
      EXPECT_EQ(json["costs"], (kFixtures / "costs_infantry.txt").string());
      EXPECT_EQ(json["agent"]["capability"], "ground,swamp,trees");
      EXPECT_EQ(json["path"].front(), nlohmann::json::array({0, 0}));
      EXPECT_EQ(json["path"].back(), nlohmann::json::array({46, 38}));
      EXPECT_GE(json["length"].get<double>(), optimum - 1e-9) << algo << " size " << size;
      // Within the detours HAA* may take; the uniform length (about 1.5x) would be far above.
      EXPECT_LT(json["length"].get<double>(), optimum * 1.25) << algo << " size " << size;
      if (algo == "haa-hq") {
        const CommandRun unit = rts(query + " --unit infantry --algo haa-hq");
        ASSERT_EQ(unit.exitCode, 0) << unit.err;
        const auto byUnit = nlohmann::json::parse(unit.out);
        if (size == "1") {  // infantry is size 1
          EXPECT_NEAR(byUnit["length"].get<double>(), json["length"].get<double>(), 1e-9);
          EXPECT_EQ(byUnit["path"], json["path"]);
        }
      }
    }
  }
}

TEST(RtsCliTest, PathForACatalogueUnit) {
  // Infantry: size 1 on ground, swamp and trees at 1.5, 0.8 and 1.0 cells/s: the same route
  // and cost as the cost table that says so.
  const std::string query = "path " + fixture("small.map") + " --from 0,0 --to 5,3 --json";
  const CommandRun unit = rts(query + " --unit infantry");
  ASSERT_EQ(unit.exitCode, 0) << unit.err;
  const CommandRun table = rts(query + " --costs " + fixture("costs_infantry.txt"));
  ASSERT_EQ(table.exitCode, 0) << table.err;
  const auto a = nlohmann::json::parse(unit.out);
  const auto b = nlohmann::json::parse(table.out);
  EXPECT_NEAR(a["length"].get<double>(), b["length"].get<double>(), 1e-9);
  EXPECT_EQ(a["path"], b["path"]);
  EXPECT_EQ(a["agent"]["capability"], "ground,swamp,trees");
  expectBadInput(query + " --unit bogus", "--unit: no type 'bogus'");
}

TEST(RtsCliTest, BenchScenUnderTerrainCosts) {
  // The scen's optimal lengths are the weighted costs: they match under --costs only.
  const std::string args = "bench scen " + fixture("small.map") + " " +
                           fixture("small_costs_ground_2.scen") + " --json --check-optimal";
  const CommandRun weighted = rts(args + " --costs " + fixture("costs_ground_2.txt"));
  ASSERT_EQ(weighted.exitCode, 0) << weighted.err;
  const auto json = nlohmann::json::parse(weighted.out);
  EXPECT_EQ(json["optimal_matches"], 2);
  EXPECT_EQ(json["queries"], 2);
  EXPECT_EQ(rts(args).exitCode, 1);
}

TEST(RtsCliTest, BenchScenUnderTerrainCostsWithEveryPlanner) {
  // The small fixture: every planner matches both weighted optima.
  for (const std::string algo : {"aa", "haa-hq", "haa-lq", "hybrid"}) {
    const CommandRun run =
        rts("bench scen " + fixture("small.map") + " " + fixture("small_costs_ground_2.scen") +
            " --json --check-optimal " + "--cluster-size 4 --algo " + algo + " --costs " +
            fixture("costs_ground_2.txt"));
    ASSERT_EQ(run.exitCode, 0) << algo << ": " << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["algo"], algo);
    EXPECT_EQ(json["solved"], 2);
    EXPECT_EQ(json["optimal_matches"], 2) << algo;
  }
  // Infantry's speeds on a map of every terrain (optima from weighted AA*): AA* matches every
  // one; the hierarchical planners solve every query, never below the weighted optimum and
  // close to it (against the uniform model they would be some 50% off).
  const std::string args = "bench scen " + fixture("terrain.map") + " " +
                           fixture("terrain_costs_infantry.scen") + " --json --cluster-size 8 " +
                           "--costs " + fixture("costs_infantry.txt") + " --algo ";
  const CommandRun aa = rts(args + "aa --check-optimal");
  ASSERT_EQ(aa.exitCode, 0) << aa.err;
  EXPECT_EQ(nlohmann::json::parse(aa.out)["optimal_matches"], 12);
  for (const std::string algo : {"haa-hq", "haa-lq", "hybrid"}) {
    const CommandRun run = rts(args + algo);
    ASSERT_EQ(run.exitCode, 0) << algo << ": " << run.err;
    const auto json = nlohmann::json::parse(run.out);
    for (const char* key : kContractKeys)
      EXPECT_TRUE(json.contains(key)) << key;
    EXPECT_EQ(json["costs"], (kFixtures / "costs_infantry.txt").string());
    EXPECT_EQ(json["queries"], 12);
    EXPECT_EQ(json["solved"], 12) << algo;
    EXPECT_GE(json["optimal_matches"].get<int>(), 3) << algo;
    EXPECT_LE(json["optimal_matches"].get<int>(), 12) << algo;
    EXPECT_GE(json["mean_suboptimality_pct"].get<double>(), 0.0) << algo;
    EXPECT_LT(json["mean_suboptimality_pct"].get<double>(), 10.0) << algo;
    EXPECT_GT(json["abstract_nodes"].get<int>(), 0) << algo;
  }
}

TEST(RtsCliTest, PathWithoutRouteExitsOne) {
  // Water-only agent from ground: cannot stand at the start.
  const CommandRun run =
      rts("path " + fixture("small.map") + " --capability water --from 0,0 --to 5,0");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.out.find("invalid-start"), std::string::npos);
}

TEST(RtsCliTest, BadInputExitsTwoWithFileLineAndProblem) {
  expectBadInput("path " + fixture("bad_row_length.map") + " --from 0,0 --to 1,1",
                 "bad_row_length.map:7: row y=2 has 5 characters, expected 6");
  expectBadInput("path " + fixture("small.map") + " --from 0,0 --to 9,1",
                 "--to 9,1 is outside the map");
  expectBadInput("path " + fixture("small.map") + " --from '0;0' --to 1,1", "--from: expected X,Y");
  expectBadInput("path " + fixture("small.map") + " --capability lava --from 0,0 --to 1,1",
                 "'lava' is not a traversable terrain");
  expectBadInput("path " + fixture("missing.map") + " --from 0,0 --to 1,1",
                 "missing.map: no such file");
  EXPECT_EQ(rts("path " + fixture("small.map") + " --size 0 --from 0,0 --to 1,1").exitCode, 2);
  EXPECT_EQ(rts("frobnicate").exitCode, 2);
}

TEST(RtsCliTest, BenchScenReportsTheContractKeys) {
  const CommandRun run = rts("bench scen " + fixture("small.map") + " " +
                             fixture("small.map.scen") + " --algo aa --json --check-optimal");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  for (const char* key : kContractKeys)
    EXPECT_TRUE(json.contains(key)) << key;
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

TEST(RtsCliTest, BenchScenRejectsBadInput) {
  const std::string small = "bench scen " + fixture("small.map") + " ";
  expectBadInput(small + fixture("wrong_size.map.scen"), "wrong_size.map.scen:3:");
  expectBadInput(small + fixture("bad_coordinate.scen"), "bad_coordinate.scen:3:");
  expectBadInput(small + fixture("small.map.scen") + " --algo dijkstra",
                 "--algo: unknown planner 'dijkstra'");
  expectBadInput(small + fixture("small.map.scen") + " --algo haa-hq --cluster-size 1",
                 "--cluster-size 1");
  expectBadInput(small + fixture("small.map.scen") + " --bucket-min 2", "--bucket-min 2: no query");
}

TEST(RtsCliTest, BenchScenRunsTheHierarchicalPlanners) {
  for (const std::string algo : {"haa-hq", "haa-lq", "hybrid"}) {
    const CommandRun run =
        rts("bench scen " + fixture("small.map") + " " + fixture("small.map.scen") + " --algo " +
            algo + " --cluster-size 4 --json");
    ASSERT_EQ(run.exitCode, 0) << algo << ": " << run.err;
    const auto json = nlohmann::json::parse(run.out);
    for (const char* key : kContractKeys)
      EXPECT_TRUE(json.contains(key)) << key;
    for (const char* key :
         {"abstract_inter_edges", "abstract_intra_edges", "abstraction_bytes", "cached_path_bytes",
          "mean_insertion_expanded", "mean_abstract_expanded", "mean_refinement_expanded",
          "grid_search_queries"}) {
      EXPECT_TRUE(json.contains(key)) << key;
    }
    EXPECT_EQ(json["algo"], algo);
    EXPECT_EQ(json["cluster_size"], 4);
    EXPECT_EQ(json["queries"], 3);
    EXPECT_EQ(json["solved"], 3);
    // Two clusters side by side: the border between them has entrances.
    EXPECT_GT(json["abstract_nodes"].get<int>(), 0);
    EXPECT_EQ(json["abstract_edges"].get<int>(),
              json["abstract_inter_edges"].get<int>() + json["abstract_intra_edges"].get<int>());
    EXPECT_GT(json["abstraction_build_ms"].get<double>(), 0.0);
  }
  // Built on several threads, the same graph (`--threads` only changes how fast).
  const auto graphOn = [&](int threads) {
    const CommandRun run =
        rts("bench scen " + fixture("small.map") + " " + fixture("small.map.scen") +
            " --algo haa-hq --cluster-size 2 " + "--json --threads " + std::to_string(threads));
    EXPECT_EQ(run.exitCode, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["build_threads"], threads);
    return std::tuple{json["abstract_nodes"].get<int>(), json["abstract_edges"].get<int>(),
                      json["cached_path_bytes"].get<int>(), json["total_expanded"].get<int>()};
  };
  EXPECT_EQ(graphOn(3), graphOn(1));
  expectBadInput("bench scen " + fixture("small.map") + " " + fixture("small.map.scen") +
                     " --algo haa-hq --threads 0",
                 "--threads");
}

TEST(RtsCliTest, BenchScenBucketMinKeepsTheLongQueries) {
  const CommandRun run = rts("bench scen " + fixture("small.map") + " " +
                             fixture("small.map.scen") + " --bucket-min 1 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["queries"], 1);
}

TEST(RtsCliTest, BenchRandomFindsNoCompletenessFailures) {
  for (const std::string algo : {"aa", "haa-hq", "haa-lq", "hybrid"}) {
    const std::string args = "bench random " + fixture("terrain.map") +
                             " --size 2 --capability ground,swamp --queries 150 --seed 5 --algo " +
                             algo + " --cluster-size 8 --json";
    const CommandRun run = rts(args);
    ASSERT_EQ(run.exitCode, 0) << algo << ": " << run.err;
    const auto json = nlohmann::json::parse(run.out);
    for (const char* key : kContractKeys)
      EXPECT_TRUE(json.contains(key)) << key;
    EXPECT_EQ(json["algo"], algo);
    EXPECT_EQ(json["queries"], 150);
    EXPECT_EQ(json["completeness_failures"], 0);
    EXPECT_EQ(json["illegal_paths"], 0);
    EXPECT_EQ(json["cheaper_than_optimal"], 0);
    // Random standable pairs on a multi-terrain map: some connect, some do not.
    EXPECT_GT(json["solved"].get<int>(), 50);
    EXPECT_GT(json["unreachable"].get<int>(), 0);
    if (algo == "aa") {
      EXPECT_EQ(json["optimal_matches"], json["solved"]);
      EXPECT_EQ(json["abstract_nodes"], 0);
    } else {
      EXPECT_GT(json["abstract_nodes"].get<int>(), 0);
    }
    // The queries and answers (not the timings) repeat exactly.
    const auto again = nlohmann::json::parse(rts(args).out);
    for (const char* key : {"solved", "optimal_matches", "max_abs_error", "total_expanded"})
      EXPECT_EQ(json[key], again[key]) << key;
  }
}

TEST(RtsCliTest, BenchRandomUnderTerrainCosts) {
  const auto run = [](const std::string& algo, const std::string& costs) {
    const CommandRun r = rts("bench random " + fixture("terrain.map") +
                             " --size 2 --capability water --queries 150 --seed 5 --algo " + algo +
                             " --cluster-size 8 --json --costs " + fixture(costs));
    EXPECT_EQ(r.exitCode, 0) << algo << " " << costs << ": " << r.err;
    return nlohmann::json::parse(r.out);
  };
  for (const std::string algo : {"aa", "haa-hq", "haa-lq", "hybrid"}) {
    const auto json = run(algo, "costs_ground_2.txt");
    for (const char* key : kContractKeys)
      EXPECT_TRUE(json.contains(key)) << key;
    EXPECT_EQ(json["costs"], (kFixtures / "costs_ground_2.txt").string());
    // The agent moves on the terrains with a cost, whatever --capability says.
    EXPECT_EQ(json["agent"]["capability"], "ground");
    EXPECT_EQ(json["completeness_failures"], 0);
    EXPECT_EQ(json["illegal_paths"], 0);
    EXPECT_EQ(json["cheaper_than_optimal"], 0);
    EXPECT_GT(json["solved"].get<int>(), 50);
    if (algo == "aa") {
      EXPECT_EQ(json["optimal_matches"], json["solved"]);
      continue;
    }
    EXPECT_GT(json["abstract_nodes"].get<int>(), 0);
    // Costs twice as high: the same queries, paths and relative error, absolute errors twice
    // as large.
    const auto unit = run(algo, "costs_ground_1.txt");
    EXPECT_EQ(json["solved"], unit["solved"]);
    EXPECT_EQ(json["optimal_matches"], unit["optimal_matches"]);
    EXPECT_NEAR(json["mean_suboptimality_pct"].get<double>(),
                unit["mean_suboptimality_pct"].get<double>(), 1e-9);
    if (algo == "haa-hq") {
      EXPECT_GT(unit["max_abs_error"].get<double>(), 0.1);
    }
    EXPECT_NEAR(json["max_abs_error"].get<double>(), 2.0 * unit["max_abs_error"].get<double>(),
                1e-9)
        << algo;
  }
  const auto infantry = run("hybrid", "costs_infantry.txt");
  EXPECT_EQ(infantry["agent"]["capability"], "ground,swamp,trees");
  EXPECT_GE(infantry["mean_suboptimality_pct"].get<double>(), 0.0);
  EXPECT_LT(infantry["mean_suboptimality_pct"].get<double>(), 10.0);
}

TEST(RtsCliTest, BenchRandomRejectsBadInput) {
  const std::string random = "bench random " + fixture("terrain.map");
  expectBadInput(random + " --algo astar", "--algo: unknown planner 'astar'");
  expectBadInput(random + " --algo hybrid --attempt jps", "--attempt: unknown 'jps' (choose");
  expectBadInput(random + " --algo haa-lq --cluster-size 1", "clusterSize must be 2..4096 (got 1)");
  expectBadInput(random + " --size 30 --capability water", "can stand nowhere");
  expectBadInput("bench random " + fixture("missing.map"), "missing.map: no such file");
}

TEST(RtsCliTest, BenchPaperPrintsItsTables) {
  CommandRun run = rts("bench paper " + fixture("terrain.map") +
                       " --queries 10 --percents 0,20 --cluster-sizes 8 --markdown");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("| map | trees % | cluster | quality | grid nodes |"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("| map | trees % | cluster | quality | mean error % |"), std::string::npos)
      << run.out;
  // One row per map x share x cluster size x quality in each table.
  for (const char* row : {"| terrain | 0 | 8 | HQ |", "| terrain | 0 | 8 | LQ |",
                          "| terrain | 20 | 8 | HQ |", "| terrain | 20 | 8 | LQ |"}) {
    const std::size_t first = run.out.find(row);
    ASSERT_NE(first, std::string::npos) << row;
    EXPECT_NE(run.out.find(row, first + 1), std::string::npos) << row;
  }

  run = rts("bench paper " + fixture("terrain.map") + " " + fixture("small.map") +
            " --queries 10 --percents 10 --cluster-sizes 4,8");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  ASSERT_EQ(json["rows"].size(), 8u);  // 2 maps x 1 share x 2 cluster sizes x 2 qualities
  for (const auto& row : json["rows"]) {
    EXPECT_EQ(row["queries"], 10);
    EXPECT_EQ(row["solved"], 10);
    EXPECT_EQ(row["failures"], 0);
    EXPECT_GE(row["mean_error_pct"].get<double>(), 0.0);
    EXPECT_GT(row["grid_nodes"].get<int>(), 0);
  }
}

TEST(RtsCliTest, BenchPaperUnderTerrainCosts) {
  const std::string paper =
      "bench paper " + fixture("terrain.map") + " --queries 10 --percents 0,20 --cluster-sizes 8";
  // Infantry prices ground and trees: every agent kind takes part, each on its own graph.
  CommandRun run = rts(paper + " --costs " + fixture("costs_infantry.txt"));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["costs"], (kFixtures / "costs_infantry.txt").string());
  EXPECT_EQ(json["capabilities"], nlohmann::json::array({"ground", "trees", "ground,trees"}));
  ASSERT_EQ(json["rows"].size(), 4u);  // 2 shares x 1 cluster size x 2 qualities
  for (const auto& row : json["rows"]) {
    EXPECT_EQ(row["solved"], 10);
    EXPECT_EQ(row["failures"], 0);
    EXPECT_GT(row["graphs"].get<int>(), 1);
    EXPECT_LE(row["graphs"].get<int>(), 6);
    EXPECT_GE(row["mean_error_pct"].get<double>(), 0.0);
  }
  // Ground at 2 a cell prices {ground} only: those agents alone, errors against the weighted
  // optimum (against the uniform one they would be 100%).
  run = rts(paper + " --costs " + fixture("costs_ground_2.txt"));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["capabilities"], nlohmann::json::array({"ground"}));
  for (const auto& row : json["rows"]) {
    EXPECT_EQ(row["solved"], 10);
    EXPECT_EQ(row["failures"], 0);
    EXPECT_LE(row["graphs"].get<int>(), 2);
    EXPECT_GE(row["mean_error_pct"].get<double>(), 0.0);
    EXPECT_LT(row["mean_error_pct"].get<double>(), 20.0);
  }
  run = rts(paper + " --markdown --costs " + fixture("costs_ground_2.txt"));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("capability {ground}, start and goal"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("every agent moves by the terrain costs of " +
                         (kFixtures / "costs_ground_2.txt").string()),
            std::string::npos)
      << run.out;
  expectBadInput(paper + " --costs " + fixture("costs_water.txt"),
                 "prices none of the experiment's capabilities");
}

TEST(RtsCliTest, BenchPaperRejectsBadInput) {
  const std::string paper = "bench paper " + fixture("terrain.map") + " --queries 5";
  expectBadInput(paper + " --percents 0,x", "--percents: expected comma-separated whole numbers");
  expectBadInput(paper + " --percents 150", "--percents: 150 is not in 0..100");
  expectBadInput(paper + " --cluster-sizes 1",
                 "--cluster-sizes: 1: clusterSize must be 2..4096 (got 1)");
  expectBadInput(paper + " --cluster-sizes 10,0",
                 "--cluster-sizes: 0: clusterSize must be 2..4096 (got 0)");
}

// Files that cannot be maps are refused at once, naming the file and the problem. Before,
// `rts path /dev/zero` read until it had grown past 4 GB.
TEST(RtsCliTest, SpecialFilesDirectoriesAndHugeFilesAreRefusedQuickly) {
  const fs::path dir = fs::temp_directory_path() / ("rts_cli_huge_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path huge = dir / "huge.map";
  { std::ofstream create(huge); }
  fs::resize_file(huge, std::uintmax_t{2} << 30);  // 2 GiB of zeros, sparse: no disk used
  const fs::path scen = dir / "huge.scen";
  { std::ofstream create(scen); }
  fs::resize_file(scen, std::uintmax_t{100} << 20);
  const std::string path = " --from 0,0 --to 1,1";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"path /dev/zero" + path, "/dev/zero: not a regular file"},
      {"path '" + dir.string() + "'" + path, dir.string() + ": is a directory"},
      {"path '" + huge.string() + "'" + path,
       huge.string() + ": larger than the 64 MiB limit for maps"},
      {"bench scen " + fixture("small.map") + " '" + scen.string() + "'",
       scen.string() + ": larger than the 64 MiB limit for scen files"},
      {"bench scen " + fixture("small.map") + " /dev/zero", "/dev/zero: not a regular file"},
      {"bench random /dev/zero", "/dev/zero: not a regular file"},
  };
  for (const auto& [args, message] : cases) {
    const auto began = std::chrono::steady_clock::now();
    expectBadInput(args, "rts: error: " + message);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    EXPECT_LT(seconds, 5.0) << args;  // in practice a few milliseconds
  }
  fs::remove_all(dir);
}

TEST(RtsCliTest, PathWithTheHierarchicalPlanners) {
  for (const std::string algo : {"haa-hq", "haa-lq", "hybrid"}) {
    const CommandRun run = rts("path " + fixture("terrain.map") +
                               " --size 2 --capability ground,swamp --from 0,0 --to 46,38 "
                               "--cluster-size 8 --json --algo " +
                               algo);
    ASSERT_EQ(run.exitCode, 0) << algo << ": " << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["algo"], algo);
    EXPECT_EQ(json["status"], "found");
    EXPECT_EQ(json["path"].front(), nlohmann::json::array({0, 0}));
    EXPECT_EQ(json["path"].back(), nlohmann::json::array({46, 38}));
    for (const char* key : {"insertion_expanded", "abstract_expanded", "refinement_expanded",
                            "used_grid_search", "preprocess_ms"}) {
      EXPECT_TRUE(json["metrics"].contains(key)) << key;
    }
    EXPECT_GT(json["abstraction"]["abstract_nodes"].get<int>(), 0);
  }
  const CommandRun text = rts("path " + fixture("terrain.map") +
                              " --capability ground,swamp --from 0,0 --to 46,38 --algo haa-hq");
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_NE(text.out.find("phases    insertion"), std::string::npos) << text.out;

  const std::string small = "path " + fixture("small.map") + " --from 0,0 --to 5,3";
  expectBadInput(small + " --algo nope", "--algo: unknown planner 'nope'");
  expectBadInput(small + " --algo haa-hq --cluster-size 1", "--cluster-size 1");
}

}  // namespace
