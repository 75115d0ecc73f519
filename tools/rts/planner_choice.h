#pragma once
// Choosing and preparing a planner from the command line, shared by `rts path` and the
// `rts bench` subcommands: the --algo family of options, the abstraction the hierarchical
// algorithms need, and the JSON keys that describe it.

#include <CLI/App.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/planner.h"
#include "pathing/terrain_costs.h"

namespace warpath::tools {

// The agent options (--size, --capability) as given on the command line.
struct AgentChoice {
  int size = 1;
  std::string capability = "ground";
};

// Adds --size and --capability to `cmd`, bound to `choice` (which must outlive the parse).
void addAgentOptions(CLI::App& cmd, AgentChoice& choice);

// The agent the options describe; throws BadInput on an unknown terrain.
pathing::Agent parseAgent(const AgentChoice& choice);

// {"size": s, "capability": "ground,swamp"}
nlohmann::json agentJson(pathing::Agent agent);

// The planner options as given on the command line.
struct PlannerChoice {
  std::string algo = "aa";
  int clusterSize = pathing::AbstractionSpec{}.clusterSize;
  int levels = pathing::AbstractionSpec{}.levels;
  int levelTwoSize = pathing::AbstractionSpec{}.levelTwoSize;
  int threads = pathing::AbstractionSpec{}.threads;
  std::uint64_t tau = pathing::HybridOptions{}.tau;
  std::string attempt{pathing::kHybridAttemptNames.name(pathing::HybridOptions{}.attempt)};
  bool noSmooth = false;
  std::string gridSearch{pathing::kGridSearchNames.name(pathing::HaaOptions{}.gridSearch)};
  std::string insertion{pathing::kInsertionModeNames.name(pathing::HaaOptions{}.insertion)};
};

// Adds --algo, --cluster-size, --levels, --level-two-size, --threads, --grid-search, --tau,
// --attempt and --no-smooth to `cmd`, bound to `choice` (which must outlive the parse).
void addPlannerOptions(CLI::App& cmd, PlannerChoice& choice);

// The algorithm named by `name` ("aa", "haa-hq", "haa-lq", "hybrid"); throws BadInput.
pathing::Algorithm parseAlgorithm(const std::string& name);

// Adds --costs to `cmd`, bound to `file`.
CLI::Option* addCostsOption(CLI::App& cmd, std::string& file);
// The --costs table, or nullopt when `file` is empty; throws BadInput on a bad file or a table
// that gives no terrain a cost.
std::optional<pathing::TerrainCosts> loadCostsOption(const std::string& file);

// A planner ready for queries: the abstraction (none for AA*), the costs AA* plans under (none
// in the uniform model, or for the hierarchical algorithms, whose abstraction holds its own)
// and what preparing them cost. Planners made from it refer to its abstraction and costs, so
// it must stay where it is meanwhile.
struct PreparedPlanner {
  pathing::Algorithm algorithm = pathing::Algorithm::AStar;
  pathing::HybridOptions hybrid;
  pathing::HaaOptions haa;
  std::optional<pathing::ClusterAbstraction> abstraction;
  std::optional<pathing::CostField> aaCosts;
  double preprocessMs = 0.0;  // [Unit: ms] annotating the grid + costs + abstraction

  const pathing::ClusterAbstraction* abstractionOrNull() const {
    return abstraction ? &*abstraction : nullptr;
  }
  // The costs every query is planned under (the weighted abstraction's, or AA*'s); null in the
  // uniform model.
  const pathing::CostField* costsOrNull() const {
    if (abstraction) return abstraction->costs();
    return aaCosts ? &*aaCosts : nullptr;
  }
  // One query object (one per thread).
  pathing::Planner makePlanner(const pathing::AnnotatedGrid& grid) const {
    return pathing::Planner(grid, algorithm, abstractionOrNull(), hybrid, haa,
                            aaCosts ? &*aaCosts : nullptr);
  }
};

// planner.prepare(agent) for each of `agents` (JPS+ builds their jump tables, which it would
// otherwise build inside their first timed query); returns what that took [Unit: ms], part of
// preprocessing.
double prepareAgents(pathing::Planner& planner, std::span<const pathing::Agent> agents);

// What a hierarchical abstraction must serve.
struct AbstractionNeeds {
  std::vector<pathing::Capability> capabilities;  // duplicates are dropped
  int maxAgentSize = 1;
};

// Annotates the grid for every agent in `annotate` and, when `algorithm` is hierarchical, builds
// the abstraction of its quality for `needs`; preprocessMs times both. Throws BadInput when the
// abstraction cannot be built with these options (e.g. a bad --cluster-size).
PreparedPlanner preparePlanner(const pathing::AnnotatedGrid& grid, pathing::Algorithm algorithm,
                               const PlannerChoice& choice,
                               std::span<const pathing::Agent> annotate, AbstractionNeeds needs);

// Under terrain costs: a planner for the one agent every query is for, moving by `costs`:
// AA* under the agent's CostField, or the hierarchical algorithms on a weighted abstraction
// (pathing::weightedAbstractionSpec) serving that agent alone. preprocessMs times the annotation,
// the costs and the abstraction. Throws BadInput as preparePlanner does.
PreparedPlanner prepareCostPlanner(const pathing::AnnotatedGrid& grid, pathing::Algorithm algorithm,
                                   const PlannerChoice& choice, pathing::Agent agent,
                                   const pathing::TerrainCosts& costs);

// Throws BadInput naming the options when `spec` cannot be built.
void checkSpecOrThrow(const pathing::AbstractionSpec& spec);

// Validates and builds one abstraction; throws BadInput naming the options when it cannot.
pathing::ClusterAbstraction buildAbstractionOrThrow(const pathing::AnnotatedGrid& grid,
                                                    pathing::AbstractionSpec spec);

// abstract_nodes, abstract_edges (inter + intra), abstract_inter_edges, abstract_intra_edges,
// abstraction_bytes, cached_path_bytes, abstraction_build_ms: zeros without an abstraction (AA*
// searches the grid); and build_threads (AbstractionSpec::threads; 1 without one).
void writeAbstractionKeys(const pathing::ClusterAbstraction* abstraction, nlohmann::json& out);
// The same keys for graph statistics (e.g. summed over several graphs).
void writeAbstractionKeys(const pathing::AbstractionStats& stats, nlohmann::json& out);

}  // namespace warpath::tools
