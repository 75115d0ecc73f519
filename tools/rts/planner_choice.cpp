#include "rts/planner_choice.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>

#include "pathing/map_io.h"
#include "rts/cli_support.h"

namespace warpath::tools {

using namespace pathing;

void addAgentOptions(CLI::App& cmd, AgentChoice& choice) {
  cmd.add_option("--size", choice.size, "agent size in cells (occupies size x size)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd.add_option(
         "--capability", choice.capability,
         "terrains the agent may stand on, comma-separated: " + traversableTerrainNames(","))
      ->capture_default_str();
}

Agent parseAgent(const AgentChoice& choice) {
  const Result<Capability> capability = parseCapability(choice.capability);
  if (!capability) throw BadInput{"--capability: " + capability.error().describe()};
  return {choice.size, capability.value()};
}

CLI::Option* addCostsOption(CLI::App& cmd, std::string& file) {
  return cmd.add_option(
      "--costs", file,
      "plan under terrain costs from a warthog cost table (one line per map "
      "character: the character, its cost; 0 impassable); the agent's capability is "
      "the terrains with a cost, and every --algo plans under the costs (the hierarchical ones "
      "on a graph built for that one agent)");
}

std::optional<TerrainCosts> loadCostsOption(const std::string& file) {
  if (file.empty()) return std::nullopt;
  Result<TerrainCosts> loaded = loadCostTable(file);
  if (!loaded) throw BadInput{loaded.error().describe()};
  if (loaded.value().capability().empty())
    throw BadInput{"--costs: " + file + " gives no terrain a cost (every cost is 0)"};
  return loaded.value();
}

nlohmann::json agentJson(Agent agent) {
  return {{"size", agent.size}, {"capability", agent.capability.toString()}};
}

void addPlannerOptions(CLI::App& cmd, PlannerChoice& choice) {
  cmd.add_option("--algo", choice.algo,
                 "planner: aa (Annotated A*, optimal), haa-hq / haa-lq (hierarchical, high- or "
                 "low-quality graph), hybrid (AA* within a node budget for short queries, else "
                 "haa-hq), jps (jump point search, optimal, uniform costs only), jps+ (jps with "
                 "jump distances precomputed per agent layer, before the queries are timed "
                 "(counted in preprocess_ms): optimal, faster, 16 bytes a cell and layer)")
      ->capture_default_str();
  cmd.add_option("--cluster-size", choice.clusterSize,
                 "side of the clusters of the hierarchical algorithms, in cells")
      ->capture_default_str();
  cmd.add_option("--levels", choice.levels,
                 "hierarchical algorithms: levels of clusters (2: blocks of --level-two-size "
                 "clusters a side are crossed by exact level-2 edges)")
      ->check(CLI::Range(1, 2))
      ->capture_default_str();
  cmd.add_option("--level-two-size", choice.levelTwoSize,
                 "hierarchical algorithms with --levels 2: side of a level-2 cluster, in clusters")
      ->check(CLI::Range(2, 256))
      ->capture_default_str();
  cmd.add_option("--threads", choice.threads,
                 "hierarchical algorithms: threads that search the graph's clusters at once "
                 "while it is built (the same graph for any count; counted in preprocess_ms)")
      ->check(CLI::Range(1, pathing::kMaxBuildThreads))
      ->capture_default_str();
  cmd.add_option("--tau", choice.tau,
                 "hybrid: node budget of the short-query AA* attempt; queries up to sqrt(tau)/2 "
                 "apart try it first")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40))
      ->capture_default_str();
  cmd.add_option("--attempt", choice.attempt,
                 "hybrid: what a query tries within tau before HAA*: aa (AA*, queries up to "
                 "sqrt(tau)/2 apart) or jps+ (JPS+ counting jump points, every query; uniform "
                 "costs)")
      ->capture_default_str();
  cmd.add_option("--grid-search", choice.gridSearch,
                 "hierarchical algorithms: how they search the grid inside a cluster (same-cluster "
                 "queries, refinement without cached paths) and for agents the graph does not "
                 "serve: aa (AA*) or jps (jump points, uniform costs; as short, other cells)")
      ->capture_default_str();
  cmd.add_option("--insertion", choice.insertion,
                 "hierarchical algorithms: how a query links its start and goal to their "
                 "clusters' nodes: search (a Dijkstra over each end's cluster) or tables (costs "
                 "from every cell to its cluster's nodes, per agent kind, built before the timed "
                 "queries and counted in preprocess_ms; uniform costs)")
      ->capture_default_str();
  cmd.add_flag("--no-smooth", choice.noSmooth,
               "hierarchical algorithms: keep the refined path as it is, unsmoothed");
}

Algorithm parseAlgorithm(const std::string& name) {
  if (const auto algorithm = algorithmFromName(name)) return *algorithm;
  throw BadInput{"--algo: unknown planner '" + name + "' (choose " + kAlgorithmNames.list() + ")"};
}

void checkSpecOrThrow(const AbstractionSpec& spec) {
  if (const std::string problem = problemWith(spec); !problem.empty()) {
    throw BadInput{
        fmt::format("cannot build the abstraction (--cluster-size {}, agents up to size {}): {}",
                    spec.clusterSize, spec.maxAgentSize, problem)};
  }
}

