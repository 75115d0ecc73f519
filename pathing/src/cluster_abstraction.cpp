#include "pathing/cluster_abstraction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <numeric>

#include "cluster_dijkstra.h"
#include "limit_messages.h"
#include "parallel_for.h"
#include "pathing/invariant.h"
#include "pathing/moves.h"

namespace warpath::pathing {

std::string problemWith(const AbstractionSpec& spec) {
  if (spec.clusterSize < 2 || spec.clusterSize > kMaxClusterSize)
    return limits::between("clusterSize", 2, kMaxClusterSize, spec.clusterSize);
  if (spec.maxAgentSize < 1 || spec.maxAgentSize > 255)
    return limits::between("maxAgentSize", 1, 255, spec.maxAgentSize);
  if (spec.capabilities.empty()) return "capabilities must not be empty (got none)";
  for (std::size_t i = 0; i < spec.capabilities.size(); ++i) {
    if (spec.capabilities[i].empty()) {
      return "capabilities[" + std::to_string(i) + "] must allow at least one terrain (got none)";
    }
  }
  if (spec.costs) {
    if (spec.capabilities.size() != 1) {
      return "capabilities must hold exactly one capability when costs are given (got " +
             std::to_string(spec.capabilities.size()) + ")";
    }
    if (!spec.capabilities[0].isSubsetOf(spec.costs->capability()))
      return "costs must give a cost to every terrain of capabilities[0]";
  }
  if (spec.levels < 1 || spec.levels > 2) return limits::between("levels", 1, 2, spec.levels);
  if (spec.threads < 1 || spec.threads > kMaxBuildThreads)
    return limits::between("threads", 1, kMaxBuildThreads, spec.threads);
  if (spec.levels == 2 && (spec.levelTwoSize < 2 || spec.levelTwoSize > 256))
    return limits::between("levelTwoSize", 2, 256, spec.levelTwoSize);
  return {};
}

AbstractionSpec weightedAbstractionSpec(Agent agent, const TerrainCosts& costs, int clusterSize,
                                        AbstractionQuality quality) {
  AbstractionSpec spec;
  spec.clusterSize = clusterSize;
  spec.maxAgentSize = agent.size;
  spec.capabilities = {agent.capability};
  spec.quality = quality;
  spec.costs = costs;
  return spec;
}

bool ClusterAbstraction::supports(Agent agent) const {
  return agent.size >= smallestAgentSize(spec_) && agent.size <= spec_.maxAgentSize &&
         std::find(spec_.capabilities.begin(), spec_.capabilities.end(), agent.capability) !=
             spec_.capabilities.end();
}

CellRect ClusterAbstraction::clusterBounds(int cluster) const {
  const int b = spec_.clusterSize;
  const int x = (cluster % clustersX_) * b;
  const int y = (cluster / clustersX_) * b;
  const GridMap& map = grid_->map();
  return {x, y, std::min(b, map.width() - x), std::min(b, map.height() - y)};
}

void ClusterAbstraction::appendEdgeCells(std::uint32_t from, const AbstractEdge& edge,
                                         std::vector<Cell>* out) const {
  WARPATH_INVARIANT(!edge.intra || edge.path != AbstractEdge::kNoPath,
                    "appendEdgeCells: an intra-edge without a cached path must be re-planned");
  if (edge.path == AbstractEdge::kNoPath) {
    out->push_back(nodeCells_[edge.target]);
    return;
  }
  const ClusterPaths& paths = paths_[static_cast<std::size_t>(clusterOf(nodeCells_[from]))];
  const auto first = paths.steps.begin() + paths.begin[edge.path];
  const auto last = paths.steps.begin() + paths.begin[edge.path + 1];
  Cell at = nodeCells_[from];
  const auto step = [&](int d) {
    at.x += kDirections[static_cast<std::size_t>(d)].dx;
    at.y += kDirections[static_cast<std::size_t>(d)].dy;
    out->push_back(at);
  };
  if (!edge.reversed) {
    for (auto it = first; it != last; ++it)
      step(*it);
  } else {
    for (auto it = last; it != first;)
      step(oppositeDirection(*--it));
  }
}

// Builds a ClusterAbstraction in stages: transitions and inter-edges per capability, then
// intra-edges per (capability, size), then dominance pruning, then the compact graph.
class AbstractionBuilder {
 public:
  // Builds a new graph (build()).
  AbstractionBuilder(const AnnotatedGrid& grid, AbstractionSpec spec)
      : grid_(grid),
        map_(grid.map()),
        maxSize_(spec.maxAgentSize),
        minSize_(smallestAgentSize(spec)),
        g_(out_) {
    g_.grid_ = &grid;
    g_.spec_ = std::move(spec);
    if (g_.spec_.costs) {
      g_.costs_.emplace(grid, Agent{maxSize_, g_.spec_.capabilities[0]}, *g_.spec_.costs);
    }
    const int b = g_.spec_.clusterSize;
    g_.clustersX_ = (map_.width() + b - 1) / b;
    g_.clustersY_ = (map_.height() + b - 1) / b;
    // Terrains absent from the map lie on no path, so capabilities equal on the map's
    // terrains share one clearance field and one set of edges, annotated with the smaller
    // (effective) capability, which every agent of the larger one may use.
    const Capability present = map_.terrainsPresent();
    for (Capability c : g_.spec_.capabilities)
      g_.effective_.push_back(Capability::fromMask(c.mask() & present.mask()));
    useEffectiveCapabilities();
    nodeOf_.assign(map_.cellCount(), kNone);
  }

  // Repairs `existing` in place (repair()).
  explicit AbstractionBuilder(ClusterAbstraction& existing)
      : grid_(existing.grid()),
        map_(existing.grid().map()),
        maxSize_(existing.spec_.maxAgentSize),
        minSize_(smallestAgentSize(existing.spec_)),
        g_(existing),
        repairing_(true) {
    useEffectiveCapabilities();
  }

