#pragma once
// The annotated cluster abstraction of HAA* (Harabor & Botea 2008): the map is cut into
// square clusters; along every border between two clusters and for every capability in use,
// maximal entrances are found and each gets a transition (a pair of adjacent cells, one per
// cluster); transitions become abstract nodes joined by inter-edges (one step across the
// border) and by intra-edges (shortest paths inside a cluster), every edge annotated with the
// capability and clearance an agent needs to use it. An agent (s, c) may use an edge e iff
// c_e ⊆ c and cv_e >= s.
//
// Completeness: entrances end where the (truncated) clearance starts to rise on either side,
// so along an entrance the clearance never increases away from its first pair; every pair an
// agent could cross at is joined to the entrance's max-clearance transition by cells the agent
// can stand on. Every transition kept carries the maximal clearance of its entrance for its
// capability, and dominance pruning only removes an edge when the graph keeps another route
// usable by every agent that could use it.
//
// The abstraction changes only through repair() (terrain that changes, docs/haa.md) and is
// safe to share between threads otherwise; queries (HierarchicalAStar) own their scratch
// memory.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/enum_names.h"
#include "pathing/terrain_costs.h"

namespace warpath::pathing {

enum class AbstractionQuality : std::uint8_t {
  High,  // strong dominance only: abstract paths as short as the full annotated graph's
  Low,   // weak dominance, clearances truncated to the largest agent: smaller, slightly worse
};
inline constexpr EnumNames<AbstractionQuality, 2> kAbstractionQualityNames{{{
    {AbstractionQuality::High, "HQ"},
    {AbstractionQuality::Low, "LQ"},
}}};

// Largest cluster side a spec may ask for (a cluster larger than the map is cut to the map).
inline constexpr int kMaxClusterSize = 4096;

// The most threads an AbstractionSpec may ask for.
inline constexpr int kMaxBuildThreads = 256;

struct AbstractionSpec {
  // [Unit: cells] [Limit: 2..kMaxClusterSize] side of a cluster; edge clusters may be smaller
  int clusterSize = 16;
  int maxAgentSize = 3;  // [Unit: cells] [Limit: 1..255] largest agent the graph serves
  // Capabilities the graph serves; an agent's capability must be one of them.
  // [Limit: non-empty, and no capability empty]
  std::vector<Capability> capabilities;
  AbstractionQuality quality = AbstractionQuality::High;
  // Keep every intra-edge's grid path for refinement (memory for speed; see stats()).
  bool cachePaths = true;
  // Terrain costs (issue 13). When set, the graph serves one agent kind, moving by these
  // costs: size maxAgentSize, capability capabilities[0] (the only one). Edge costs are then
  // its travel times (CostField), an entrance is also cut where the cost of crossing it
  // changes (so a border half swamp, half ground gets a transition on each), and dominance
  // compares those costs. One graph per cost profile: a footprint's cost depends on its size.
  // [Limit: exactly one capability, every terrain of which has a cost]
  std::optional<TerrainCosts> costs = std::nullopt;
  // Levels of the hierarchy (HPA*'s levels, Botea et al. 2004). With 2, every levelTwoSize ×
  // levelTwoSize block of clusters is a level-2 cluster: its level-1 nodes with an inter-edge
  // leaving the block are joined by level-2 edges, the shortest paths over the level-1 graph
  // inside the block for every agent the graph serves (annotated like any edge). A query
  // searches level 1 only in the level-2 clusters of its start and goal and crosses the others
  // by level-2 edges, so long queries expand far fewer nodes; answers cost what level 1 alone
  // gives (the level-2 edges are exact over level 1). [Limit: 1..2]
  int levels = 1;
  int levelTwoSize = 4;  // [Unit: clusters] [Limit: 2..256] side of a level-2 cluster
  // Threads that search clusters' intra-edges at once, in a build and in every repair(). The
  // graph is the same for any count: clusters are searched apart and joined in cluster order.
  // [Limit: 1..kMaxBuildThreads]
  int threads = 1;
};

// The smallest agent size a graph built from `spec` serves: 1, or maxAgentSize for a weighted
// graph (its one agent's).
inline int smallestAgentSize(const AbstractionSpec& spec) {
  return spec.costs ? spec.maxAgentSize : 1;
}

// The spec of a weighted graph (AbstractionSpec::costs): it serves `agent` alone (its size and
// capability, every terrain of which `costs` must price), moving by `costs`.
AbstractionSpec weightedAbstractionSpec(Agent agent, const TerrainCosts& costs, int clusterSize,
                                        AbstractionQuality quality);

// Empty when the spec can be built, else what is wrong with it, naming the field, its limit and
// the value (e.g. "clusterSize must be 2..4096 (got 1)"). build() throws std::invalid_argument
// with this message, so callers taking user input check it first.
std::string problemWith(const AbstractionSpec& spec);

struct AbstractEdge {
  static constexpr std::uint32_t kNoPath = UINT32_MAX;

