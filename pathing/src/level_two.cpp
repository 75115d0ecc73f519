// Level 2 of the cluster hierarchy (AbstractionSpec::levels): HPA*'s next level (Botea et al.
// 2004), built over the annotated level-1 graph the way HAA* builds level 1 over the grid.
//
// Completeness and exactness: a level-2 cluster's level-2 nodes are its level-1 nodes with an
// inter-edge leaving it. Any level-1 path crossing a level-2 cluster it neither starts nor ends
// in enters and leaves it at such nodes, and between them runs inside it. For every agent the
// graph serves (each capability of the spec, each size) and every pair of level-2 nodes, the
// shortest such inside run over the level-1 edges the agent may use becomes a level-2 edge,
// annotated with the union of its edges' capabilities and the least of their clearances, so
// the agent may use it; dominance removes an edge only for another as cheap that every agent
// able to use it may use. A query that crosses other level-2 clusters by level-2 edges alone
// therefore finds a path exactly when level 1 does, at the same cost.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <queue>

#include "parallel_for.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/invariant.h"

namespace warpath::pathing {

class LevelTwoBuilder {
 public:
  explicit LevelTwoBuilder(ClusterAbstraction& g) : g_(g) {}

  std::uint64_t settled() const { return settled_; }

  // Debug and sanitizer builds: what queries rely on. Every level-2 edge of the block joins two
  // of its level-2 nodes, has its reverse, and refines, for the least agent it admits, into
  // level-1 steps inside the block, each usable, that add up to its cost.
  void check(int block) const {
    std::vector<std::pair<std::uint32_t, const AbstractEdge*>> steps;
    for (const std::uint32_t n : g_.levelTwoNodes_[static_cast<std::size_t>(block)]) {
      for (const AbstractEdge& e : g_.levelTwoEdgesOf(n)) {
        WARPATH_INVARIANT(e.intra && e.target != n && g_.levelTwoClusterOfNode(e.target) == block,
                          "level 2: an edge must join two nodes of its block");
        const auto back = g_.levelTwoEdgesOf(e.target);
        WARPATH_INVARIANT(std::any_of(back.begin(), back.end(),
                                      [&](const AbstractEdge& r) { return r.isReverseOf(e, n); }),
                          "level 2: an edge without its reverse");
        const Agent least{e.clearance, e.capability};
        steps.clear();
        g_.appendLevelOneSteps(n, e, least, &steps);
        double cost = 0.0;
        std::uint32_t at = n;
        for (const auto& [from, step] : steps) {
          WARPATH_INVARIANT(from == at && step->usableBy(least) &&
                                g_.levelTwoClusterOfNode(step->target) == block,
                            "level 2: a step must go on inside the block, usable");
          cost += step->cost;
          at = step->target;
        }
        WARPATH_INVARIANT(at == e.target && std::abs(cost - e.cost) < 1e-6,
                          "level 2: the steps must reach the target at the edge's cost");
      }
    }
  }

  // Builds the level-2 edges of level-2 cluster `block` again from the level-1 graph.
  void rebuild(int block) {
    ClusterAbstraction::LevelTwoPaths& paths = g_.levelTwoPaths_[static_cast<std::size_t>(block)];
    paths = {};
    collectNodes(block);
    // The last level-2 node has no later one to search for: its edges are the others' reverses.
    const int smallest = smallestAgentSize(g_.spec_);
    for (std::uint32_t i = 0; i + 1 < entries_.size(); ++i) {
      candidates_.clear();
      const std::uint32_t u = entries_[i];
      for (const Capability& capability : g_.spec_.capabilities) {
        for (int size = smallest; size <= g_.spec_.maxAgentSize; ++size)
          searchFrom(u, Agent{size, capability}, i);
      }
      keepUndominated(u, paths);
    }
    for (std::uint32_t n : nodes_)
      localOf_[n] = kNone;
  }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;

  struct Candidate {
    std::uint32_t target = 0;  // graph node
    double cost = 0.0;
    Capability capability;
    std::uint8_t clearance = 0;
    std::uint32_t stepsBegin = 0;  // in steps_
    std::uint32_t stepsEnd = 0;
    bool removed = false;
  };