  ClusterAbstraction build() {
    const auto began = std::chrono::steady_clock::now();
    // The agent layers the searches read, computed on the threads before they start.
    std::vector<Agent> agents;
    for (const Capability capability : capabilities_) {
      for (int size = minSize_; size <= maxSize_; ++size)
        agents.push_back({size, capability});
    }
    grid_.prepare(agents, g_.spec_.threads);
    findTransitions();
    findIntraEdges();
    pruneSamePairDominance();
    if (g_.spec_.quality == AbstractionQuality::Low) {
      pruneDominatedCrossings();
      pruneIntraCircuits();
    }
    assemble();
#if WARPATH_INVARIANTS_ON
    checkGraph();
#endif
    g_.stats_.buildExpanded = expanded_;
    g_.stats_.buildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
    return std::move(out_);
  }

  // Repairs g_ after the terrain of `area` changed (the grid's caches and g_'s costs already
  // repaired). The cells whose truncated clearance, moves or anchor costs can differ lie in
  // the area grown up and left by the largest size (clearance looks right and down) and by
  // one more each way (moves look at neighbours); the clusters holding such cells find their
  // intra-edges again, the borders whose two strips hold any find their entrances again, and
  // so do the clusters beside those borders (their transitions change).
  void repair(CellRect area, RepairStats& stats, std::vector<bool>& redo) {
    const CellRect reach = map_.clip({area.x - maxSize_, area.y - maxSize_,
                                      area.width + maxSize_ + 1, area.height + maxSize_ + 1});
    const int clusters = g_.clusterCount();
    redo.assign(static_cast<std::size_t>(clusters), false);
    std::vector<std::pair<int, bool>> borders;  // (cluster, east)
    const int b = g_.spec_.clusterSize;
    const int cx0 = reach.x / b;
    const int cy0 = reach.y / b;
    const int cx1 = (reach.x + reach.width - 1) / b;
    const int cy1 = (reach.y + reach.height - 1) / b;
    // Borders west of or above the reached clusters count too: their strips may hold a cell.
    for (int cy = std::max(0, cy0 - 1); cy <= cy1; ++cy) {
      for (int cx = std::max(0, cx0 - 1); cx <= cx1; ++cx) {
        const int k = cy * g_.clustersX_ + cx;
        const CellRect r = g_.clusterBounds(k);
        if (cx >= cx0 && cy >= cy0) redo[static_cast<std::size_t>(k)] = true;
        if (cx + 1 < g_.clustersX_ && reach.overlaps({r.x + b - 1, r.y, 2, r.height})) {
          borders.push_back({k, true});
          redo[static_cast<std::size_t>(k)] = redo[static_cast<std::size_t>(k + 1)] = true;
        }
        if (cy + 1 < g_.clustersY_ && reach.overlaps({r.x, r.y + b - 1, r.width, 2})) {
          borders.push_back({k, false});
          redo[static_cast<std::size_t>(k)] = redo[static_cast<std::size_t>(k + g_.clustersX_)] =
              true;
        }
      }
    }
    const Tally before = tally(redo);
    // Take out the old crossings of those borders and the old intra-edges of those clusters.
    for (const auto& [k, east] : borders) {
      const CellRect r = g_.clusterBounds(k);
      for (std::uint32_t n : g_.nodesInCluster(k)) {
        const Cell c = g_.nodeCells_[n];
        if (east ? c.x != r.x + b - 1 : c.y != r.y + b - 1) continue;
        const Cell across = east ? Cell{c.x + 1, c.y} : Cell{c.x, c.y + 1};
        dropEdges(n, [&](const AbstractEdge& e) {
          return !e.intra && g_.nodeCells_[e.target] == across;
        });
      }
    }
    for (int k = 0; k < clusters; ++k) {
      if (!redo[static_cast<std::size_t>(k)]) continue;
      for (std::uint32_t n : g_.nodesInCluster(k))
        dropEdges(n, [](const AbstractEdge& e) { return e.intra; });
      g_.paths_[static_cast<std::size_t>(k)] = {};
      ++stats.clusters;
    }
    // Nodes still crossing a border stay: they join the clusters' new intra-edges.
    for (int k = 0; k < clusters; ++k) {
      if (!redo[static_cast<std::size_t>(k)]) continue;
      for (std::uint32_t n : g_.nodesInCluster(k)) {
        if (g_.edges_[n].empty()) continue;
        const std::uint32_t local = nodeAt(g_.nodeCells_[n]);
        persisting_.resize(nodeCells_.size(), false);
        persisting_[local] = true;
      }
    }
    for (const auto& [k, east] : borders)
      scanBorder(k, east);
    stats.borders = static_cast<int>(borders.size());
    persisting_.resize(nodeCells_.size(), false);
    findIntraEdges();
    pruneSamePairDominance();
    if (g_.spec_.quality == AbstractionQuality::Low) {
      pruneDominatedCrossings();
      pruneIntraCircuits();
    }
    // Builder nodes to graph nodes: the one already at the cell, else a free id, else a new one.
    std::vector<bool> live(nodeCells_.size(), false);
    for (const Candidate& e : candidates_) {
      if (!e.removed) live[e.a] = live[e.b] = true;
    }
    std::map<std::uint32_t, std::uint32_t> existing;  // cell index -> graph node
    for (int k = 0; k < clusters; ++k) {
      if (!redo[static_cast<std::size_t>(k)]) continue;
      for (std::uint32_t n : g_.nodesInCluster(k))
        existing.emplace(map_.indexOf(g_.nodeCells_[n]), n);
    }
    std::vector<std::uint32_t> id(nodeCells_.size(), kNone);
    for (std::uint32_t local = 0; local < nodeCells_.size(); ++local) {
      if (!live[local] && !persisting_[local]) continue;
      const auto it = existing.find(map_.indexOf(nodeCells_[local]));
      if (it != existing.end()) {
        id[local] = it->second;
      } else if (!g_.freeNodes_.empty()) {
        id[local] = g_.freeNodes_.back();
        g_.freeNodes_.pop_back();
        g_.nodeCells_[id[local]] = nodeCells_[local];
      } else {
        id[local] = static_cast<std::uint32_t>(g_.nodeCells_.size());
        g_.nodeCells_.push_back(nodeCells_[local]);
        g_.edges_.emplace_back();
      }
    }
    addEdges(id);
    // The clusters' node lists again; nodes left without edges are freed.
    for (int k = 0; k < clusters; ++k) {
      if (!redo[static_cast<std::size_t>(k)]) continue;
      std::vector<std::uint32_t>& nodes = g_.clusterNodes_[static_cast<std::size_t>(k)];
      for (std::uint32_t local = 0; local < nodeCells_.size(); ++local) {
        if (id[local] != kNone && g_.clusterOf(nodeCells_[local]) == k &&
            std::find(nodes.begin(), nodes.end(), id[local]) == nodes.end())
          nodes.push_back(id[local]);
      }
      std::erase_if(nodes, [&](std::uint32_t n) {
        if (!g_.edges_[n].empty()) return false;
        g_.nodeCells_[n] = {-1, -1};
        g_.freeNodes_.push_back(n);
        return true;
      });
      std::sort(nodes.begin(), nodes.end(), [&](std::uint32_t l, std::uint32_t r) {
        return map_.indexOf(g_.nodeCells_[l]) < map_.indexOf(g_.nodeCells_[r]);
      });
    }
    // Free ids are reused lowest first.
    std::sort(g_.freeNodes_.begin(), g_.freeNodes_.end(), std::greater<>());
    updateStats(before, tally(redo));
    stats.expanded = expanded_;
#if WARPATH_INVARIANTS_ON
    checkGraph();
#endif
  }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;

