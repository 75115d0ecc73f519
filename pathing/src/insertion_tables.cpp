#include "insertion_tables.h"

#include <algorithm>
#include <cmath>

#include "pathing/invariant.h"
#include "pathing/moves.h"

namespace warpath::pathing {

InsertionTables::InsertionTables(const ClusterAbstraction& graph, Agent agent)
    : graph_(graph),
      agent_(agent),
      layer_(graph.grid().layer(agent)),
      clusters_(static_cast<std::size_t>(graph.clusterCount())) {}

bool InsertionTables::current(int cluster) const {
  return clusters_[static_cast<std::size_t>(cluster)].revision == graph_.clusterRevision(cluster);
}

std::uint64_t InsertionTables::prepareAll() {
  std::uint64_t expanded = 0;
  for (int k = 0; k < graph_.clusterCount(); ++k) {
    if (!current(k)) expanded += build(k);
  }
  return expanded;
}

std::uint64_t InsertionTables::build(int cluster) {
  Cluster& c = clusters_[static_cast<std::size_t>(cluster)];
  const CellRect bounds = graph_.clusterBounds(cluster);
  const GridMap& map = graph_.grid().map();
  c.revision = graph_.clusterRevision(cluster);
  c.nodes.clear();
  for (const std::uint32_t n : graph_.nodesInCluster(cluster)) {
    if (graph_.grid().canStand(agent_, graph_.nodeCell(n))) c.nodes.push_back(n);
  }
  const std::size_t cells = regionCells(bounds);
  c.costs.resize(c.nodes.size() * cells);
  c.vias.resize(c.nodes.size() * cells);
  c.costs.shrink_to_fit();
  c.vias.shrink_to_fit();
  if (c.nodes.empty()) return 0;
  moves_.load(map, layer_, bounds);
  std::uint64_t expanded = 0;
  const std::size_t nodes = c.nodes.size();
  nodeCosts_.resize(cells);
  for (std::size_t slot = 0; slot < nodes; ++slot) {
    search_.run(moves_, graph_.nodeCell(c.nodes[slot]), {});
    search_.copyTree(nodeCosts_, std::span<std::uint8_t>(c.vias).subspan(slot * cells, cells));
    for (std::size_t i = 0; i < cells; ++i)
      c.costs[i * nodes + slot] = nodeCosts_[i];
    expanded += search_.expanded();
  }
  return expanded;
}

std::uint64_t InsertionTables::lookupExpansions(Cell cell) const {
  const int cluster = graph_.clusterOf(cell);
  if (!current(cluster)) {
    const CellRect bounds = graph_.clusterBounds(cluster);
    const auto cells = static_cast<std::uint64_t>(bounds.width) * bounds.height;
    return std::max<std::uint64_t>(1, graph_.nodesInCluster(cluster).size() * cells);
  }
  return std::max<std::uint64_t>(1, clusters_[static_cast<std::size_t>(cluster)].nodes.size());
}

std::uint64_t InsertionTables::links(Cell cell,
                                     std::vector<std::pair<std::uint32_t, double>>* out) {
  const int cluster = graph_.clusterOf(cell);
  std::uint64_t expanded = current(cluster) ? 0 : build(cluster);
  const Cluster& c = clusters_[static_cast<std::size_t>(cluster)];
  const CellRect bounds = graph_.clusterBounds(cluster);
  const std::size_t nodes = c.nodes.size();
  const float* costs = c.costs.data() + regionIndex(bounds, cell) * nodes;
  out->clear();
  for (std::size_t slot = 0; slot < nodes; ++slot) {
    const float cost = costs[slot];
    if (std::isfinite(cost)) out->emplace_back(c.nodes[slot], static_cast<double>(cost));
  }
  return expanded + std::max<std::size_t>(1, c.nodes.size());
}

std::size_t InsertionTables::slotOf(int cluster, std::uint32_t node) const {
  const std::vector<std::uint32_t>& nodes = clusters_[static_cast<std::size_t>(cluster)].nodes;
  const auto it = std::find(nodes.begin(), nodes.end(), node);
  WARPATH_INVARIANT(it != nodes.end(), "insertion tables: a way to a node of another cluster");
  return static_cast<std::size_t>(it - nodes.begin());
}

void InsertionTables::walk(int cluster, std::size_t slot, Cell cell, std::vector<Cell>* out) const {
  const Cluster& c = clusters_[static_cast<std::size_t>(cluster)];
  const CellRect bounds = graph_.clusterBounds(cluster);
  const std::size_t cells = regionCells(bounds);
  const std::uint8_t* vias = c.vias.data() + slot * cells;
  const Cell node = graph_.nodeCell(c.nodes[slot]);
  // Each cell's via is the move that reached it from its parent in the node's search: back
  // along it is one move nearer the node.
  for (Cell at = cell; at != node;) {
    const Direction& dir = kDirections[vias[regionIndex(bounds, at)]];
    at = {at.x - dir.dx, at.y - dir.dy};
    out->push_back(at);
  }
}

void InsertionTables::appendWayToNode(Cell cell, std::uint32_t node, std::vector<Cell>* out) const {
  const int cluster = graph_.clusterOf(cell);
  walk(cluster, slotOf(cluster, node), cell, out);
}

void InsertionTables::appendWayFromNode(std::uint32_t node, Cell cell,
                                        std::vector<Cell>* out) const {
  const int cluster = graph_.clusterOf(cell);
  const std::size_t first = out->size();
  out->push_back(cell);
  walk(cluster, slotOf(cluster, node), cell, out);
  // cell .. node, reversed: node .. cell; then the node's cell goes.
  std::reverse(out->begin() + static_cast<std::ptrdiff_t>(first), out->end());
  out->erase(out->begin() + static_cast<std::ptrdiff_t>(first));
}

std::size_t InsertionTables::bytes() const {
  std::size_t total = clusters_.capacity() * sizeof(Cluster);
  for (const Cluster& c : clusters_) {
    total += c.nodes.capacity() * sizeof(std::uint32_t) + c.costs.capacity() * sizeof(float) +
             c.vias.capacity();
  }
  return total;
}

}  // namespace warpath::pathing