  // The block's level-1 nodes (cluster by cluster, each cluster's in its order), their local
  // indices, and its level-2 nodes; the old level-2 nodes' edges are dropped.
  void collectNodes(int block) {
    const AbstractionSpec& spec = g_.spec_;
    const int bx = block % g_.levelTwoX_;
    const int by = block / g_.levelTwoX_;
    std::vector<std::uint32_t>& old = g_.levelTwoNodes_[static_cast<std::size_t>(block)];
    for (std::uint32_t n : old)
      g_.levelTwoEdges_[n].clear();
    old.clear();
    nodes_.clear();
    for (int cy = by * spec.levelTwoSize;
         cy < std::min(g_.clustersY_, (by + 1) * spec.levelTwoSize); ++cy) {
      for (int cx = bx * spec.levelTwoSize;
           cx < std::min(g_.clustersX_, (bx + 1) * spec.levelTwoSize); ++cx) {
        for (std::uint32_t n : g_.nodesInCluster(cy * g_.clustersX_ + cx))
          nodes_.push_back(n);
      }
    }
    if (localOf_.size() < g_.nodeCells_.size()) localOf_.resize(g_.nodeCells_.size(), kNone);
    entries_.clear();
    entryOf_.assign(nodes_.size(), kNone);
    for (std::uint32_t i = 0; i < nodes_.size(); ++i) {
      const std::uint32_t n = nodes_[i];
      localOf_[n] = i;
      g_.nodeLevelTwo_[n] = block;
      const auto edges = g_.edgesOf(n);
      if (std::any_of(edges.begin(), edges.end(), [&](const AbstractEdge& e) {
            return !e.intra && g_.levelTwoClusterOf(g_.nodeCells_[e.target]) != block;
          })) {
        entryOf_[i] = static_cast<std::uint32_t>(entries_.size());
        entries_.push_back(n);
      }
    }
    old = entries_;
    dist_.assign(nodes_.size(), 0.0);
    parent_.assign(nodes_.size(), kNone);
    parentEdge_.assign(nodes_.size(), 0);
    stamp_.assign(nodes_.size(), 0);
    generation_ = 0;
  }

  // Dijkstra from level-2 node `u` over the block's level-1 edges `agent` may use; a candidate
  // for every level-2 node after it in entries_ (the edge's reverse serves the other way: level-1
  // edges are undirected, so the cost is the same both ways). It stops once those are settled.
  void searchFrom(std::uint32_t u, Agent agent, std::uint32_t entryIndex) {
    const auto usable = g_.edgesOf(u);
    if (std::none_of(usable.begin(), usable.end(),
                     [&](const AbstractEdge& e) { return e.usableBy(agent); }))
      return;
    ++generation_;
    const std::uint32_t open = generation_ * 2;
    const std::uint32_t closed = open + 1;
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
    const std::uint32_t source = localOf_[u];
    stamp_[source] = open;
    dist_[source] = 0.0;
    parent_[source] = kNone;
    heap.push({0.0, source});
    std::size_t targetsLeft = entries_.size() - entryIndex - 1;
    while (!heap.empty()) {
      const auto [d, x] = heap.top();
      heap.pop();
      if (stamp_[x] == closed) continue;
      stamp_[x] = closed;
      ++settled_;
      if (entryOf_[x] != kNone && entryOf_[x] > entryIndex && --targetsLeft == 0) break;
      const auto edges = g_.edgesOf(nodes_[x]);
      for (std::uint32_t k = 0; k < edges.size(); ++k) {
        const AbstractEdge& e = edges[k];
        if (!e.usableBy(agent)) continue;
        const std::uint32_t y = localOf_[e.target];
        if (y == kNone || stamp_[y] == closed) continue;
        const double nd = d + e.cost;
        if (stamp_[y] == open && nd >= dist_[y]) continue;
        stamp_[y] = open;
        dist_[y] = nd;
        parent_[y] = x;
        parentEdge_[y] = k;
        heap.push({nd, y});
      }
    }
    for (std::uint32_t j = entryIndex + 1; j < entries_.size(); ++j) {
      const std::uint32_t v = localOf_[entries_[j]];
      if (stamp_[v] != closed) continue;
      Candidate c;
      c.target = entries_[j];
      c.cost = dist_[v];
      c.clearance = UINT8_MAX;
      c.stepsBegin = static_cast<std::uint32_t>(steps_.size());
      for (std::uint32_t at = v; at != source; at = parent_[at]) {
        const AbstractEdge& e = g_.edges_[nodes_[parent_[at]]][parentEdge_[at]];
        c.capability = Capability::fromMask(c.capability.mask() | e.capability.mask());
        c.clearance = std::min(c.clearance, e.clearance);
        steps_.push_back(nodes_[at]);
      }
      std::reverse(steps_.begin() + c.stepsBegin, steps_.end());
      c.stepsEnd = static_cast<std::uint32_t>(steps_.size());
      candidates_.push_back(c);
    }
  }

