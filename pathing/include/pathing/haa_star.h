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
#include "pathing/enum_names.h"
#include "pathing/jump_point_search.h"
#include "pathing/search.h"

namespace warpath::pathing {

class InsertionTables;

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
  // True when `on` is 0 for every edge with both ends in level-2 cluster `levelTwoCluster` of
  // `graph` (AbstractionSpec::levels), whatever g: a search may then cross it by level-2
  // edges. The default, false, has surcharged searches expand level 1 there.
  virtual bool freeWithin(const ClusterAbstraction& graph, int levelTwoCluster) const {
    (void)graph;
    (void)levelTwoCluster;
    return false;
  }
};

// How HAA* searches the grid where it does (ClusterSearch below).
enum class GridSearch : std::uint8_t {
  AStar,       // "aa": AA*
  JumpPoints,  // "jps": JPS on the agent's layer (jump_point_search.h), uniform costs only
};
inline constexpr EnumNames<GridSearch, 2> kGridSearchNames{{{
    {GridSearch::AStar, "aa"},
    {GridSearch::JumpPoints, "jps"},
}}};

// How HAA* links the start and the goal to the nodes of their clusters (insertion).
enum class InsertionMode : std::uint8_t {
  // "search": a Dijkstra over the cluster from each end, every query.
  Search,
  // "tables": the costs from every cell of a cluster to its nodes, and the ways there, kept
  // per agent kind and cluster (built at a cluster's first query, or by prepare(); again after
  // a repair changes the cluster): a query reads them. Uniform costs only (a weighted graph
  // searches); about 5 bytes per node of a cluster and cell of it, per agent kind.
  Tables,
};
inline constexpr EnumNames<InsertionMode, 2> kInsertionModeNames{{{
    {InsertionMode::Search, "search"},
    {InsertionMode::Tables, "tables"},
}}};

struct HaaOptions {
  // Shorten the refined path with straight, capability- and clearance-legal segments.
  bool smooth = true;
  // The searches on the grid: the same-cluster attempt, intra-edges refined without cached
  // paths, and agents the graph does not serve. JumpPoints finds paths as short as AA*'s
  // (other cells at times, so other answers) expanding fewer nodes; under a weighted graph's
  // costs those searches stay AA*'s, except for agents the graph does not serve, which are
  // planned in the uniform model anyway.
  GridSearch gridSearch = GridSearch::AStar;
  InsertionMode insertion = InsertionMode::Search;
};

// A query: (1) start and goal in the same cluster: AA* inside the cluster, done if found;
// (2) insert start and goal (one Dijkstra each over their cluster reaches every node there);
// (3) A* over the abstract graph using only edges the agent may use; (4) refine abstract
// edges to grid cells (cached paths); (5) smooth. Each phase is one private member working on
// the query object's scratch, so that a query can be sliced across ticks (beginPath). Agents the
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

  // The same query sliced (search.h). Expansions are those metrics.expanded counts: grid cells
  // of the searches on the grid and abstract nodes alike. Every phase stops between two
  // expansions but insertion: the Dijkstra over the start's cluster, and then the goal's, is
  // one step each (splitting its tuned inner loop would cost every query), of at most its
  // cluster's cells (nextStepExpansions()). It is begun only when the slice has room for it, or
  // as the update's first step: an updatePath spends at most max(maxExpansions, clusterSize^2).
  // Refining an edge whose path is not cached, and the same-cluster attempt, are AA* searches
  // sliced like any other.
  // `surcharge` must outlive the query.
  PathStatus beginPath(Agent agent, Cell start, Cell goal,
                       const EdgeSurcharge* surcharge = nullptr);
  PathStatus updatePath(std::uint64_t maxExpansions);
  PathResult finalizePath(std::vector<Cell>* path);
  std::uint64_t expandedSoFar() const;
  std::uint64_t nextStepExpansions() const;
  // For a planner that runs this one's queries inside its own and times them (PhaseTiming).
  void stopTimingPhases() { timing_.stopTimingPhases(); }
  // Builds now what queries for `agent` would build at first use (insertion tables), so that
  // no timed query carries it; nothing for the other options.
  void prepare(Agent agent);
  // Memory the insertion tables hold (0 unless HaaOptions::insertion is Tables).
  std::size_t insertionTableBytes() const;

 private:
  friend class HybridPlanner;
  struct Scratch;
  // The phases of a query, in order; each works on the query object's scratch, adds its effort
  // to the result's metrics and leaves its output there (the refined path in `refined`).
  enum class Phase : std::uint8_t {
    GridOnly,     // an agent the graph does not serve: AA* on the grid, uniform costs
    SameCluster,  // start and goal share a cluster: AA* inside it first
    InsertStart,  // insertion: the start's cluster Dijkstra
    InsertGoal,   // and the goal's
    Abstract,     // A* over the abstract graph
    Refine,       // abstract edges to grid cells, then smoothing
  };
  // updatePath; `mayOverrun`: a step larger than the slice may be its first (the hybrid's
  // attempt may have spent part of the caller's slice already).
  PathStatus advance(std::uint64_t maxExpansions, bool mayOverrun);
  // Advances the phase under way by at most `budget` expansions (insertion: one step);
  // returns the expansions spent.
  std::uint64_t step(std::uint64_t budget);
  // A sub-search on the grid (gridSearch_) advanced within `budget`: the expansions spent;
  // `done` tells whether it finished.
  std::uint64_t stepGridSearch(std::uint64_t budget, bool& done);
  void insertEndpoint(bool goalSide);
  void beginAbstract();
  std::uint64_t searchAbstract(std::uint64_t budget);
  void tracePath();
  std::uint64_t refine(std::uint64_t budget);
  // Smoothing, cost and the total of the phases: the query is Found.
  void complete();
  void smooth(const AgentLayer& layer);
  // Starts the grid search (options_.gridSearch) for an agent the graph serves: AA* under the
  // graph's costs when it has them; `uniform`: in the uniform model whatever the graph.
  PathStatus beginGridSearch(Agent agent, Cell start, Cell goal, const SearchLimits& limits,
                             bool uniform = false);
  PathResult finalizeGridSearch(std::vector<Cell>* path);

  // The insertion tables for `agent`, made at first ask; null when insertion searches (the
  // option, or a weighted graph) or the graph does not serve the agent.
  InsertionTables* tablesFor(Agent agent);

  const ClusterAbstraction& abstraction_;
  HaaOptions options_;
  std::vector<std::unique_ptr<InsertionTables>> tables_;  // per agent kind asked for
  AnnotatedAStar gridSearch_;
  JumpPointSearch jumpSearch_;  // options_.gridSearch == JumpPoints (its scratch at first use)
  bool gridJumping_ = false;    // the grid search under way is jumpSearch_'s
  std::unique_ptr<Scratch> scratch_;  // defined in the source so the header stays small
  PhaseTiming timing_;
};

