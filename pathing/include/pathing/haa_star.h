#pragma once
// Hierarchical Annotated A* (Harabor & Botea 2008) over a ClusterAbstraction, and the hybrid
// short/long rule of Mould & Horsch. Query objects own their scratch memory and reuse it;
// use one per thread. The abstraction (and its grid) may be shared.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/search.h"

namespace warpath::pathing {

// A surcharge on abstract edges, so that long routes can avoid congestion (the engine's
// expected wait at a crowded bridge): the abstract search adds it to an edge's cost when it
// relaxes the edge. The search stays exact for the surcharged costs as long as reaching an
// edge later never gets past it earlier (g + surcharge(g) does not fall as g grows), which a
// queue's wait satisfies; a surcharge is never negative, so the heuristic stays admissible.
// Start and goal links (inside their clusters) and the same-cluster search carry none.
class EdgeSurcharge {
 public:
  virtual ~EdgeSurcharge() = default;
  // [Unit: the graph's cost unit] the surcharge on `edge`, taken from node `from` of `graph`,
  // reached at cost `g` from the start.
  virtual double on(const ClusterAbstraction& graph, std::uint32_t from, const AbstractEdge& edge,
                    double g) const = 0;
};

struct HaaOptions {
  // Shorten the refined path with straight, capability- and clearance-legal segments.
  bool smooth = true;
};

// A query: (1) start and goal in the same cluster: AA* inside the cluster, done if found;
// (2) insert start and goal (one Dijkstra each over their cluster reaches every node there);
// (3) A* over the abstract graph using only edges the agent may use; (4) refine abstract
// edges to grid cells (cached paths); (5) smooth. Each phase is one private member working on
// the query object's scratch, so that the phases can later be sliced across ticks. Agents the
// abstraction does not serve (capability not built, size above maxAgentSize) are answered by
// AA* on the grid (in the uniform model), flagged in metrics.usedGridSearch. A weighted graph
// (AbstractionSpec::costs) plans every phase under its costs, and result.cost is the path's
// cost in their unit; smoothing then only takes shortcuts that are cheaper. Unreachable goals are
// answered at once from the grid's connected components. Bad arguments (start or goal off the map
// or where the agent cannot stand, size 0, empty capability) get InvalidStart / InvalidGoal, never
// a throw.
class HierarchicalAStar {
 public:
  explicit HierarchicalAStar(const ClusterAbstraction& abstraction, HaaOptions options = {});
  ~HierarchicalAStar();
  HierarchicalAStar(const HierarchicalAStar&) = delete;
  HierarchicalAStar& operator=(const HierarchicalAStar&) = delete;

  // When found and `path` is not null, it receives every cell from start to goal inclusive;
  // each step is a legal move for the agent. `surcharge` (may be null) adds to the abstract
  // edges' costs; result.cost stays the path's own cost.
  PathResult findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                      const EdgeSurcharge* surcharge = nullptr);

 private:
  friend class HybridPlanner;
  struct Scratch;
  // The phases of a query, in order; each adds its effort to `metrics` and leaves its
  // output in the scratch (the refined path in `refined`).
  bool searchSameCluster(Agent agent, Cell start, Cell goal, SearchMetrics& metrics);
  void insertEndpoints(const AgentLayer& layer, Cell start, Cell goal, SearchMetrics& metrics);
  bool searchAbstract(Agent agent, Cell start, Cell goal, const EdgeSurcharge* surcharge,
                      SearchMetrics& metrics);
  bool refine(Agent agent, Cell start, SearchMetrics& metrics);
  void smooth(const AgentLayer& layer);
  // AA* on the grid for an agent the graph serves: under the graph's costs when it has them.
  PathResult gridSearch(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                        const SearchLimits& limits);

  const ClusterAbstraction& abstraction_;
  HaaOptions options_;
  AnnotatedAStar gridSearch_;
  std::unique_ptr<Scratch> scratch_;  // defined in the source so the header stays small
};

struct HybridOptions {
  // Node budget of the short-query AA* attempt. Queries whose straight-line distance is at
  // most sqrt(tau) / 2 try AA* with this budget first, the rest (and short queries that run
  // out of budget) go to HAA*. [Limit: >= 1]
  std::uint64_t tau = 4096;
};

// Empty when the options are usable, else what is wrong ("tau must be >= 1 (got 0)").
// HybridPlanner and Planner throw std::invalid_argument with this message; callers taking
// user input check it first.
std::string problemWith(const HybridOptions& options);

class HybridPlanner {
 public:
  // [Limit: problemWith(hybrid).empty(), else std::invalid_argument]
  HybridPlanner(const ClusterAbstraction& abstraction, HybridOptions hybrid = {},
                HaaOptions haa = {});
  // Short queries answered by AA* carry no surcharge (HierarchicalAStar::findPath).
  PathResult findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                      const EdgeSurcharge* surcharge = nullptr);

 private:
  HybridOptions options_;
  double shortQueryDistance_;
  // Short queries use the hierarchical planner's own AA* query object: a second one would
  // hold another whole-map scratch (12 bytes a cell) for nothing.
  HierarchicalAStar hierarchical_;
};

}  // namespace warpath::pathing