  // Removes node n's edges that match, and their reverses at the other end.
  template <class Match>
  void dropEdges(std::uint32_t n, Match match) {
    std::vector<AbstractEdge>& edges = g_.edges_[n];
    for (const AbstractEdge& e : edges) {
      if (!match(e)) continue;
      std::erase_if(g_.edges_[e.target],
                    [&](const AbstractEdge& back) { return back.isReverseOf(e, n); });
    }
    std::erase_if(edges, match);
  }

  void useEffectiveCapabilities() {
    if (g_.costs_) costs_ = &*g_.costs_;
    for (Capability effective : g_.effective_) {
      if (effective.empty() ||
          std::find(capabilities_.begin(), capabilities_.end(), effective) != capabilities_.end())
        continue;
      capabilities_.push_back(effective);
      fields_.push_back(&grid_.clearance(effective));
    }
  }
  // Shorter runs of one crossing cost stay part of their neighbour's entrance. Measured with
  // infantry costs (docs/benchmarks.md): splitting at every change gave 9,600 nodes on the
  // 512² patchwork map and 2.2 % HQ error; 6 cells, 8,000 nodes, the same error and 20 % faster
  // queries; never splitting, 6,000 nodes but 3.1 % error.
  static constexpr std::size_t kMinCostRun = 6;
  // HQ: a weighted entrance at least this long also gets a transition at each end (as HPA*
  // does for long entrances): cheap routes hug a wall or a terrain's edge, and straight
  // smoothing cannot pull a route off a mid-entrance crossing when the straight line would
  // cross dearer terrain. Measured (docs/benchmarks.md): HQ error 1.54 -> 0.65 % on
  // heart2heart, 1.38 -> 0.50 % on AR0011SR, 2.29 -> 1.12 % on dustwallowkeys, 2.15 -> 1.40 %
  // on the patchwork map, for 35-70 % more time on random queries. The ends alone (no middle)
  // cost 11 % more on swamp_detour, whose best crossing is mid-border; LQ keeps one.
  static constexpr std::size_t kEndsRun = 10;

  struct Candidate {
    std::uint32_t a = 0;  // node ids, a < b
    std::uint32_t b = 0;
    double cost = 0.0;
    Capability capability;
    std::uint8_t clearance = 0;
    bool intra = false;
    bool removed = false;
    std::uint32_t path = kNone;  // steps a -> b in paths_
  };

  // Clearance of `cell` for capability `ci`, truncated to the largest agent size: beyond
  // it, differences cannot matter to any agent the graph serves. Below the smallest (a
  // weighted graph serves one size) the cell is as closed as a wall.
  int truncated(std::size_t ci, Cell cell) const {
    const int clearance = std::min<int>(fields_[ci]->at(cell), maxSize_);
    return clearance < minSize_ ? 0 : clearance;
  }

  // What crossing from `from` to its orthogonal neighbour `to` costs: 1, or the weighted
  // graph's agent's travel time.
  double crossingCost(Cell from, Cell to) const {
    return costs_ ? costs_->moveCost(from, directionOf(to.x - from.x, to.y - from.y)) : 1.0;
  }

  std::uint32_t nodeAt(Cell cell) {
    // A repair sees a few dozen nodes: a map from cell to node instead of a whole-map array.
    std::uint32_t& id = repairing_
                            ? repairNodeOf_.try_emplace(map_.indexOf(cell), kNone).first->second
                            : nodeOf_[map_.indexOf(cell)];
    if (id == kNone) {
      id = static_cast<std::uint32_t>(nodeCells_.size());
      nodeCells_.push_back(cell);
    }
    return id;
  }

  void addInterEdge(Cell first, Cell second, std::size_t ci, int clearance) {
    std::uint32_t a = nodeAt(first);
    std::uint32_t b = nodeAt(second);
    if (a > b) std::swap(a, b);
    Candidate e;
    e.a = a;
    e.b = b;
    e.cost = crossingCost(first, second);
    e.capability = capabilities_[ci];
    e.clearance = static_cast<std::uint8_t>(clearance);
    candidates_.push_back(e);
  }

