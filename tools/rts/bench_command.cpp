// `rts bench scen`: run every query of a MovingAI .scen file and summarise quality and speed.
// `rts bench random` and `rts bench paper` live in their own files.

#include <fmt/core.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/map_io.h"
#include "pathing/terrain_costs.h"
#include "rts/bench_support.h"
#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/planner_choice.h"

namespace warpath::tools {
namespace {

using namespace pathing;

struct ScenBenchOptions {
  std::string mapFile;
  std::string scenFile;
  PlannerChoice planner;
  int bucketMin = 0;
  bool json = false;
  bool checkOptimal = false;
  std::string rowsFile;
  std::string costsFile;  // empty: the uniform model
};

struct QueryRow {
  const ScenQuery* query;
  PathResult result;
};

void writeRows(const std::string& file, const std::vector<QueryRow>& rows) {
  std::FILE* out = std::fopen(file.c_str(), "w");
  if (!out) throw BadInput{"--rows: cannot write " + file};
  fmt::print(out,
             "line\tbucket\tstart_x\tstart_y\tgoal_x\tgoal_y\toptimal\tstatus\tcost\t"
             "expanded\tgenerated\tmicroseconds\tinsertion_expanded\tabstract_expanded\t"
             "refinement_expanded\tgrid_search\n");
  for (const QueryRow& row : rows) {
    const ScenQuery& q = *row.query;
    const SearchMetrics& m = row.result.metrics;
    fmt::print(out, "{}\t{}\t{}\t{}\t{}\t{}\t{:.6f}\t{}\t{:.6f}\t{}\t{}\t{:.2f}\t{}\t{}\t{}\t{}\n",
               q.line, q.bucket, q.start.x, q.start.y, q.goal.x, q.goal.y, q.optimalLength,
               toString(row.result.status), row.result.cost, m.expanded, m.generated,
               m.microseconds, m.insertionExpanded, m.abstractExpanded, m.refinementExpanded,
               m.usedGridSearch ? 1 : 0);
  }
  std::fclose(out);
}

int runScenBench(const ScenBenchOptions& options) {
  const Algorithm algorithm = parseAlgorithm(options.planner.algo);
  auto scen = loadScen(options.scenFile);
  if (!scen) throw BadInput{scen.error().describe()};
  const AnnotatedGrid grid(loadMapOrThrow(options.mapFile));
  if (const Status fits = checkScenAgainstMap(scen.value(), grid.map(), options.scenFile); !fits)
    throw BadInput{fits.error().describe()};
  std::vector<ScenQuery> queries;
  for (const ScenQuery& q : scen.value()) {
    if (q.bucket >= options.bucketMin) queries.push_back(q);
  }
  if (queries.empty() && !scen.value().empty()) {
    throw BadInput{fmt::format("--bucket-min {}: no query of {} has a bucket that large",
                               options.bucketMin, options.scenFile)};
  }

  // MovingAI semantics: size 1, capability = the start cell's movement class; under costs,
  // the terrains with a cost (warthog's semantics), and every algorithm plans under them (the
  // hierarchical ones on a graph for that one agent).
  const std::optional<TerrainCosts> costs = loadCostsOption(options.costsFile);
  const auto agentFor = [&](const ScenQuery& q) {
    return Agent{1, costs ? costs->capability() : movingAiClassOf(grid.map().at(q.start))};
  };
  // Preprocessing = every annotation the queries will need (and the abstraction serving their
  // classes), built before timing them.
  std::vector<Agent> agents;
  AbstractionNeeds needs{.capabilities = {}, .maxAgentSize = 1};
  for (const ScenQuery& q : queries) {
    const Agent agent = agentFor(q);
    if (agent.capability.empty()) continue;
    if (std::find(agents.begin(), agents.end(), agent) == agents.end()) agents.push_back(agent);
    needs.capabilities.push_back(agent.capability);
  }
  const PreparedPlanner prepared =
      costs ? prepareCostPlanner(grid, algorithm, options.planner, Agent{1, costs->capability()},
                                 *costs)
            : preparePlanner(grid, algorithm, options.planner, agents, std::move(needs));
  Planner planner = prepared.makePlanner(grid);
  const double preparedAgentsMs = prepareAgents(planner, agents);

  std::vector<QueryRow> rows;
  rows.reserve(queries.size());
  for (const ScenQuery& q : queries)
    rows.push_back({&q, planner.findPath(agentFor(q), q.start, q.goal, nullptr)});

  ResultTally tally;
  std::vector<const QueryRow*> mismatches;
  for (const QueryRow& row : rows) {
    tally.add(row.result, row.query->optimalLength);
    if (!row.result.found() ||
        std::abs(row.result.cost - row.query->optimalLength) > kOptimalTolerance) {
      mismatches.push_back(&row);
    }
  }

  nlohmann::json out;
  out["map"] = options.mapFile;
  out["scen"] = options.scenFile;
  out["algo"] = std::string(toString(algorithm));
  if (prepared.abstraction) out["cluster_size"] = options.planner.clusterSize;
  if (algorithm == Algorithm::Hybrid) {
    out["tau"] = options.planner.tau;
    out["attempt"] = options.planner.attempt;
  }
  out["bucket_min"] = options.bucketMin;
  out["costs"] = costs ? nlohmann::json(options.costsFile) : nlohmann::json(nullptr);
  tally.writeTo(out);
  out["preprocess_ms"] = prepared.preprocessMs + preparedAgentsMs;
  const ClusterAbstraction* abstraction = prepared.abstractionOrNull();
  out["preprocess_bytes"] =
      grid.cacheBytes() +
      (abstraction ? abstraction->stats().graphBytes + abstraction->stats().pathBytes : 0);
  writeAbstractionKeys(abstraction, out);
  if (prepared.abstraction) {
    out["insertion"] = options.planner.insertion;
    out["insertion_table_bytes"] = planner.insertionTableBytes();
  }
  // JPS and JPS+ keep per-layer bit maps (and tables), built at each layer's first query.
  if (const std::vector<LayerBytes> layers = planner.layerBytes(); !layers.empty()) {
    nlohmann::json perLayer = nlohmann::json::array();
    for (const LayerBytes& layer : layers)
      perLayer.push_back({{"agent", agentJson(layer.agent)}, {"bytes", layer.bytes}});
    out["layer_bytes"] = perLayer;
  }

  if (!options.rowsFile.empty()) writeRows(options.rowsFile, rows);
  printReport(out, options.json);
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

  auto [scen, options] = addSubcommand<ScenBenchOptions>(
      *bench, run, "scen",
      "Run every query of a MovingAI .scen file (size-1 agents whose capability is the start "
      "cell's class: {ground,swamp}, {water} or {trees}) and print quality and speed. The "
      "hierarchical planners' abstraction serves the classes of all start cells. With --costs, "
      "every query is for one size-1 agent whose capability is the terrains with a cost, every "
      "--algo plans under the costs (the hierarchical planners on one graph built for that "
      "agent), and the scen's optimal lengths are read as weighted optimal costs: "
      "optimal_matches and the error figures compare with them.\n"
      "Exit status: 0 done, 1 --check-optimal found a mismatch, 2 bad input.",
      runScenBench);
  scen->add_option("map", options->mapFile, "MovingAI .map file")->required();
  scen->add_option("scen", options->scenFile, "MovingAI .scen file for that map")->required();
  addPlannerOptions(*scen, options->planner);
  scen->add_option("--bucket-min", options->bucketMin,
                   "run only the queries whose bucket is at least this (e.g. 100: long queries)")
      ->capture_default_str();
  addCostsOption(*scen, options->costsFile);
  scen->add_flag("--json", options->json, "print one JSON object");
  scen->add_flag("--check-optimal", options->checkOptimal,
                 "exit 1 unless every query matches its optimal length within 0.01");
  scen->add_option("--rows", options->rowsFile, "also write one tab-separated row per query here");

  registerBenchRandomCommand(*bench, run);
  registerBenchPaperCommand(*bench, run);
  registerBenchMovementCommand(*bench, run);
}

}  // namespace warpath::tools