  // Of the candidates from `u` to each node, those no other dominates (as cheap, capability a
  // subset, clearance at least; of equals the first), stored at both ends.
  void keepUndominated(std::uint32_t u, ClusterAbstraction::LevelTwoPaths& paths) {
    constexpr double kSame = 1e-9;
    // x serves every agent y serves, at no greater cost.
    const auto dominates = [](const Candidate& x, const Candidate& y) {
      return !x.removed && x.cost <= y.cost + kSame && x.capability.isSubsetOf(y.capability) &&
             x.clearance >= y.clearance;
    };
    std::stable_sort(candidates_.begin(), candidates_.end(),
                     [](const Candidate& l, const Candidate& r) { return l.target < r.target; });
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
      Candidate& a = candidates_[i];
      for (std::size_t j = i; j-- > 0 && candidates_[j].target == a.target;) {
        if (dominates(candidates_[j], a)) {
          a.removed = true;
          break;
        }
      }
      if (a.removed) continue;
      // A later candidate may dominate earlier ones it is strictly better than.
      for (std::size_t j = i; j-- > 0 && candidates_[j].target == a.target;) {
        if (dominates(a, candidates_[j])) candidates_[j].removed = true;
      }
    }
    for (const Candidate& c : candidates_) {
      if (c.removed) continue;
      AbstractEdge forward;
      forward.target = c.target;
      forward.path = static_cast<std::uint32_t>(paths.begin.size() - 1);
      forward.cost = c.cost;
      forward.capability = c.capability;
      forward.clearance = c.clearance;
      forward.intra = true;
      paths.nodes.insert(paths.nodes.end(), steps_.begin() + c.stepsBegin,
                         steps_.begin() + c.stepsEnd);
      paths.begin.push_back(static_cast<std::uint32_t>(paths.nodes.size()));
      AbstractEdge backward = forward;
      backward.target = u;
      backward.reversed = true;
      g_.levelTwoEdges_[u].push_back(forward);
      g_.levelTwoEdges_[c.target].push_back(backward);
    }
    steps_.clear();
  }

  ClusterAbstraction& g_;
  std::vector<std::uint32_t> nodes_;    // the block's level-1 nodes
  std::vector<std::uint32_t> entries_;  // its level-2 nodes
  std::vector<std::uint32_t> entryOf_;  // local index -> index in entries_, kNone if none
  std::vector<std::uint32_t> localOf_;  // graph node -> index in nodes_, kNone outside
  std::vector<double> dist_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> parentEdge_;  // index in the parent's edges
  std::vector<std::uint32_t> stamp_;       // generation * 2 + {0 open, 1 closed}
  std::uint32_t generation_ = 0;
  std::uint64_t settled_ = 0;
  std::vector<Candidate> candidates_;
  std::vector<std::uint32_t> steps_;  // candidates' paths (level-1 nodes after the source)
};