// What a hybrid query tries before HAA*.
enum class HybridAttempt : std::uint8_t {
  // "aa": AA* within tau expanded cells, for queries up to sqrt(tau) / 2 apart.
  AStar,
  // "jps+": JPS+ (jump_point_search.h, tables per agent layer) within tau expanded jump points,
  // for every query: its jump points are few whatever the distance, and it is optimal. Under
  // terrain costs (a weighted graph) the attempt is AA*'s.
  JumpPoints,
};
inline constexpr EnumNames<HybridAttempt, 2> kHybridAttemptNames{{{
    {HybridAttempt::AStar, "aa"},
    {HybridAttempt::JumpPoints, "jps+"},
}}};

struct HybridOptions {
  // Node budget of the attempt. Queries it may answer try it first with this budget, the rest
  // (and those that run out of budget) go to HAA*. [Limit: >= 1]
  std::uint64_t tau = 4096;
  HybridAttempt attempt = HybridAttempt::AStar;
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
  // Builds `agent`'s jump table now with the JPS+ attempt (JumpPointSearch::prepare), and
  // HAA*'s insertion tables (HierarchicalAStar::prepare).
  void prepare(Agent agent);
  std::size_t insertionTableBytes() const { return hierarchical_.insertionTableBytes(); }
  // The same query sliced (search.h): the short-query attempt, then HAA* when it runs out.
  PathStatus beginPath(Agent agent, Cell start, Cell goal,
                       const EdgeSurcharge* surcharge = nullptr);
  PathStatus updatePath(std::uint64_t maxExpansions);
  PathResult finalizePath(std::vector<Cell>* path);
  std::uint64_t expandedSoFar() const;
  std::uint64_t nextStepExpansions() const;

 private:
  enum class Stage : std::uint8_t {
    Attempt,   // the short-query AA* attempt under way
    Answered,  // it answered (anything but BudgetExhausted)
    Hierarchical,
  };
  // beginPath and updatePath, untimed.
  PathStatus begin(Agent agent, Cell start, Cell goal, const EdgeSurcharge* surcharge);
  PathStatus update(std::uint64_t maxExpansions);
  // After the attempt's begin or update returned `status`: moves on to HAA* when it ran out
  // of budget. Returns the query's status.
  PathStatus afterAttempt(PathStatus status);
  // f(search) on the attempt's search object (AA* or JPS+).
  // Whether the attempt is JPS+ (HybridAttempt::JumpPoints, on a uniform-cost graph).
  bool attemptsJumpPoints() const;
  template <typename F>
  decltype(auto) withAttempt(F&& f);
  template <typename F>
  decltype(auto) withAttempt(F&& f) const;

  HybridOptions options_;
  double shortQueryDistance_;
  // Short queries use the hierarchical planner's own AA* query object: a second one would
  // hold another whole-map scratch (12 bytes a cell) for nothing.
  HierarchicalAStar hierarchical_;
  // The JPS+ attempt (HybridAttempt::JumpPoints; its tables are built at a layer's first use).
  JumpPointSearch jumps_;
  // The query under way.
  bool jumping_ = false;  // its attempt is JPS+'s
  Stage stage_ = Stage::Hierarchical;
  PathStatus attemptStatus_ = PathStatus::Pending;
  PathResult attempt_;  // a short query's attempt, once it ran out of budget
  Agent agent_;
  Cell start_;
  Cell goal_;
  const EdgeSurcharge* surcharge_ = nullptr;
  double microseconds_ = 0.0;  // its phases' times so far
  PhaseTiming timing_;
};

}  // namespace warpath::pathing
