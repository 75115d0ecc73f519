#pragma once
// HAA* insertion by lookup (HaaOptions::insertion == InsertionMode::Tables): for one agent kind
// on a graph in the uniform model, the cost from every cell of a cluster to each node of that
// cluster, and the way there, inside the cluster. A query then links its start and goal to
// their clusters' nodes by reading a few numbers instead of running a Dijkstra over each
// cluster (most of a query's time on open maps). Moves cost the same both ways, so one
// Dijkstra from a node, kept whole, gives the cheapest way from any cell of the cluster to it.
// A cluster's tables are built at its first lookup, or all at once by prepareAll(), and again
// once a repair changed the cluster (ClusterAbstraction::clusterRevision).

#include <cstdint>
#include <utility>
#include <vector>

#include "cluster_dijkstra.h"
#include "pathing/cluster_abstraction.h"

namespace warpath::pathing {

class InsertionTables {
 public:
  // [Limit: graph.costs() == nullptr, graph.supports(agent)] The graph must outlive the tables.
  InsertionTables(const ClusterAbstraction& graph, Agent agent);

  Agent agent() const { return agent_; }
  // Builds every cluster's tables that are not current; returns the cells the searches expanded.
  std::uint64_t prepareAll();
  // Expansions the next lookup at `cell` costs: the nodes of its cluster, or, when the
  // cluster's tables are not current, the searches that build them (a cell each, at most).
  std::uint64_t lookupExpansions(Cell cell) const;
  // Replaces `out` by the nodes of `cell`'s cluster the agent reaches from `cell` inside the
  // cluster, each with the cost of the way; returns the expansions spent (lookupExpansions).
  // [Limit: the agent can stand at cell]
  std::uint64_t links(Cell cell, std::vector<std::pair<std::uint32_t, double>>* out);
  // Append the cells of the way, inside the cluster, from `cell` to `node`'s cell (node's cell
  // included, `cell` not), or from `node`'s cell to `cell` (`cell` included, the node's not).
  // [Limit: links(cell) listed node, and no repair since]
  void appendWayToNode(Cell cell, std::uint32_t node, std::vector<Cell>* out) const;
  void appendWayFromNode(std::uint32_t node, Cell cell, std::vector<Cell>* out) const;
  // Memory the tables hold.
  std::size_t bytes() const;

 private:
  struct Cluster {
    std::uint64_t revision = 0;        // the graph's clusterRevision when built; 0: never
    std::vector<std::uint32_t> nodes;  // those the agent can stand on, in the graph's order
    // Per cell of the region's arrays (regionIndex), per node: a lookup reads one run.
    std::vector<float> costs;
    // Per node, per cell: the move that reached the cell in the node's search (a walk reads
    // one node's).
    std::vector<std::uint8_t> vias;
  };
  bool current(int cluster) const;
  std::uint64_t build(int cluster);
  // The cells from `cell` along node `slot`'s tree to the node, `cell` excluded.
  void walk(int cluster, std::size_t slot, Cell cell, std::vector<Cell>* out) const;
  std::size_t slotOf(int cluster, std::uint32_t node) const;

  const ClusterAbstraction& graph_;
  Agent agent_;
  const AgentLayer& layer_;
  std::vector<Cluster> clusters_;
  RegionMoves moves_;
  ClusterDijkstra search_;
  std::vector<float> nodeCosts_;  // build(): one node's costs, before they are interleaved
};

}  // namespace warpath::pathing
