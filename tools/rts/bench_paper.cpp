// `rts bench paper`: the experiment of the HAA* paper (Harabor & Botea 2008) on given maps.
// Each map is turned into derived maps with a share of its traversable cells made trees ("soft
// obstacles"); on each, agents of sizes 1 and 2 with capability {ground}, {trees} or
// {ground,trees} get random reachable queries, answered by AA* and by HAA* on the HQ and LQ
// graphs of every cluster size. Rows: map × share × cluster size × quality. With --costs every
// agent moves by the costs (those whose capability they do not price are left out): the
// optimum is weighted AA*, and HAA* uses one weighted graph per agent kind.

#include <fmt/core.h>

#include <algorithm>
#include <bit>
#include <deque>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/annotated_grid.h"
#include "pathing/haa_star.h"
#include "pathing/map_generator.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"
#include "rts/bench_support.h"
#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/planner_choice.h"

namespace warpath::tools {
namespace {

using namespace pathing;

struct PaperBenchOptions {
  std::vector<std::string> mapFiles;
  std::string percents = "0,10,20,30,40,50";
  std::string clusterSizes = "10,15,20";
  int queries = 200;
  std::uint64_t seed = 1;
  bool noSmooth = false;
  bool markdown = false;
  std::string costsFile;  // empty: the uniform model
};

const Capability kGround = Capability::of({Terrain::Ground});
const Capability kTrees = Capability::of({Terrain::Trees});
const Capability kGroundTrees = Capability::of({Terrain::Ground, Terrain::Trees});
constexpr int kMaxAgentSize = 2;

// The agent kinds of the experiment: sizes 1 and 2, each capability; under costs, only the
// capabilities whose every terrain has a cost (an agent moves by them on its own terrains).
std::vector<Agent> experimentAgents(const std::optional<TerrainCosts>& costs) {
  std::vector<Agent> agents;
  for (int size = 1; size <= kMaxAgentSize; ++size) {
    for (Capability c : {kGround, kTrees, kGroundTrees}) {
      if (!costs || c.isSubsetOf(costs->capability())) agents.push_back({size, c});
    }
  }
  return agents;
}

// The grid graph the abstraction is measured against (Table I): nodes are the traversable
// cells, edges the legal moves (undirected) of a size-1 agent that may stand on every terrain
// present, i.e. {ground,trees} on the derived maps.
std::pair<std::size_t, std::size_t> gridGraphSize(const AnnotatedGrid& grid) {
  std::size_t nodes = 0;
  for (Terrain t : grid.map().cells())
    nodes += isTraversable(t) ? 1 : 0;
  const Capability everything = grid.map().terrainsPresent();
  if (everything.empty()) return {nodes, 0};
  std::size_t directedMoves = 0;
  for (std::uint8_t mask : grid.layer({1, everything}).moveMasks())
    directedMoves += static_cast<std::size_t>(std::popcount(mask));
  return {nodes, directedMoves / 2};
}

AbstractionSpec experimentSpec(int clusterSize, AbstractionQuality quality) {
  return {.clusterSize = clusterSize,
          .maxAgentSize = kMaxAgentSize,
          .capabilities = {kGround, kTrees, kGroundTrees},
          .quality = quality,
          .cachePaths = true};
}

struct AgentQuery {
  std::size_t kind;  // index in the experiment's agents
  Agent agent;
  Query query;
  PathResult optimal;
};

// `count` queries, each for an agent kind drawn at random among those of `kinds` with a
// reachable pair, between two distinct mutually reachable cells.
std::vector<AgentQuery> drawQueries(const AnnotatedGrid& grid, const std::vector<Agent>& kinds,
                                    int count, std::uint64_t seed, const std::string& mapName,
                                    int percent) {
  std::vector<std::size_t> agents;
  std::vector<QuerySampler> samplers;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    QuerySampler sampler(grid, kinds[k]);
    if (!sampler.hasReachablePair()) continue;
    agents.push_back(k);
    samplers.push_back(std::move(sampler));
  }
  if (agents.empty()) {
    throw BadInput{
        fmt::format("{} with {}% trees: no agent of the experiment has two mutually "
                    "reachable cells",
                    mapName, percent)};
  }
  SplitMix64 rng(~seed);  // a stream apart from the one that derived the map
  std::vector<AgentQuery> queries;
  for (int i = 0; i < count; ++i) {
    const std::uint32_t drawn = rng.below(static_cast<std::uint32_t>(agents.size()));
    queries.push_back(
        {agents[drawn], kinds[agents[drawn]], samplers[drawn].reachablePair(rng), {}});
  }
  return queries;
}

struct Failures {
  std::size_t count = 0;
  std::vector<std::string> examples;
  void add(const std::string& what) {
    if (++count <= 10) examples.push_back(what);
  }
};

// The experiment on one derived map: its agent kinds and, under costs, what they move by.
struct Experiment {
  std::vector<Agent> kinds;
  std::optional<TerrainCosts> costs;
};

AbstractionStats& operator+=(AbstractionStats& sum, const AbstractionStats& more) {
  sum.clusters += more.clusters;
  sum.nodes += more.nodes;
  sum.interEdges += more.interEdges;
  sum.intraEdges += more.intraEdges;
  sum.graphBytes += more.graphBytes;
  sum.pathBytes += more.pathBytes;
  sum.buildMilliseconds += more.buildMilliseconds;
  return sum;
}

// One row: HAA* on the graphs of one cluster size and quality against the AA* answers of the
// same queries. One graph serves every agent kind; under costs, one weighted graph per kind
// that has queries (the row's graph figures are their sums).
nlohmann::json measureAbstraction(const AnnotatedGrid& grid, const Experiment& experiment,
                                  const std::vector<AgentQuery>& queries,
                                  const ResultTally& optimalTally, int clusterSize,
                                  AbstractionQuality quality, const PaperBenchOptions& options,
                                  Failures& failures) {
  std::vector<ClusterAbstraction> graphs;
  std::vector<std::size_t> graphOfKind(experiment.kinds.size(), 0);
  if (!experiment.costs) {
    graphs.push_back(buildAbstractionOrThrow(grid, experimentSpec(clusterSize, quality)));
  } else {
    for (std::size_t k = 0; k < experiment.kinds.size(); ++k) {
      if (std::none_of(queries.begin(), queries.end(),
                       [&](const AgentQuery& q) { return q.kind == k; })) {
        continue;
      }
      graphOfKind[k] = graphs.size();
      graphs.push_back(buildAbstractionOrThrow(
          grid,
          weightedAbstractionSpec(experiment.kinds[k], *experiment.costs, clusterSize, quality)));
    }
  }
  std::deque<HierarchicalAStar> searches;  // HierarchicalAStar cannot move
  AbstractionStats stats;
  for (const ClusterAbstraction& graph : graphs) {
    searches.emplace_back(graph, HaaOptions{.smooth = !options.noSmooth});
    stats += graph.stats();
  }
  ResultTally tally;
  std::vector<Cell> path;
  for (const AgentQuery& q : queries) {
    const std::size_t g = graphOfKind[q.kind];
    path.clear();
    const PathResult result = searches[g].findPath(q.agent, q.query.start, q.query.goal, &path);
    tally.add(result, q.optimal.cost);
    std::string problem;
    if (!result.found()) {
      problem = fmt::format("HAA* says {} where AA* found a path", toString(result.status));
    } else {
      problem =
          pathProblem(grid, q.agent, q.query.start, q.query.goal, result, path, graphs[g].costs());
      if (problem.empty() && result.cost < q.optimal.cost - 1e-6) {
        problem =
            fmt::format("cost {:.6f} is below the optimum {:.6f}", result.cost, q.optimal.cost);
      }
    }
    if (!problem.empty()) {
      failures.add(fmt::format("cluster {} {}: size {} {} {},{} -> {},{}: {}", clusterSize,
                               kAbstractionQualityNames.name(quality), q.agent.size,
                               q.agent.capability.toString(), q.query.start.x, q.query.start.y,
                               q.query.goal.x, q.query.goal.y, problem));
    }
  }
  nlohmann::json row;
  writeAbstractionKeys(stats, row);
  row["graphs"] = graphs.size();
  row["build_ms"] = stats.buildMilliseconds;
  row["queries"] = tally.queries();
  row["solved"] = tally.solved();
  row["mean_error_pct"] = tally.meanSuboptimalityPct();
  row["max_error_pct"] = tally.maxSuboptimalityPct();
  row["haa_mean_expanded"] = tally.meanExpanded();
  row["aa_mean_expanded"] = optimalTally.meanExpanded();
  row["expanded_ratio"] =
      optimalTally.meanExpanded() > 0.0 ? tally.meanExpanded() / optimalTally.meanExpanded() : 0.0;
  row["haa_mean_us"] = tally.meanMicroseconds();
  row["aa_mean_us"] = optimalTally.meanMicroseconds();
  return row;
}

double percentOf(const nlohmann::json& part, const nlohmann::json& whole) {
  const double w = whole.get<double>();
  return w > 0.0 ? 100.0 * part.get<double>() / w : 0.0;
}

void printMarkdown(const nlohmann::json& rows, const PaperBenchOptions& options,
                   const std::vector<Agent>& kinds) {
  // "{ground}, {trees} or {ground,trees}": the capabilities taking part (every size has them).
  std::vector<std::string> names;
  for (const Agent& agent : kinds) {
    if (agent.size == 1) names.push_back("{" + agent.capability.toString() + "}");
  }
  std::string capabilities;
  for (std::size_t i = 0; i < names.size(); ++i)
    capabilities += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  fmt::print(
      "Abstract graph size (Table I). Grid graph: nodes = traversable cells; edges = legal "
      "undirected moves of a size-1 agent that may stand on every terrain of the map. Abstract "
      "edges = inter + intra.\n\n");
  fmt::print(
      "| map | trees % | cluster | quality | grid nodes | grid edges | abstract nodes | nodes % "
      "| abstract edges | edges % | graph KiB | cached paths KiB | build ms |\n");
  fmt::print("|---|--:|--:|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  for (const nlohmann::json& r : rows) {
    fmt::print(
        "| {} | {} | {} | {} | {} | {} | {} | {:.2f} | {} | {:.2f} | {:.0f} | {:.0f} | "
        "{:.1f} |\n",
        r["map"].get<std::string>(), r["soft_percent"].get<int>(), r["cluster_size"].get<int>(),
        r["quality"].get<std::string>(), r["grid_nodes"].get<std::size_t>(),
        r["grid_edges"].get<std::size_t>(), r["abstract_nodes"].get<std::size_t>(),
        percentOf(r["abstract_nodes"], r["grid_nodes"]), r["abstract_edges"].get<std::size_t>(),
        percentOf(r["abstract_edges"], r["grid_edges"]),
        r["abstraction_bytes"].get<double>() / 1024.0,
        r["cached_path_bytes"].get<double>() / 1024.0, r["build_ms"].get<double>());
  }
  fmt::print(
      "\nQueries against AA* ({} per map and share, seed {}; agents of size 1 or 2 with "
      "capability {}, start and goal mutually reachable; HAA* {}{}). Error = (HAA* cost - AA* "
      "cost) / AA* cost; expanded = mean HAA* expansions (all phases) / mean AA* "
      "expansions.\n\n",
      options.queries, options.seed, capabilities, options.noSmooth ? "unsmoothed" : "smoothed",
      options.costsFile.empty()
          ? ""
          : fmt::format("; every agent moves by the terrain costs of {} and HAA* uses a "
                        "weighted graph per agent kind (the graph columns above sum them)",
                        options.costsFile));
  fmt::print(
      "| map | trees % | cluster | quality | mean error % | max error % | expanded vs AA* | "
      "HAA* µs | AA* µs | speed-up | failures |\n");
  fmt::print("|---|--:|--:|---|--:|--:|--:|--:|--:|--:|--:|\n");
  for (const nlohmann::json& r : rows) {
    const double haaUs = r["haa_mean_us"].get<double>();
    const double aaUs = r["aa_mean_us"].get<double>();
    fmt::print(
        "| {} | {} | {} | {} | {:.2f} | {:.2f} | {:.3f} | {:.1f} | {:.1f} | {:.1f}× | {} |\n",
        r["map"].get<std::string>(), r["soft_percent"].get<int>(), r["cluster_size"].get<int>(),
        r["quality"].get<std::string>(), r["mean_error_pct"].get<double>(),
        r["max_error_pct"].get<double>(), r["expanded_ratio"].get<double>(), haaUs, aaUs,
        haaUs > 0.0 ? aaUs / haaUs : 0.0, r["failures"].get<std::size_t>());
  }
}

int runPaperBench(const PaperBenchOptions& options) {
  const std::vector<int> percents = parseIntList(options.percents, "--percents");
  const std::vector<int> clusterSizes = parseIntList(options.clusterSizes, "--cluster-sizes");
  for (int p : percents) {
    if (p < 0 || p > 100) throw BadInput{fmt::format("--percents: {} is not in 0..100", p)};
  }
  for (int clusterSize : clusterSizes) {
    const std::string problem = problemWith(experimentSpec(clusterSize, AbstractionQuality::High));
    if (!problem.empty())
      throw BadInput{fmt::format("--cluster-sizes: {}: {}", clusterSize, problem)};
  }
  Experiment experiment;
  experiment.costs = loadCostsOption(options.costsFile);
  experiment.kinds = experimentAgents(experiment.costs);
  if (experiment.kinds.empty()) {
    throw BadInput{fmt::format(
        "--costs: {} prices none of the experiment's capabilities {{ground}}, {{trees}}, "
        "{{ground,trees}} (it prices {})",
        options.costsFile, experiment.costs->capability().toString())};
  }
  std::vector<GridMap> maps;
  for (const std::string& file : options.mapFiles)
    maps.push_back(loadMapOrThrow(file));

  nlohmann::json rows = nlohmann::json::array();
  Failures failures;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const std::string name = std::filesystem::path(options.mapFiles[m]).stem().string();
    for (int percent : percents) {
      const AnnotatedGrid grid(withSoftObstacles(maps[m], percent, Terrain::Trees, options.seed));
      const auto [gridNodes, gridEdges] = gridGraphSize(grid);
      std::vector<AgentQuery> queries =
          drawQueries(grid, experiment.kinds, options.queries, options.seed, name, percent);
      // Under costs, the optimum is AA* under each agent kind's costs.
      std::vector<CostField> fields;
      if (experiment.costs) {
        for (const Agent& kind : experiment.kinds)
          fields.emplace_back(grid, kind, *experiment.costs);
      }
      AnnotatedAStar optimal(grid);
      ResultTally optimalTally;
      for (AgentQuery& q : queries) {
        q.optimal = fields.empty() ? optimal.findPath(q.agent, q.query.start, q.query.goal, nullptr)
                                   : optimal.findPath(q.agent, q.query.start, q.query.goal, nullptr,
                                                      fields[q.kind]);
        optimalTally.add(q.optimal, q.optimal.cost);
        // The sampler drew a reachable pair, so AA* must find it.
        if (!q.optimal.found())
          failures.add(fmt::format("{} {}%: AA* found no path", name, percent));
      }
      for (int clusterSize : clusterSizes) {
        for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
          std::size_t failuresBefore = failures.count;
          nlohmann::json row = measureAbstraction(grid, experiment, queries, optimalTally,
                                                  clusterSize, quality, options, failures);
          row["map"] = name;
          row["soft_percent"] = percent;
          row["cluster_size"] = clusterSize;
          row["quality"] = std::string(kAbstractionQualityNames.name(quality));
          row["grid_nodes"] = gridNodes;
          row["grid_edges"] = gridEdges;
          row["failures"] = failures.count - failuresBefore;
          rows.push_back(std::move(row));
        }
      }
      fmt::print(stderr, "rts: bench paper: {} with {}% trees done\n", name, percent);
    }
  }

  if (options.markdown) {
    printMarkdown(rows, options, experiment.kinds);
  } else {
    nlohmann::json capabilities = nlohmann::json::array();
    for (const Agent& agent : experiment.kinds) {
      if (agent.size == 1) capabilities.push_back(agent.capability.toString());
    }
    const nlohmann::json out{
        {"seed", options.seed},
        {"queries", options.queries},
        {"smooth", !options.noSmooth},
        {"costs", experiment.costs ? nlohmann::json(options.costsFile) : nlohmann::json(nullptr)},
        {"capabilities", capabilities},
        {"rows", rows}};
    fmt::print("{}\n", out.dump());
  }
  for (const std::string& example : failures.examples)
    fmt::print(stderr, "{}\n", example);
  if (failures.count > 0) {
    fmt::print(stderr, "rts: {} queries failed (no path, illegal path or below the optimum)\n",
               failures.count);
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace

void registerBenchPaperCommand(CLI::App& bench, CommandRunner& run) {
  auto [cmd, options] = addSubcommand<PaperBenchOptions>(
      bench, run, "paper",
      "The HAA* paper's experiment: for each map and each share of its traversable cells turned "
      "into trees, random reachable queries for agents of size 1 or 2 with capability {ground}, "
      "{trees} or {ground,trees}, answered by AA* and by HAA* on the HQ and LQ graph of each "
      "cluster size; prints graph sizes, path error, expansions and time per row (JSON, or "
      "Markdown tables). With --costs every agent moves by the costs: only the capabilities "
      "among those three whose every terrain has a cost take part, the optimum is AA* under "
      "the costs, and HAA* uses one weighted graph per agent kind (size x capability) with "
      "queries, as a weighted graph serves one kind; a row's graph figures sum them.\n"
      "Exit status: 0 done, 1 HAA* missed a path or returned an illegal or too cheap one, "
      "2 bad input.",
      runPaperBench);
  cmd->add_option("maps", options->mapFiles, "MovingAI .map files")->required();
  cmd->add_option("--percents", options->percents,
                  "shares of the traversable cells turned into trees, comma-separated")
      ->capture_default_str();
  cmd->add_option("--cluster-sizes", options->clusterSizes, "cluster sizes, comma-separated")
      ->capture_default_str();
  cmd->add_option("--queries", options->queries, "random queries per map and share")
      ->check(CLI::Range(1, 1'000'000))
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "seed of the derived maps and the queries")
      ->capture_default_str();
  cmd->add_flag("--no-smooth", options->noSmooth, "keep HAA*'s refined paths unsmoothed");
  cmd->add_flag("--markdown", options->markdown, "print Markdown tables instead of JSON");
  addCostsOption(*cmd, options->costsFile);
}

}  // namespace warpath::tools
