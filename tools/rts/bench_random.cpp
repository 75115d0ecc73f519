// `rts bench random`: a planner against AA* (the optimum) on random queries for one agent.

#include <fmt/core.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/map_generator.h"
#include "pathing/planner.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"
#include "rts/bench_support.h"
#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/planner_choice.h"

namespace warpath::tools {
namespace {

using namespace pathing;

struct RandomBenchOptions {
  std::string mapFile;
  AgentChoice agent;
  int queries = 1000;
  std::uint64_t seed = 1;
  PlannerChoice planner;
  bool json = false;
  std::string costsFile;  // empty: the uniform model
};

// The unit catalogue's capabilities (infantry; jeep and tank; amphibious), which the
// abstraction serves besides the agent's own, as a shared service would.
const std::vector<Capability> kCatalogueCapabilities{
    Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees}),
    Capability::of({Terrain::Ground}),
    Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water}),
};

int runRandomBench(const RandomBenchOptions& options) {
  const Algorithm algorithm = parseAlgorithm(options.planner.algo);
  Agent agent = parseAgent(options.agent);
  // Under costs the agent moves on the terrains that have a cost, as in `rts path`.
  const std::optional<TerrainCosts> costs = loadCostsOption(options.costsFile);
  if (costs) agent.capability = costs->capability();
  const AnnotatedGrid grid(loadMapOrThrow(options.mapFile));

  const QuerySampler sampler(grid, agent);
  if (!sampler.canStandAnywhere()) {
    throw BadInput{fmt::format("a size-{} agent with capability {} can stand nowhere on {}",
                               agent.size, agent.capability.toString(), options.mapFile)};
  }
  SplitMix64 rng(options.seed);
  std::vector<Query> queries(static_cast<std::size_t>(options.queries));
  for (Query& q : queries)
    q = sampler.anyPair(rng);

  // Uniform: the abstraction is shared as a service's would be. Under costs: a weighted graph
  // serves one agent kind, so it is built for this agent alone.
  const auto prepare = [&] {
    if (costs) return prepareCostPlanner(grid, algorithm, options.planner, agent, *costs);
    AbstractionNeeds needs{.capabilities = kCatalogueCapabilities,
                           .maxAgentSize = std::max(3, agent.size)};
    needs.capabilities.push_back(agent.capability);
    const std::vector<Agent> annotate{agent};
    return preparePlanner(grid, algorithm, options.planner, annotate, std::move(needs));
  };
  const PreparedPlanner prepared = prepare();
  Planner planner = prepared.makePlanner(grid);
  const double preparedAgentMs = prepareAgents(planner, std::span(&agent, 1));
  // The optimum: AA* under the same costs.
  Planner optimal(grid, Algorithm::AStar, nullptr, {}, {}, prepared.costsOrNull());

  ResultTally tally;
  ResultTally reference;
  std::size_t completenessFailures = 0, illegalPaths = 0, cheaperThanOptimal = 0;
  std::vector<std::string> problems;
  const auto report = [&](const Query& q, const std::string& what) {
    if (problems.size() < 10) {
      problems.push_back(
          fmt::format("{},{} -> {},{}: {}", q.start.x, q.start.y, q.goal.x, q.goal.y, what));
    }
  };
  std::vector<Cell> path;
  for (const Query& q : queries) {
    const PathResult best = optimal.findPath(agent, q.start, q.goal, nullptr);
    path.clear();  // so that a found result without its path cannot pass on a stale one
    const PathResult result = planner.findPath(agent, q.start, q.goal, &path);
    reference.add(best, best.found() ? std::optional(best.cost) : std::nullopt);
    tally.add(result, best.found() ? std::optional(best.cost) : std::nullopt);
    if (result.found() != best.found()) {
      ++completenessFailures;
      report(q, fmt::format("{} says {}, AA* says {}", toString(algorithm), toString(result.status),
                            toString(best.status)));
    }
    if (!result.found()) continue;
    if (std::string problem =
            pathProblem(grid, agent, q.start, q.goal, result, path, prepared.costsOrNull());
        !problem.empty()) {
      ++illegalPaths;
      report(q, problem);
    }
    if (best.found() && result.cost < best.cost - 1e-6) {
      ++cheaperThanOptimal;
      report(q, fmt::format("cost {:.6f} is below the optimum {:.6f}", result.cost, best.cost));
    }
  }

  nlohmann::json out;
  out["map"] = options.mapFile;
  out["algo"] = std::string(toString(algorithm));
  out["agent"] = agentJson(agent);
  out["seed"] = options.seed;
  out["costs"] = costs ? nlohmann::json(options.costsFile) : nlohmann::json(nullptr);
  if (prepared.abstraction) out["cluster_size"] = options.planner.clusterSize;
  if (algorithm == Algorithm::Hybrid) {
    out["tau"] = options.planner.tau;
    out["attempt"] = options.planner.attempt;
  }
  tally.writeTo(out);
  out["completeness_failures"] = completenessFailures;
  out["illegal_paths"] = illegalPaths;
  out["cheaper_than_optimal"] = cheaperThanOptimal;
  out["preprocess_ms"] = prepared.preprocessMs + preparedAgentMs;
  writeAbstractionKeys(prepared.abstractionOrNull(), out);
  out["aa_median_us"] = reference.medianMicroseconds();
  out["aa_mean_us"] = reference.meanMicroseconds();
  out["aa_mean_expanded"] = reference.meanExpanded();
  printReport(out, options.json);

  for (const std::string& problem : problems)
    fmt::print(stderr, "{}: {}\n", options.mapFile, problem);
  const bool failed = completenessFailures + illegalPaths + cheaperThanOptimal > 0;
  if (failed) {
    fmt::print(stderr,
               "rts: {} completeness failures, {} illegal paths, {} paths cheaper than optimal\n",
               completenessFailures, illegalPaths, cheaperThanOptimal);
  }
  return failed ? kExitFailed : kExitOk;
}

}  // namespace

void registerBenchRandomCommand(CLI::App& bench, CommandRunner& run) {
  auto [cmd, options] = addSubcommand<RandomBenchOptions>(
      bench, run, "random",
      "Compare a planner with AA* (the optimum) on random queries for one agent: start and goal "
      "drawn uniformly (seeded) among the cells where the agent can stand, reachable or not. "
      "The hierarchical planners' abstraction serves the agent's capability and the unit "
      "catalogue's, agents up to max(3, size). With --costs the agent (--size) moves on the "
      "terrains with a cost (--capability is ignored), the optimum is AA* under the costs, and "
      "the hierarchical planners use a graph priced by the costs built for this agent alone "
      "(a weighted graph serves one agent kind).\n"
      "Exit status: 0 done, 1 a completeness failure, an illegal path or a path cheaper than "
      "AA*'s, 2 bad input.",
      runRandomBench);
  cmd->add_option("map", options->mapFile, "MovingAI .map file")->required();
  addAgentOptions(*cmd, options->agent);
  cmd->add_option("--queries", options->queries, "number of random queries")
      ->check(CLI::Range(1, 10'000'000))
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "seed of the query generator")->capture_default_str();
  options->planner.algo = "haa-hq";  // comparing AA* with itself is the odd case here
  addPlannerOptions(*cmd, options->planner);
  addCostsOption(*cmd, options->costsFile);
  cmd->add_flag("--json", options->json, "print one JSON object");
}

}  // namespace warpath::tools
