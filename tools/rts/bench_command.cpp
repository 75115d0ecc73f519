// `rts bench scen`: run every query of a MovingAI .scen file and summarise quality and speed.

#include <fmt/core.h>
#include <fmt/os.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/annotated_grid.h"
#include "pathing/map_io.h"
#include "rts/cli_support.h"
#include "rts/commands.h"

namespace warpath::tools {
namespace {

using namespace pathing;

// A query counts as optimal when its cost is within this of the scen file's length; the
// files print lengths to 2 decimals or ~6 significant digits.
constexpr double kOptimalTolerance = 0.01;

struct ScenBenchOptions {
  std::string mapFile;
  std::string scenFile;
  std::string algo = "aa";
  bool json = false;
  bool checkOptimal = false;
  std::string rowsFile;
};

struct QueryRow {
  const ScenQuery* query;
  PathResult result;
};

// Nearest-rank percentile of an unsorted sample (copied, so the caller's order is kept).
double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const std::size_t rank =
      static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  const std::size_t index = rank == 0 ? 0 : rank - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

int runScenBench(const ScenBenchOptions& options) {
  auto scen = loadScen(options.scenFile);
  if (!scen) throw BadInput{scen.error().describe()};
  const std::vector<ScenQuery>& queries = scen.value();
  const AnnotatedGrid grid(loadMapOrThrow(options.mapFile));
  if (auto mismatch = checkScenAgainstMap(queries, grid.map(), options.scenFile)) {
    throw BadInput{mismatch->describe()};
  }

  // MovingAI semantics: size 1, capability = the start cell's movement class.
  const auto agentFor = [&](const ScenQuery& q) {
    return Agent{1, movingAiClassOf(grid.map().at(q.start))};
  };
  // Preprocessing = every annotation the queries will need, built before timing them.
  const auto preprocessBegan = std::chrono::steady_clock::now();
  for (const ScenQuery& q : queries) {
    const Agent agent = agentFor(q);
    if (!agent.capability.empty()) grid.layer(agent);
  }
  const double preprocessMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - preprocessBegan)
          .count();

  AnnotatedAStar search(grid);
  std::vector<QueryRow> rows;
  rows.reserve(queries.size());
  for (const ScenQuery& q : queries) {
    rows.push_back({&q, search.findPath(agentFor(q), q.start, q.goal, nullptr)});
  }

  std::size_t solved = 0, unreachable = 0, optimalMatches = 0, suboptimalCount = 0;
  double maxAbsError = 0.0, sumSuboptimalityPct = 0.0, maxSuboptimalityPct = 0.0;
  double totalMicroseconds = 0.0;
  std::uint64_t totalExpanded = 0;
  std::vector<double> micros;
  std::vector<const QueryRow*> mismatches;
  for (const QueryRow& row : rows) {
    const PathResult& r = row.result;
    micros.push_back(r.metrics.microseconds);
    totalMicroseconds += r.metrics.microseconds;
    totalExpanded += r.metrics.expanded;
    if (!r.found()) {
      ++unreachable;
      mismatches.push_back(&row);
      continue;
    }
    ++solved;
    const double optimal = row.query->optimalLength;
    const double error = std::abs(r.cost - optimal);
    maxAbsError = std::max(maxAbsError, error);
    if (error <= kOptimalTolerance) {
      ++optimalMatches;
    } else {
      mismatches.push_back(&row);
    }
    if (optimal > 0.0) {
      const double pct = 100.0 * (r.cost - optimal) / optimal;
      sumSuboptimalityPct += pct;
      maxSuboptimalityPct = std::max(maxSuboptimalityPct, pct);
      ++suboptimalCount;
    }
  }