std::uint64_t ClusterAbstraction::buildLevelTwo(const std::vector<bool>* levelTwoClusters) {
  if (spec_.levels != 2) return 0;
  const auto began = std::chrono::steady_clock::now();
  const int side = spec_.levelTwoSize;
  levelTwoX_ = (clustersX_ + side - 1) / side;
  levelTwoY_ = (clustersY_ + side - 1) / side;
  const auto blocks = static_cast<std::size_t>(levelTwoX_ * levelTwoY_);
  if (!levelTwoClusters) {
    levelTwoEdges_.assign(nodeCells_.size(), {});
    nodeLevelTwo_.assign(nodeCells_.size(), -1);
    levelTwoPaths_.assign(blocks, {});
    levelTwoNodes_.assign(blocks, {});
    stats_.levelTwoNodes = 0;
    stats_.levelTwoEdges = 0;
    levelTwoPathBytes_ = 0;
  }
  // The statistics follow what the blocks rebuilt held before and hold after (a repair touches
  // a few blocks; sweeping them all would cost it as much as the repair on large maps).
  const auto count = [&](std::size_t b, std::ptrdiff_t sign) {
    const auto add = [sign](std::size_t& total, std::size_t part) {
      total = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(total) +
                                       sign * static_cast<std::ptrdiff_t>(part));
    };
    add(stats_.levelTwoNodes, levelTwoNodes_[b].size());
    for (const std::uint32_t n : levelTwoNodes_[b])
      add(stats_.levelTwoEdges, levelTwoEdges_[n].size());
    add(levelTwoPathBytes_, levelTwoNodes_[b].size() * sizeof(std::uint32_t) +
                                (levelTwoPaths_[b].begin.size() + levelTwoPaths_[b].nodes.size()) *
                                    sizeof(std::uint32_t));
  };
  std::vector<std::size_t> todo;
  for (std::size_t b = 0; b < blocks; ++b) {
    if (!levelTwoClusters || (*levelTwoClusters)[b]) todo.push_back(b);
  }
  for (const std::size_t b : todo)
    count(b, -1);
  // A block's rebuild writes only what belongs to its own nodes, so blocks may be rebuilt on
  // several threads (AbstractionSpec::threads) once the per-node arrays have their size.
  if (levelTwoEdges_.size() < nodeCells_.size()) levelTwoEdges_.resize(nodeCells_.size());
  if (nodeLevelTwo_.size() < nodeCells_.size()) nodeLevelTwo_.resize(nodeCells_.size(), -1);
  std::vector<LevelTwoBuilder> builders(workersFor(todo.size(), spec_.threads),
                                        LevelTwoBuilder(*this));
  parallelFor(todo.size(), spec_.threads, [&](std::size_t worker, std::size_t i) {
    builders[worker].rebuild(static_cast<int>(todo[i]));
  });
  std::uint64_t settled = 0;
  for (const LevelTwoBuilder& builder : builders)
    settled += builder.settled();
  for (const std::size_t b : todo)
    count(b, +1);
#if WARPATH_INVARIANTS_ON
  for (const std::size_t b : todo)
    builders.front().check(static_cast<int>(b));
#endif
  stats_.levelTwoBytes = nodeLevelTwo_.size() * (sizeof(int) + sizeof(std::vector<AbstractEdge>)) +
                         stats_.levelTwoEdges * sizeof(AbstractEdge) + levelTwoPathBytes_;
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
  if (!levelTwoClusters) stats_.levelTwoMilliseconds = ms;
  return settled;
}

CellRect ClusterAbstraction::levelTwoClusterBounds(int levelTwoCluster) const {
  const int side = spec_.clusterSize * spec_.levelTwoSize;
  const int x = (levelTwoCluster % levelTwoX_) * side;
  const int y = (levelTwoCluster / levelTwoX_) * side;
  const GridMap& map = grid_->map();
  return {x, y, std::min(side, map.width() - x), std::min(side, map.height() - y)};
}

void ClusterAbstraction::appendLevelOneSteps(
    std::uint32_t from, const AbstractEdge& edge, Agent agent,
    std::vector<std::pair<std::uint32_t, const AbstractEdge*>>* out) const {
  const LevelTwoPaths& paths = levelTwoPaths_[static_cast<std::size_t>(nodeLevelTwo_[from])];
  const std::span<const std::uint32_t> passed(paths.nodes.data() + paths.begin[edge.path],
                                              paths.begin[edge.path + 1] - paths.begin[edge.path]);
  // The stored path runs from the edge's source; a reversed edge walks it back to its start,
  // `edge.target`.
  const std::size_t count = passed.size();
  const auto nodeAt = [&](std::size_t k) {  // k-th node from `from`, 0 = from
    if (!edge.reversed) return k == 0 ? from : passed[k - 1];
    return k == count ? edge.target : passed[count - 1 - k];
  };
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t a = nodeAt(k);
    const std::uint32_t b = nodeAt(k + 1);
    const AbstractEdge* best = nullptr;
    for (const AbstractEdge& e : edges_[a]) {
      if (e.target == b && e.usableBy(agent) && (!best || e.cost < best->cost)) best = &e;
    }
    WARPATH_INVARIANT(best != nullptr, "level 2: a level-1 step the agent cannot take");
    out->push_back({a, best});
  }
}

}  // namespace warpath::pathing
