#pragma once
// One front door to every planner, for tools and services that choose the algorithm at run
// time: `Planner` is a query object (one per thread) bound to a shared grid and, for the
// hierarchical algorithms, a shared abstraction of the matching quality.

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/enum_names.h"
#include "pathing/haa_star.h"
#include "pathing/jump_point_search.h"

namespace warpath::pathing {

enum class Algorithm : std::uint8_t {
  AStar,    // "aa": Annotated A* on the grid, optimal
  HaaHigh,  // "haa-hq": HAA* on the high-quality (strong dominance) graph
  HaaLow,   // "haa-lq": HAA* on the low-quality (weak dominance) graph
  Hybrid,   // "hybrid": AA* within a node budget for short queries, else HAA* (HQ graph)
  Jps,      // "jps": jump point search on the agent's layer, optimal, uniform costs only
  JpsPlus,  // "jps+": the same with jump distances precomputed per layer (the same answers)
};
inline constexpr EnumNames<Algorithm, 6> kAlgorithmNames{{{
    {Algorithm::AStar, "aa"},
    {Algorithm::HaaHigh, "haa-hq"},
    {Algorithm::HaaLow, "haa-lq"},
    {Algorithm::Hybrid, "hybrid"},
    {Algorithm::Jps, "jps"},
    {Algorithm::JpsPlus, "jps+"},
}}};

// Names from kAlgorithmNames (kAlgorithmNames.list() for "choose one of" messages).
std::string_view toString(Algorithm algorithm);
std::optional<Algorithm> algorithmFromName(std::string_view name);
// The abstraction quality an algorithm needs; nullopt for AA*, JPS and JPS+.
std::optional<AbstractionQuality> abstractionQualityFor(Algorithm algorithm);

// Empty when Planner(grid, algorithm, abstraction, hybrid) can be built, else what is wrong:
// the abstraction (present, of the quality the algorithm needs, on the same grid) or the
// hybrid options.
std::string problemWith(const AnnotatedGrid& grid, Algorithm algorithm,
                        const ClusterAbstraction* abstraction, const HybridOptions& hybrid = {});

class Planner {
 public:
  // [Limit: abstraction non-null, on `grid`, with the quality abstractionQualityFor(algorithm)
  // unless AA* (where it is ignored); problemWith(hybrid).empty(). Else std::invalid_argument
  // with the message of problemWith(grid, algorithm, abstraction, hybrid).]
  // Terrain costs: AA* plans under `costs` when given (built for the agents it is asked
  // about, and it must outlive the planner); the hierarchical algorithms plan under their
  // abstraction's (AbstractionSpec::costs) and ignore it. JPS and JPS+ plan on uniform costs
  // only [Limit: no `costs` with them, else std::invalid_argument].
  // `jumpSuccessors`: JPS and JPS+'s successor rule (jump_point_search.h).
  Planner(const AnnotatedGrid& grid, Algorithm algorithm, const ClusterAbstraction* abstraction,
          HybridOptions hybrid = {}, HaaOptions haa = {}, const CostField* costs = nullptr,
          JumpSuccessors jumpSuccessors = JumpSuccessors::ForcedOnly);

  Algorithm algorithm() const { return algorithm_; }
  // `surcharge` (may be null) is taken by the hierarchical algorithms' abstract search
  // (EdgeSurcharge); AA* and JPS plan without it.
  PathResult findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                      const EdgeSurcharge* surcharge = nullptr);
  // The same query sliced (search.h), by the algorithm's own sliced search.
  PathStatus beginPath(Agent agent, Cell start, Cell goal,
                       const EdgeSurcharge* surcharge = nullptr);
  PathStatus updatePath(std::uint64_t maxExpansions);
  PathResult finalizePath(std::vector<Cell>* path);
  std::uint64_t expandedSoFar() const;
  std::uint64_t nextStepExpansions() const;
  // Builds now what the planner would build at `agent`'s first query (JPS+ jump tables, also
  // the hybrid's with the JPS+ attempt; HAA*'s insertion tables), so that no timed query
  // carries it; the others build nothing per agent.
  void prepare(Agent agent);
  // JPS and JPS+: the memory their layers hold (bit maps, jump tables); empty for the others.
  std::vector<LayerBytes> layerBytes() const;
  // HAA* and the hybrid: the memory their insertion tables hold (HaaOptions::insertion).
  std::size_t insertionTableBytes() const;

 private:
  Algorithm algorithm_;
  const CostField* costs_;
  std::variant<AnnotatedAStar, HierarchicalAStar, HybridPlanner, JumpPointSearch> impl_;
};

}  // namespace warpath::pathing