ClusterAbstraction buildAbstractionOrThrow(const AnnotatedGrid& grid, AbstractionSpec spec) {
  checkSpecOrThrow(spec);
  return ClusterAbstraction::build(grid, std::move(spec));
}

namespace {

// preparePlanner and prepareCostPlanner: the options, then `build` (timed) fills in the rest.
template <typename Build>
PreparedPlanner prepare(Algorithm algorithm, const PlannerChoice& choice, Build&& build) {
  PreparedPlanner prepared;
  prepared.algorithm = algorithm;
  prepared.hybrid.tau = choice.tau;
  if (const auto attempt = kHybridAttemptNames.parse(choice.attempt)) {
    prepared.hybrid.attempt = *attempt;
  } else {
    throw BadInput{"--attempt: unknown '" + choice.attempt + "' (choose " +
                   kHybridAttemptNames.list() + ")"};
  }
  if (const std::string problem = problemWith(prepared.hybrid); !problem.empty())
    throw BadInput{"--tau: " + problem};
  prepared.haa.smooth = !choice.noSmooth;
  if (const auto search = kGridSearchNames.parse(choice.gridSearch)) {
    prepared.haa.gridSearch = *search;
  } else {
    throw BadInput{"--grid-search: unknown '" + choice.gridSearch + "' (choose " +
                   kGridSearchNames.list() + ")"};
  }
  if (const auto insertion = kInsertionModeNames.parse(choice.insertion)) {
    prepared.haa.insertion = *insertion;
  } else {
    throw BadInput{"--insertion: unknown '" + choice.insertion + "' (choose " +
                   kInsertionModeNames.list() + ")"};
  }
  const auto began = std::chrono::steady_clock::now();
  build(prepared);
  prepared.preprocessMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
  return prepared;
}

}  // namespace

PreparedPlanner preparePlanner(const AnnotatedGrid& grid, Algorithm algorithm,
                               const PlannerChoice& choice, std::span<const Agent> annotate,
                               AbstractionNeeds needs) {
  return prepare(algorithm, choice, [&](PreparedPlanner& prepared) {
    for (const Agent& agent : annotate)
      grid.layer(agent);
    const auto quality = abstractionQualityFor(algorithm);
    if (!quality) return;
    std::sort(needs.capabilities.begin(), needs.capabilities.end());
    needs.capabilities.erase(std::unique(needs.capabilities.begin(), needs.capabilities.end()),
                             needs.capabilities.end());
    prepared.abstraction.emplace(
        buildAbstractionOrThrow(grid, AbstractionSpec{.clusterSize = choice.clusterSize,
                                                      .maxAgentSize = needs.maxAgentSize,
                                                      .capabilities = std::move(needs.capabilities),
                                                      .quality = *quality,
                                                      .cachePaths = true,
                                                      .levels = choice.levels,
                                                      .levelTwoSize = choice.levelTwoSize,
                                                      .threads = choice.threads}));
  });
}

PreparedPlanner prepareCostPlanner(const AnnotatedGrid& grid, Algorithm algorithm,
                                   const PlannerChoice& choice, Agent agent,
                                   const TerrainCosts& costs) {
  return prepare(algorithm, choice, [&](PreparedPlanner& prepared) {
    grid.layer(agent);
    if (const auto quality = abstractionQualityFor(algorithm)) {
      AbstractionSpec spec = weightedAbstractionSpec(agent, costs, choice.clusterSize, *quality);
      spec.levels = choice.levels;
      spec.levelTwoSize = choice.levelTwoSize;
      spec.threads = choice.threads;
      prepared.abstraction.emplace(buildAbstractionOrThrow(grid, std::move(spec)));
    } else {
      prepared.aaCosts.emplace(grid, agent, costs);
    }
  });
}

double prepareAgents(Planner& planner, std::span<const Agent> agents) {
  const auto began = std::chrono::steady_clock::now();
  for (const Agent& agent : agents)
    planner.prepare(agent);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began)
      .count();
}

void writeAbstractionKeys(const ClusterAbstraction* abstraction, nlohmann::json& out) {
  writeAbstractionKeys(abstraction ? abstraction->stats() : AbstractionStats{}, out);
  // How the graph was built, beside how long it took (abstraction_build_ms).
  out["build_threads"] = abstraction ? abstraction->spec().threads : 1;
}

void writeAbstractionKeys(const AbstractionStats& stats, nlohmann::json& out) {
  out["abstract_nodes"] = stats.nodes;
  out["abstract_edges"] = stats.interEdges + stats.intraEdges;
  out["abstract_inter_edges"] = stats.interEdges;
  out["abstract_intra_edges"] = stats.intraEdges;
  out["abstraction_bytes"] = stats.graphBytes;
  out["cached_path_bytes"] = stats.pathBytes;
  out["abstraction_build_ms"] = stats.buildMilliseconds;
  if (stats.levelTwoNodes > 0) {
    out["level_two_nodes"] = stats.levelTwoNodes;
    out["level_two_edges"] = stats.levelTwoEdges;
    out["level_two_bytes"] = stats.levelTwoBytes;
    out["level_two_build_ms"] = stats.levelTwoMilliseconds;
  }
}

}  // namespace warpath::tools