  // One border: pairs (inside[i], outside[i]) of adjacent cells in two clusters, in scan
  // order (left to right, or top to bottom, the directions in which clearance can only rise
  // by jumps and fall by one). Entrances are maximal runs of pairs open for the capability
  // whose clearances never rise on either side; each gets one transition at the pair of largest
  // clearance nearest the entrance's middle. In a weighted graph (one agent size, so every
  // open pair has the same truncated clearance) an entrance also ends where the cost of crossing
  // changes once it is kMinCostRun pairs long, and its transition is its cheapest crossing
  // nearest the middle: a border half swamp, half ground gets one on each half. In HQ a
  // weighted entrance kEndsRun pairs long or more also gets one at each end.
  void scanBorder(std::span<const Cell> first, std::span<const Cell> second) {
    const std::size_t n = first.size();
    for (std::size_t ci = 0; ci < fields_.size(); ++ci) {
      std::size_t i = 0;
      while (i < n) {
        int cvA = truncated(ci, first[i]);
        int cvB = truncated(ci, second[i]);
        if (cvA == 0 || cvB == 0) {
          ++i;
          continue;
        }
        const std::size_t begin = i;
        // Clearances never rise along the run, so the maximal pairs are a prefix of it.
        const int best = std::min(cvA, cvB);
        double cost = crossingCost(first[i], second[i]);
        std::size_t bestEnd = i;
        for (++i; i < n; ++i) {
          const int nextA = truncated(ci, first[i]);
          const int nextB = truncated(ci, second[i]);
          if (nextA == 0 || nextB == 0 || nextA > cvA || nextB > cvB) break;
          if (costs_ && i - begin >= kMinCostRun && crossingCost(first[i], second[i]) != cost)
            break;
          cvA = nextA;
          cvB = nextB;
          if (std::min(cvA, cvB) == best) bestEnd = i;
        }
        const std::size_t middle = (begin + i - 1) / 2;
        std::size_t chosen = std::min(middle, bestEnd);
        if (costs_) {
          // Weighted: the cheapest crossing of the run, nearest its middle.
          const auto fromMiddle = [&](std::size_t k) {
            return k > middle ? k - middle : middle - k;
          };
          cost = crossingCost(first[chosen], second[chosen]);
          for (std::size_t k = begin; k < i; ++k) {
            const double c = crossingCost(first[k], second[k]);
            if (c < cost || (c == cost && fromMiddle(k) < fromMiddle(chosen))) {
              cost = c;
              chosen = k;
            }
          }
        }
        addInterEdge(first[chosen], second[chosen], ci, best);
        if (costs_ && g_.spec_.quality == AbstractionQuality::High && i - begin >= kEndsRun) {
          addInterEdge(first[begin], second[begin], ci, best);
          addInterEdge(first[i - 1], second[i - 1], ci, best);
        }
      }
    }
  }

  void findTransitions() {
    for (int k = 0; k < g_.clusterCount(); ++k) {
      if (k % g_.clustersX_ + 1 < g_.clustersX_) scanBorder(k, true);
      if (k / g_.clustersX_ + 1 < g_.clustersY_) scanBorder(k, false);
    }
  }

  // The border of cluster k with its east (or south) neighbour.
  void scanBorder(int k, bool east) {
    const int b = g_.spec_.clusterSize;
    const CellRect r = g_.clusterBounds(k);
    first_.clear();
    second_.clear();
    if (east) {
      for (int y = r.y; y < r.y + r.height; ++y) {
        first_.push_back({r.x + b - 1, y});
        second_.push_back({r.x + b, y});
      }
    } else {
      for (int x = r.x; x < r.x + r.width; ++x) {
        first_.push_back({x, r.y + b - 1});
        second_.push_back({x, r.y + b});
      }
    }
    scanBorder(first_, second_);
  }

  // What the searches of one cluster for one capability add: its intra-edge candidates, their
  // paths numbered from 0. These are searched apart (on several threads with
  // AbstractionSpec::threads) and added to the graph in the order of (cluster, capability), so
  // the graph is the same for any number of threads.
  struct ClusterEdges {
    std::vector<Candidate> candidates;
    std::vector<std::uint32_t> pathBegin;
    std::vector<std::uint8_t> pathSteps;
    std::uint64_t expanded = 0;
  };

  // The scratch one thread reuses from cluster to cluster.
  struct IntraScratch {
    ClusterDijkstra dijkstra;
    RegionMoves moves;
    RegionComponents parts;
    std::vector<std::uint8_t> cv;
    std::vector<Cell> targets;
    std::vector<std::uint32_t> targetNodes;
    std::vector<std::uint8_t> steps;
    std::vector<int> coveredTo;
  };

  // For every cluster, capability and size: one Dijkstra per transition reaches all the
  // others. A size-s search whose paths to every higher-numbered node also admit size s+1
  // answers the size-(s+1) search too (those paths stay optimal), so it is skipped.
  void findIntraEdges() {
    const int clusters = g_.clusterCount();
    std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(clusters));
    for (std::uint32_t n = 0; n < nodeCells_.size(); ++n)
      members[static_cast<std::size_t>(g_.clusterOf(nodeCells_[n]))].push_back(n);
    std::vector<std::pair<int, std::size_t>> todo;  // (cluster, capability)
    for (int k = 0; k < clusters; ++k) {
      if (members[static_cast<std::size_t>(k)].size() < 2) continue;
      for (std::size_t ci = 0; ci < fields_.size(); ++ci)
        todo.push_back({k, ci});
    }
    if (workersFor(todo.size(), g_.spec_.threads) == 1) {
      IntraScratch scratch;
      ClusterEdges found;
      for (const auto& [k, ci] : todo) {
        searchCluster(k, ci, members[static_cast<std::size_t>(k)], scratch, found);
        addClusterEdges(found);
      }
      return;
    }
    // The results wait in task order, each thread with its own scratch.
    std::vector<ClusterEdges> found(todo.size());
    std::vector<IntraScratch> scratch(workersFor(todo.size(), g_.spec_.threads));
    parallelFor(todo.size(), g_.spec_.threads, [&](std::size_t worker, std::size_t i) {
      const auto& [k, ci] = todo[i];
      searchCluster(k, ci, members[static_cast<std::size_t>(k)], scratch[worker], found[i]);
    });
    for (const ClusterEdges& edges : found)
      addClusterEdges(edges);
  }