  std::uint32_t target = 0;      // node index
  std::uint32_t path = kNoPath;  // cached grid path (intra-edges with cachePaths), internal
  double cost = 0.0;             // [Unit: cells, or the costs' unit (spec().costs)]
  Capability capability;         // terrains the edge's grid path needs
  std::uint8_t clearance = 0;    // [Unit: cells] largest agent size the path admits
  bool intra = false;            // false: one step across a cluster border
  bool reversed = false;         // cached path is stored target -> source, internal

  bool usableBy(Agent agent) const {
    return capability.isSubsetOf(agent.capability) && clearance >= agent.size;
  }
  // True when this edge, stored at node `to`'s end, is the other direction of `edge` taken from
  // node `from` (every edge is stored once per end, with the same annotation).
  bool isReverseOf(const AbstractEdge& edge, std::uint32_t from) const {
    return target == from && intra == edge.intra && cost == edge.cost &&
           capability == edge.capability && clearance == edge.clearance;
  }
};

struct AbstractionStats {
  int clusters = 0;
  std::size_t nodes = 0;
  std::size_t interEdges = 0;  // undirected
  std::size_t intraEdges = 0;  // undirected
  std::size_t graphBytes = 0;  // nodes, edges, cluster index
  std::size_t pathBytes = 0;   // cached refinement paths
  double buildMilliseconds = 0.0;
  std::uint64_t buildExpanded = 0;  // cells the build's intra-edge searches expanded
  // Level 2 (spec.levels == 2): level-1 nodes that are level-2 nodes (on a level-2 border),
  // level-2 edges (directed: stored at their source), their bytes with the level-1 edge lists
  // they refine to, and the share of buildMilliseconds that built them.
  std::size_t levelTwoNodes = 0;
  std::size_t levelTwoEdges = 0;
  std::size_t levelTwoBytes = 0;
  double levelTwoMilliseconds = 0.0;
};

// What one repair did (ClusterAbstraction::repair).
struct RepairStats {
  int clusters = 0;      // clusters whose intra-edges were found again
  int borders = 0;       // borders whose entrances were found again
  bool rebuilt = false;  // the whole graph was built again (a terrain new to a capability)
  // cells the intra-edge searches expanded, and level-1 nodes the level-2 searches settled (the
  // repair's effort)
  std::uint64_t expanded = 0;
  double milliseconds = 0;  // wall time: measurement only
};

class ClusterAbstraction {
 public:
  // [Limit: problemWith(spec).empty(), else std::invalid_argument] The grid must outlive the
  // abstraction.
  static ClusterAbstraction build(const AnnotatedGrid& grid, AbstractionSpec spec);

  const AnnotatedGrid& grid() const { return *grid_; }
  const AbstractionSpec& spec() const { return spec_; }
  // The costs' field for the one agent a weighted graph serves (spec().costs); null when the
  // graph is in the uniform model.
  const CostField* costs() const { return costs_ ? &*costs_ : nullptr; }
  const AbstractionStats& stats() const { return stats_; }

  // After the grid's terrain changed (AnnotatedGrid::setTerrain and the obstacle calls, which
  // repaired the grid's caches first): repairs the graph cluster by cluster, finding again
  // the entrances of the borders and the intra-edges of the clusters the change can reach
  // (the changed cells grown by the largest agent's size), and the costs under them. The
  // graph stays complete: a path exists in it exactly when AA* finds one on the changed map.
  // Not safe while a query runs on the graph.
  RepairStats repair(const TerrainChange& change);

  // True when the graph serves this agent: its capability is one the graph was built for and
  // its size is at most maxAgentSize (exactly maxAgentSize for a weighted graph).
  bool supports(Agent agent) const;

  int clusterCount() const { return clustersX_ * clustersY_; }
  int clusterOf(Cell c) const {
    return (c.y / spec_.clusterSize) * clustersX_ + c.x / spec_.clusterSize;
  }
  CellRect clusterBounds(int cluster) const;

  // Changes whenever cluster `cluster`'s nodes or the moves of its cells may have changed (a
  // repair redid the cluster, or built the graph again): what is derived from one cluster
  // (HAA*'s insertion tables) is stale once this differs from what it was derived at.
  std::uint64_t clusterRevision(int cluster) const {
    return clusterRevision_[static_cast<std::size_t>(cluster)];
  }

  // Node ids run below nodeCount(); after a repair some ids may be free (listed in no cluster,
  // with no edges) until a later repair reuses them.
  std::uint32_t nodeCount() const { return static_cast<std::uint32_t>(nodeCells_.size()); }
  Cell nodeCell(std::uint32_t node) const { return nodeCells_[node]; }
  std::span<const AbstractEdge> edgesOf(std::uint32_t node) const { return edges_[node]; }
  std::span<const std::uint32_t> nodesInCluster(int cluster) const {
    return clusterNodes_[static_cast<std::size_t>(cluster)];
  }