  const double searchSeconds = totalMicroseconds / 1e6;
  nlohmann::json out;
  out["map"] = options.mapFile;
  out["scen"] = options.scenFile;
  out["algo"] = options.algo;
  out["queries"] = queries.size();
  out["solved"] = solved;
  out["unreachable"] = unreachable;
  out["optimal_matches"] = optimalMatches;
  out["max_abs_error"] = maxAbsError;
  out["mean_suboptimality_pct"] =
      suboptimalCount ? sumSuboptimalityPct / static_cast<double>(suboptimalCount) : 0.0;
  out["max_suboptimality_pct"] = maxSuboptimalityPct;
  out["median_us"] = percentile(micros, 0.5);
  out["p95_us"] = percentile(micros, 0.95);
  out["mean_us"] = micros.empty() ? 0.0 : totalMicroseconds / static_cast<double>(micros.size());
  out["mean_expanded"] =
      rows.empty() ? 0.0 : static_cast<double>(totalExpanded) / static_cast<double>(rows.size());
  out["total_expanded"] = totalExpanded;
  out["expanded_per_second"] =
      searchSeconds > 0.0 ? static_cast<double>(totalExpanded) / searchSeconds : 0.0;
  out["search_seconds"] = searchSeconds;
  out["preprocess_ms"] = preprocessMs;
  out["preprocess_bytes"] = grid.cacheBytes();
  out["abstract_nodes"] = 0;  // AA* searches the grid itself
  out["abstract_edges"] = 0;

  if (!options.rowsFile.empty()) {
    std::FILE* file = std::fopen(options.rowsFile.c_str(), "w");
    if (!file) throw BadInput{"--rows: cannot write " + options.rowsFile};
    fmt::print(file,
               "line\tbucket\tstart_x\tstart_y\tgoal_x\tgoal_y\toptimal\tstatus\tcost\t"
               "expanded\tgenerated\tmicroseconds\n");
    for (const QueryRow& row : rows) {
      const ScenQuery& q = *row.query;
      fmt::print(file, "{}\t{}\t{}\t{}\t{}\t{}\t{:.6f}\t{}\t{:.6f}\t{}\t{}\t{:.2f}\n", q.line,
                 q.bucket, q.start.x, q.start.y, q.goal.x, q.goal.y, q.optimalLength,
                 toString(row.result.status), row.result.cost, row.result.metrics.expanded,
                 row.result.metrics.generated, row.result.metrics.microseconds);
    }
    std::fclose(file);
  }

  if (options.json) {
    fmt::print("{}\n", out.dump());
  } else {
    for (const auto& [key, value] : out.items())
      fmt::print("{:<24}{}\n", key, value.dump());
  }
  if (options.checkOptimal && !mismatches.empty()) {
    for (std::size_t i = 0; i < mismatches.size() && i < 10; ++i) {
      const QueryRow& row = *mismatches[i];
      fmt::print(stderr, "{}:{}: {},{} -> {},{}: expected {:.4f}, got {} {:.4f}\n",
                 options.scenFile, row.query->line, row.query->start.x, row.query->start.y,
                 row.query->goal.x, row.query->goal.y, row.query->optimalLength,
                 toString(row.result.status), row.result.cost);
    }
    fmt::print(stderr, "rts: {} of {} queries did not match their optimal length\n",
               mismatches.size(), queries.size());
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace

void registerBenchCommand(CLI::App& app, CommandRunner& run) {
  CLI::App* bench = app.add_subcommand("bench", "Measure planners on benchmark queries.");
  bench->require_subcommand(1);

  auto options = std::make_shared<ScenBenchOptions>();
  CLI::App* scen = bench->add_subcommand(
      "scen",
      "Run every query of a MovingAI .scen file (size-1 agents whose capability is the start "
      "cell's class: {ground,swamp}, {water} or {trees}) and print quality and speed.\n"
      "Exit status: 0 done, 1 --check-optimal found a mismatch, 2 bad input.");
  scen->add_option("map", options->mapFile, "MovingAI .map file")->required();
  scen->add_option("scen", options->scenFile, "MovingAI .scen file for that map")->required();
  scen->add_option("--algo", options->algo, "planner: aa (Annotated A*)")
      ->check(CLI::IsMember({"aa"}))
      ->capture_default_str();
  scen->add_flag("--json", options->json, "print one JSON object");
  scen->add_flag("--check-optimal", options->checkOptimal,
                 "exit 1 unless every query matches its optimal length within 0.01");
  scen->add_option("--rows", options->rowsFile, "also write one tab-separated row per query here");
  scen->callback([&run, options] { run = [options] { return runScenBench(*options); }; });
}

}  // namespace warpath::tools