  // The intra-edges of cluster k, whose nodes are `nodes`, for capability ci, into `out`
  // (emptied first). Reads the builder and the grid only, so clusters may be searched on several
  // threads at once.
  void searchCluster(int k, std::size_t ci, const std::vector<std::uint32_t>& nodes,
                     IntraScratch& s, ClusterEdges& out) const {
    out.candidates.clear();
    out.pathBegin.clear();
    out.pathSteps.clear();
    out.expanded = 0;
    const CellRect region = g_.clusterBounds(k);
    const Capability capability = capabilities_[ci];
    // The cluster's truncated clearances, indexed as the searches index cells.
    s.cv.assign(regionCells(region), 0);
    for (int y = region.y; y < region.y + region.height; ++y) {
      for (int x = region.x; x < region.x + region.width; ++x)
        s.cv[regionIndex(region, {x, y})] = static_cast<std::uint8_t>(truncated(ci, {x, y}));
    }
    const auto clearanceAt = [&](Cell c) { return int{s.cv[regionIndex(region, c)]}; };
    // coveredTo[i]: sizes up to this are already answered for sources nodes[i].
    s.coveredTo.assign(nodes.size(), 0);
    for (int size = minSize_; size <= maxSize_; ++size) {
      const AgentLayer& layer = grid_.layer({size, capability});
      // Targets the search cannot reach inside the cluster are left out, and sources that
      // reach none are not searched from: it finds the same paths, sooner.
      s.moves.load(map_, layer, region);
      s.parts.label(s.moves);
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        const Cell source = nodeCells_[nodes[i]];
        if (clearanceAt(source) < size || s.coveredTo[i] >= size) continue;
        const std::uint32_t part = s.parts.partOf(source);
        if (part == 0) continue;
        s.targets.clear();
        s.targetNodes.clear();
        for (std::size_t j = i + 1; j < nodes.size(); ++j) {
          if (clearanceAt(nodeCells_[nodes[j]]) < size ||
              s.parts.partOf(nodeCells_[nodes[j]]) != part)
            continue;
          s.targets.push_back(nodeCells_[nodes[j]]);
          s.targetNodes.push_back(nodes[j]);
        }
        if (s.targets.empty()) continue;
        s.dijkstra.run(s.moves, source, s.targets, costs_);
        out.expanded += s.dijkstra.expanded();
        int covers = maxSize_;
        for (std::size_t t = 0; t < s.targets.size(); ++t) {
          if (!s.dijkstra.reached(s.targets[t])) continue;
          s.steps.clear();
          s.dijkstra.appendSteps(s.targets[t], &s.steps);
          // The largest size for which every step stays legal.
          const int clearance = s.dijkstra.smallestAlong(s.steps, s.cv);
          covers = std::min(covers, clearance);
          addIntraEdge(nodes[i], s.targetNodes[t], s.dijkstra.cost(s.targets[t]), capability,
                       clearance, s.steps, out);
        }
        s.coveredTo[i] = covers;
      }
    }
  }

  static void addIntraEdge(std::uint32_t from, std::uint32_t to, double cost, Capability capability,
                           int clearance, const std::vector<std::uint8_t>& steps,
                           ClusterEdges& out) {
    Candidate e;
    e.a = std::min(from, to);
    e.b = std::max(from, to);
    e.cost = cost;
    e.capability = capability;
    e.clearance = static_cast<std::uint8_t>(clearance);
    e.intra = true;
    e.path = static_cast<std::uint32_t>(out.pathBegin.size());
    out.pathBegin.push_back(static_cast<std::uint32_t>(out.pathSteps.size()));
    if (from < to) {
      out.pathSteps.insert(out.pathSteps.end(), steps.begin(), steps.end());
    } else {  // stored a -> b: reverse the walk
      for (auto it = steps.rbegin(); it != steps.rend(); ++it)
        out.pathSteps.push_back(static_cast<std::uint8_t>(oppositeDirection(*it)));
    }
    out.candidates.push_back(e);
  }

  // One cluster's edges after those of the clusters before it, as if searched in place.
  void addClusterEdges(const ClusterEdges& edges) {
    const auto pathBase = static_cast<std::uint32_t>(pathBegin_.size());
    const auto stepBase = static_cast<std::uint32_t>(pathSteps_.size());
    for (Candidate e : edges.candidates) {
      e.path += pathBase;
      candidates_.push_back(e);
    }
    for (const std::uint32_t begin : edges.pathBegin)
      pathBegin_.push_back(begin + stepBase);
    pathSteps_.insert(pathSteps_.end(), edges.pathSteps.begin(), edges.pathSteps.end());
    expanded_ += edges.expanded;
  }

  // e2 serves every agent e1 serves: needs no terrain e1 does not and admits any size e1 does.
  static bool servesAllOf(const Candidate& e2, const Candidate& e1) {
    return e2.capability.isSubsetOf(e1.capability) && e2.clearance >= e1.clearance;
  }

  // Between the same two nodes, drop an edge when another serves all its agents: at no
  // greater cost (strong dominance, HQ), or at any cost (weak dominance, LQ). Of edges that
  // dominate each other, the cheapest (then the first built) stays.
  void pruneSamePairDominance() {
    const bool weak = g_.spec_.quality == AbstractionQuality::Low;
    // Candidates in (a, b, cost, id) order: counted out by a (stable), then each node's few
    // sorted by the rest, cheaper than one sort of them all.
    std::vector<std::uint32_t> begins(nodeCells_.size() + 1, 0);
    for (const Candidate& e : candidates_)
      ++begins[e.a + 1];
    std::partial_sum(begins.begin(), begins.end(), begins.begin());
    std::vector<std::uint32_t> order(candidates_.size());
    std::vector<std::uint32_t> next(begins.begin(), begins.end() - 1);
    for (std::uint32_t id = 0; id < candidates_.size(); ++id)
      order[next[candidates_[id].a]++] = id;
    for (std::size_t a = 0; a + 1 < begins.size(); ++a) {
      std::sort(order.begin() + begins[a], order.begin() + begins[a + 1],
                [&](std::uint32_t l, std::uint32_t r) {
                  const Candidate& x = candidates_[l];
                  const Candidate& y = candidates_[r];
                  if (x.b != y.b) return x.b < y.b;
                  if (x.cost != y.cost) return x.cost < y.cost;
                  return l < r;
                });
    }
    constexpr double kSameCost = 1e-9;
    for (std::size_t begin = 0; begin < order.size();) {
      std::size_t end = begin + 1;
      while (end < order.size() && candidates_[order[end]].a == candidates_[order[begin]].a &&
             candidates_[order[end]].b == candidates_[order[begin]].b)
        ++end;
      // Sorted by cost: an edge can only be strongly dominated by an earlier one.
      for (std::size_t i = begin; i < end; ++i) {
        Candidate& e1 = candidates_[order[i]];
        for (std::size_t j = begin; j < end && !e1.removed; ++j) {
          if (j == i) continue;
          const Candidate& e2 = candidates_[order[j]];
          if (e2.removed || !servesAllOf(e2, e1)) continue;
          const bool cheaper = e2.cost <= e1.cost + kSameCost;
          const bool mutual = servesAllOf(e1, e2);
          // Mutually dominating edges: the earlier in cost order stays.
          if ((weak || cheaper) && (!mutual || j < i)) e1.removed = true;
        }
      }
      begin = end;
    }
  }

  // LQ: a crossing (inter-edge a-b) is dominated when another crossing a'-b' of the same
  // two clusters serves all its agents and a-a', b-b' are joined by intra-edges that do too,
  // together no longer than a cluster side; it is dropped, and transitions left without any
  // crossing go with their intra-edges. The intra-edges among the remaining nodes still join every
  // pair an agent can join inside a cluster, so detours through a removed node are not needed.
  void pruneDominatedCrossings() {
    // Weak dominance alone would accept any detour; between rooms whose doors lie a cluster
    // apart that made LQ paths 6 % longer on 8room_000 (1 % with this bound, measured).
    const double maxDetour = g_.spec_.clusterSize * (costs_ ? costs_->cheapest() : 1.0);
    rebuildAdjacency();
    for (std::uint32_t id = 0; id < candidates_.size(); ++id) {
      Candidate& e = candidates_[id];
      if (e.removed || e.intra) continue;
      bool dominated = false;
      for (std::uint32_t ia : adjacency_[e.a]) {
        const Candidate& toA = candidates_[ia];
        if (toA.removed || !toA.intra || !servesAllOf(toA, e)) continue;
        const std::uint32_t a2 = toA.a == e.a ? toA.b : toA.a;
        for (std::uint32_t ic : adjacency_[a2]) {
          const Candidate& cross = candidates_[ic];
          if (ic == id || cross.removed || cross.intra || !servesAllOf(cross, e)) continue;
          const std::uint32_t b2 = cross.a == a2 ? cross.b : cross.a;
          const double detour = toA.cost + (b2 == e.b ? 0.0 : linkCost(b2, e.b, e));
          dominated = detour <= maxDetour;
          if (dominated) break;
        }
        if (dominated) break;
      }
      if (dominated) e.removed = true;
    }
    // Transitions without a crossing left serve no agent: drop them and their edges.
    // A repair's nodes that keep crossings of borders it did not scan again stay too.
    std::vector<bool> keeps(nodeCells_.size(), false);
    for (std::uint32_t n = 0; n < persisting_.size(); ++n)
      keeps[n] = persisting_[n];
    for (const Candidate& e : candidates_) {
      if (!e.removed && !e.intra) keeps[e.a] = keeps[e.b] = true;
    }
    for (Candidate& e : candidates_) {
      if (!keeps[e.a] || !keeps[e.b]) e.removed = true;
    }
  }

  // The cheapest live intra-edge joining x and y that serves every agent `e` serves, or
  // infinity.
  double linkCost(std::uint32_t x, std::uint32_t y, const Candidate& e) const {
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t i : adjacency_[x]) {
      const Candidate& c = candidates_[i];
      if (!c.removed && c.intra && (c.a == y || c.b == y) && servesAllOf(c, e)) {
        best = std::min(best, c.cost);
      }
    }
    return best;
  }

  // LQ: an intra-edge u-v is dominated by a circuit u-w-v of live intra-edges that each serve
  // all its agents, as long as the detour costs at most kCircuitSlack times the edge (weak
  // dominance alone would accept any detour; the bound keeps LQ paths from wandering).
  void pruneIntraCircuits() {
    constexpr double kCircuitSlack = 1.2;
    rebuildAdjacency();
    std::vector<std::uint32_t> order;
    for (std::uint32_t id = 0; id < candidates_.size(); ++id) {
      if (!candidates_[id].removed && candidates_[id].intra) order.push_back(id);
    }
    // Longest first: long edges are the likeliest to pass near a third transition.
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t l, std::uint32_t r) {
      return candidates_[l].cost > candidates_[r].cost;
    });
    for (std::uint32_t id : order) {
      Candidate& e = candidates_[id];
      for (std::uint32_t iu : adjacency_[e.a]) {
        const Candidate& first = candidates_[iu];
        if (iu == id || first.removed || !first.intra || !servesAllOf(first, e)) continue;
        const std::uint32_t w = first.a == e.a ? first.b : first.a;
        if (w == e.b) continue;
        for (std::uint32_t iw : adjacency_[w]) {
          const Candidate& second = candidates_[iw];
          if (second.removed || !second.intra || !servesAllOf(second, e)) continue;
          if ((second.a == w ? second.b : second.a) != e.b) continue;
          if (first.cost + second.cost <= kCircuitSlack * e.cost) {
            e.removed = true;
            break;
          }
        }
        if (e.removed) break;
      }
    }
  }

  void rebuildAdjacency() {
    adjacency_.assign(nodeCells_.size(), {});
    for (std::uint32_t id = 0; id < candidates_.size(); ++id) {
      if (candidates_[id].removed) continue;
      adjacency_[candidates_[id].a].push_back(id);
      adjacency_[candidates_[id].b].push_back(id);
    }
  }

  // The graph: live nodes renumbered cluster by cluster, each node's edges (each undirected
  // edge stored once per endpoint), and the cached paths that live edges use.
  void assemble() {
    std::vector<bool> live(nodeCells_.size(), false);
    for (const Candidate& e : candidates_) {
      if (!e.removed) live[e.a] = live[e.b] = true;
    }
    std::vector<std::uint32_t> order;
    for (std::uint32_t n = 0; n < nodeCells_.size(); ++n) {
      if (live[n]) order.push_back(n);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t l, std::uint32_t r) {
      const int cl = g_.clusterOf(nodeCells_[l]);
      const int cr = g_.clusterOf(nodeCells_[r]);
      if (cl != cr) return cl < cr;
      return map_.indexOf(nodeCells_[l]) < map_.indexOf(nodeCells_[r]);
    });
    std::vector<std::uint32_t> newId(nodeCells_.size(), kNone);
    for (std::uint32_t i = 0; i < order.size(); ++i)
      newId[order[i]] = i;

    const std::size_t nodeCount = order.size();
    g_.nodeCells_.resize(nodeCount);
    for (std::uint32_t i = 0; i < nodeCount; ++i)
      g_.nodeCells_[i] = nodeCells_[order[i]];
    g_.clusterNodes_.assign(static_cast<std::size_t>(g_.clusterCount()), {});
    for (std::uint32_t i = 0; i < nodeCount; ++i)
      g_.clusterNodes_[static_cast<std::size_t>(g_.clusterOf(g_.nodeCells_[i]))].push_back(i);
    g_.edges_.assign(nodeCount, {});
    g_.paths_.assign(static_cast<std::size_t>(g_.clusterCount()), {});
    addEdges(newId);
    g_.stats_ = {};
    updateStats({}, tally(std::vector<bool>(g_.paths_.size(), true)));
  }

  // Adds the live candidates to the graph, each undirected edge once per endpoint in candidate
  // order, with their cached paths in their cluster's. `id` maps builder nodes to graph nodes.
  void addEdges(const std::vector<std::uint32_t>& id) {
    const bool cachePaths = g_.spec_.cachePaths;
    for (const Candidate& e : candidates_) {
      if (e.removed) continue;
      std::uint32_t path = AbstractEdge::kNoPath;
      if (e.intra && cachePaths) {
        ClusterAbstraction::ClusterPaths& paths =
            g_.paths_[static_cast<std::size_t>(g_.clusterOf(nodeCells_[e.a]))];
        path = static_cast<std::uint32_t>(paths.begin.size() - 1);
        const auto first = pathSteps_.begin() + pathBegin_[e.path];
        const auto last = e.path + 1 < pathBegin_.size()
                              ? pathSteps_.begin() + pathBegin_[e.path + 1]
                              : pathSteps_.end();
        paths.steps.insert(paths.steps.end(), first, last);
        paths.begin.push_back(static_cast<std::uint32_t>(paths.steps.size()));
      }
      AbstractEdge forward;
      forward.target = id[e.b];
      forward.path = path;
      forward.cost = e.cost;
      forward.capability = e.capability;
      forward.clearance = e.clearance;
      forward.intra = e.intra;
      AbstractEdge backward = forward;
      backward.target = id[e.a];
      backward.reversed = true;
      g_.edges_[id[e.a]].push_back(forward);
      g_.edges_[id[e.b]].push_back(backward);
    }
  }

  // What the nodes of some clusters hold: edges (each counted at both ends when both lie in
  // them), live nodes, cached path bytes.
  struct Tally {
    std::size_t inter = 0;
    std::size_t intra = 0;
    std::size_t nodes = 0;
    std::size_t pathBytes = 0;
  };
  Tally tally(const std::vector<bool>& clusters) const {
    Tally t;
    for (std::size_t k = 0; k < clusters.size(); ++k) {
      if (!clusters[k]) continue;
      for (std::uint32_t n : g_.clusterNodes_[k]) {
        t.nodes += g_.edges_[n].empty() ? 0 : 1;
        for (const AbstractEdge& e : g_.edges_[n])
          ++(e.intra ? t.intra : t.inter);
      }
      const ClusterAbstraction::ClusterPaths& paths = g_.paths_[k];
      t.pathBytes += (paths.begin.size() - 1) * sizeof(std::uint32_t) + paths.steps.size();
    }
    return t;
  }

  // The statistics of the whole graph; after a repair, from what the repaired clusters held
  // before and hold now (every edge a repair changes has both ends in them).
  void updateStats(const Tally& before, const Tally& after) {
    AbstractionStats& stats = g_.stats_;
    stats.clusters = g_.clusterCount();
    const auto delta = [](std::size_t now, std::size_t then) {
      return static_cast<std::ptrdiff_t>(now) - static_cast<std::ptrdiff_t>(then);
    };
    const auto add = [](std::size_t& total, std::ptrdiff_t change) {
      total = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(total) + change);
    };
    add(stats.nodes, delta(after.nodes, before.nodes));
    add(stats.interEdges, delta(after.inter, before.inter) / 2);
    add(stats.intraEdges, delta(after.intra, before.intra) / 2);
    add(stats.pathBytes, delta(after.pathBytes, before.pathBytes));
    stats.graphBytes = g_.nodeCells_.size() * (sizeof(Cell) + sizeof(std::vector<AbstractEdge>)) +
                       2 * (stats.interEdges + stats.intraEdges) * sizeof(AbstractEdge) +
                       g_.clusterNodes_.size() * sizeof(std::vector<std::uint32_t>) +
                       stats.nodes * sizeof(std::uint32_t);
  }

  // Debug and sanitizer builds: the assembled graph is what queries rely on. Every node lies
  // in the cluster that lists it; every edge has its reverse with the same annotation; an
  // inter-edge joins orthogonal neighbours in two clusters; an intra-edge stays in one cluster
  // and its cached path walks from its source to its target at the edge's cost, by moves legal
  // for the largest agent it admits.
  [[maybe_unused]] void checkGraph() const {
    const ClusterAbstraction& g = out_;
    for (int k = 0; k < g.clusterCount(); ++k) {
      for (std::uint32_t n : g.nodesInCluster(k))
        WARPATH_INVARIANT(g.clusterOf(g.nodeCell(n)) == k, "abstraction: node in wrong cluster");
    }
    std::vector<Cell> cells;
    for (std::uint32_t n = 0; n < g.nodeCount(); ++n) {
      const Cell from = g.nodeCell(n);
      for (const AbstractEdge& e : g.edgesOf(n)) {
        WARPATH_INVARIANT(e.target < g.nodeCount() && e.target != n,
                          "abstraction: edge target out of range");
        WARPATH_INVARIANT(e.clearance >= 1 && !e.capability.empty(),
                          "abstraction: edge serves no agent");
        const auto back = g.edgesOf(e.target);
        WARPATH_INVARIANT(std::any_of(back.begin(), back.end(),
                                      [&](const AbstractEdge& r) { return r.isReverseOf(e, n); }),
                          "abstraction: edge without its reverse");
        const Cell to = g.nodeCell(e.target);
        if (!e.intra) {
          WARPATH_INVARIANT(std::abs(to.x - from.x) + std::abs(to.y - from.y) == 1 &&
                                g.clusterOf(to) != g.clusterOf(from) &&
                                e.cost == crossingCost(from, to),
                            "abstraction: inter-edge must cross a border in one step");
          continue;
        }
        WARPATH_INVARIANT(g.clusterOf(to) == g.clusterOf(from),
                          "abstraction: intra-edge must stay in its cluster");
        if (e.path == AbstractEdge::kNoPath) continue;
        cells.assign(1, from);
        g.appendEdgeCells(n, e, &cells);
        const AgentLayer& layer = grid_.layer({e.clearance, e.capability});
        const CellRect bounds = g.clusterBounds(g.clusterOf(from));
        for (std::size_t i = 1; i < cells.size(); ++i) {
          const int d = directionOf(cells[i].x - cells[i - 1].x, cells[i].y - cells[i - 1].y);
          WARPATH_INVARIANT(d >= 0 && (layer.moveMasks()[map_.indexOf(cells[i - 1])] & (1u << d)),
                            "abstraction: cached path step illegal for the edge's agents");
          WARPATH_INVARIANT(bounds.contains(cells[i]), "abstraction: cached path leaves cluster");
        }
        const double walked = costs_ ? costs_->pathCost(cells) : pathCost(cells);
        WARPATH_INVARIANT(cells.back() == to && std::abs(walked - e.cost) < 1e-6,
                          "abstraction: cached path must reach the target at the edge's cost");
      }
    }
  }

  const AnnotatedGrid& grid_;
  const GridMap& map_;
  int maxSize_;
  int minSize_;                       // smallest agent served: 1, or maxSize_ in a weighted graph
  const CostField* costs_ = nullptr;  // the weighted graph's agent's costs, in g_
  ClusterAbstraction out_;            // what build() returns
  ClusterAbstraction& g_;             // the graph built or repaired: out_, or the one repaired
  bool repairing_ = false;
  std::uint64_t expanded_ = 0;                           // cells the intra-edge searches expanded
  std::map<std::uint32_t, std::uint32_t> repairNodeOf_;  // cell index -> node, when repairing
  std::vector<bool> persisting_;  // repair: builder nodes that keep crossings not scanned again
  std::vector<Cell> first_;       // scratch of scanBorder
  std::vector<Cell> second_;
  std::vector<Capability> capabilities_;  // effective capabilities, built
  std::vector<const ClearanceField*> fields_;
  std::vector<std::uint32_t> nodeOf_;
  std::vector<Cell> nodeCells_;
  std::vector<Candidate> candidates_;
  std::vector<std::uint32_t> pathBegin_;
  std::vector<std::uint8_t> pathSteps_;
  std::vector<std::vector<std::uint32_t>> adjacency_;
};