  // Level 2 (spec().levels == 2; otherwise no node has level-2 edges).
  bool hasLevelTwo() const { return spec_.levels == 2; }
  int levelTwoClusterOf(Cell c) const {
    const int side = spec_.clusterSize * spec_.levelTwoSize;
    return (c.y / side) * levelTwoX_ + c.x / side;
  }
  int levelTwoClusterCount() const { return levelTwoX_ * levelTwoY_; }
  CellRect levelTwoClusterBounds(int levelTwoCluster) const;
  // The level-2 cluster of a node, read from a table (queries ask it at every expansion).
  int levelTwoClusterOfNode(std::uint32_t node) const { return nodeLevelTwo_[node]; }
  // A level-2 node's level-2 edges, each the shortest level-1 path inside its level-2 cluster
  // for the agents its annotation admits (AbstractEdge::intra is true, path is internal).
  std::span<const AbstractEdge> levelTwoEdgesOf(std::uint32_t node) const {
    return node < levelTwoEdges_.size() ? std::span<const AbstractEdge>(levelTwoEdges_[node])
                                        : std::span<const AbstractEdge>();
  }
  // Appends the level-1 steps of level-2 edge `edge` taken from `from` by `agent` (one it may
  // use): for each, the level-1 node it leaves and the level-1 edge it takes (the cheapest one
  // the agent may use between the two nodes), in order.
  void appendLevelOneSteps(std::uint32_t from, const AbstractEdge& edge, Agent agent,
                           std::vector<std::pair<std::uint32_t, const AbstractEdge*>>* out) const;

  // Appends the grid cells of `edge`, taken from node `from`, excluding `from`'s cell and
  // including the target's. [Limit: edge.path != kNoPath or !edge.intra; a programming error,
  // checked as an invariant in debug and sanitizer builds]
  void appendEdgeCells(std::uint32_t from, const AbstractEdge& edge, std::vector<Cell>* out) const;

 private:
  friend class AbstractionBuilder;
  friend class LevelTwoBuilder;
  ClusterAbstraction() = default;
  // Level 2 of the level-2 clusters marked (all when null), after a build or repair of level 1;
  // returns the level-1 nodes its searches settled (their effort).
  std::uint64_t buildLevelTwo(const std::vector<bool>* levelTwoClusters);

  // The cached grid paths of one cluster's intra-edges: path p's moves (moves.h), source to
  // target, are steps[begin[p]] up to steps[begin[p + 1]]. Per cluster, so that a repair
  // replaces a cluster's paths without touching the others.
  struct ClusterPaths {
    std::vector<std::uint32_t> begin{0};
    std::vector<std::uint8_t> steps;
  };

  const AnnotatedGrid* grid_ = nullptr;
  AbstractionSpec spec_;
  AbstractionStats stats_;
  std::optional<CostField> costs_;
  int clustersX_ = 0;
  int clustersY_ = 0;
  // Per spec capability, the terrains of it the map had when the graph was built: edges are
  // annotated with these (a terrain new to one needs a whole build).
  std::vector<Capability> effective_;
  std::vector<Cell> nodeCells_;                           // a free id's cell is {-1, -1}
  std::vector<std::vector<AbstractEdge>> edges_;          // per node, in the order built
  std::vector<std::vector<std::uint32_t>> clusterNodes_;  // per cluster, by cell index
  std::vector<ClusterPaths> paths_;                       // per cluster
  std::vector<std::uint32_t> freeNodes_;                  // ids a repair left unused
  std::vector<std::uint64_t> clusterRevision_;            // per cluster (clusterRevision)
  std::uint64_t revisions_ = 0;                           // the last revision given

  // Level 2. A level-2 edge's path is the level-1 nodes it passes, source excluded, target
  // included, in the order from source to target; per level-2 cluster, so that a repair
  // replaces one cluster's. A repair builds level 2 again for every level-2 cluster holding a
  // cluster whose level-1 edges it changed.
  struct LevelTwoPaths {
    std::vector<std::uint32_t> begin{0};
    std::vector<std::uint32_t> nodes;
  };
  int levelTwoX_ = 0;
  int levelTwoY_ = 0;
  std::vector<int> nodeLevelTwo_;                          // per node
  std::vector<std::vector<AbstractEdge>> levelTwoEdges_;   // per node
  std::vector<LevelTwoPaths> levelTwoPaths_;               // per level-2 cluster
  std::vector<std::vector<std::uint32_t>> levelTwoNodes_;  // per level-2 cluster
  std::size_t levelTwoPathBytes_ = 0;  // level-2 node lists and paths (stats().levelTwoBytes)
};

}  // namespace warpath::pathing