ClusterAbstraction ClusterAbstraction::build(const AnnotatedGrid& grid, AbstractionSpec spec) {
  limits::require(problemWith(spec));
  ClusterAbstraction built = AbstractionBuilder(grid, std::move(spec)).build();
  built.revisions_ = 1;
  built.clusterRevision_.assign(static_cast<std::size_t>(built.clusterCount()), 1);
  built.buildLevelTwo(nullptr);
  built.stats_.buildMilliseconds += built.stats_.levelTwoMilliseconds;
  return built;
}

RepairStats ClusterAbstraction::repair(const TerrainChange& change) {
  const auto began = std::chrono::steady_clock::now();
  RepairStats stats;
  if (!change.changed) return stats;
  // Edges are annotated with the terrains each capability had on the map; a terrain new to
  // one would need edges the graph has no field for: build it whole.
  const std::uint8_t added = grid_->map().terrainsIn(change.area).mask();
  bool newTerrain = false;
  for (std::size_t i = 0; i < effective_.size(); ++i)
    newTerrain = newTerrain || (spec_.capabilities[i].mask() & added & ~effective_[i].mask()) != 0;
  if (newTerrain) {
    const std::uint64_t revisions = revisions_;
    *this = build(*grid_, spec_);
    // Revisions go on from the old graph's: nothing derived from it is current.
    revisions_ = revisions + 1;
    std::fill(clusterRevision_.begin(), clusterRevision_.end(), revisions_);
    stats.rebuilt = true;
    stats.clusters = clusterCount();
    stats.expanded = stats_.buildExpanded;
  } else {
    if (costs_) costs_->update(*grid_, change.area);
    std::vector<bool> redo;
    AbstractionBuilder(*this).repair(change.area, stats, redo);
    ++revisions_;
    for (int k = 0; k < clusterCount(); ++k) {
      if (redo[static_cast<std::size_t>(k)])
        clusterRevision_[static_cast<std::size_t>(k)] = revisions_;
    }
    if (spec_.levels == 2) {
      // Level 2 again in every level-2 cluster holding a cluster whose level-1 edges changed.
      std::vector<bool> blocks(levelTwoPaths_.size(), false);
      for (int k = 0; k < clusterCount(); ++k) {
        if (!redo[static_cast<std::size_t>(k)]) continue;
        const int cx = (k % clustersX_) / spec_.levelTwoSize;
        const int cy = (k / clustersX_) / spec_.levelTwoSize;
        blocks[static_cast<std::size_t>(cy * levelTwoX_ + cx)] = true;
      }
      stats.expanded += buildLevelTwo(&blocks);
    }
  }
  stats.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
  return stats;
}

}  // namespace warpath::pathing
