#include "pathing/haa_star.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "cluster_dijkstra.h"
#include "insertion_tables.h"
#include "limit_messages.h"
#include "pathing/invariant.h"
#include "pathing/moves.h"
#include "pathing/open_list.h"

namespace warpath::pathing {
namespace {

// Appends the cells reached by walking `steps` from `from`.
void appendWalk(Cell from, std::span<const std::uint8_t> steps, std::vector<Cell>* out) {
  for (std::uint8_t d : steps) {
    from.x += kDirections[d].dx;
    from.y += kDirections[d].dy;
    out->push_back(from);
  }
}

// True when every step of `cells` is a single move the agent may make (checked on the move
// masks, which admit only moves between cells the agent can stand on). Allocates nothing.
[[maybe_unused]] bool isLegalWalk(const AnnotatedGrid& grid, const AgentLayer& layer,
                                  std::span<const Cell> cells) {
  const GridMap& map = grid.map();
  const std::span<const std::uint8_t> masks = layer.moveMasks();
  for (std::size_t i = 1; i < cells.size(); ++i) {
    const int d = directionOf(cells[i].x - cells[i - 1].x, cells[i].y - cells[i - 1].y);
    if (d < 0 || (masks[map.indexOf(cells[i - 1])] & (1u << d)) == 0) return false;
  }
  return !cells.empty();
}

}  // namespace

struct HierarchicalAStar::Scratch {
  static constexpr std::uint32_t kNone = UINT32_MAX;

  ClusterDijkstra startSearch;
  ClusterDijkstra goalSearch;
  InsertionTables* tables = nullptr;  // the query's agent's, when insertion reads tables
  std::vector<std::pair<std::uint32_t, double>> links;
  std::uint64_t inserted = 0;  // expansions of the last insertion
  std::vector<Cell> clusterCells;
  std::vector<Cell> refined;
  std::vector<Cell> smoothed;
  std::vector<std::uint8_t> steps;
  std::vector<double> prefixCost;
  std::vector<std::int16_t> rayLengths;  // smoothing: per path cell and direction

  // Abstract search over the graph's nodes plus two: start (n) and goal (n + 1).
  std::vector<std::uint32_t> stamp;  // generation * 2 + {0 open, 1 closed}
  std::vector<double> g;
  std::vector<std::uint32_t> parent;
  std::vector<const AbstractEdge*> parentEdge;  // null for the start and goal links
  std::vector<std::uint8_t> parentIsLevelTwo;   // parentEdge is a level-2 edge
  std::vector<std::uint32_t> goalLinkStamp;
  std::vector<double> goalLinkCost;
  std::vector<std::pair<std::uint32_t, double>> startLinks;
  // The abstract path's level-1 nodes, start..goal, and the edge into each (null for links).
  std::vector<std::uint32_t> abstractPath;
  std::vector<const AbstractEdge*> pathEdges;
  std::vector<std::pair<std::uint32_t, const AbstractEdge*>> levelOneSteps;
  OpenList open;
  // Level 2 (the graph has it): the level-2 clusters of the start and goal are searched at
  // level 1, and so are those a surcharge may charge within (asked once a query: `blockFree`
  // holds generation * 2 + {0 charged, 1 free}); every other is crossed by level-2 edges.
  int startBlock = -1;
  int goalBlock = -1;
  std::vector<std::uint32_t> blockFree;
  std::uint32_t generation = 0;

  // The query under way (result.status Pending until done).
  Agent agent;
  Cell start;
  Cell goal;
  const AgentLayer* layer = nullptr;
  const EdgeSurcharge* surcharge = nullptr;
  Phase phase = Phase::GridOnly;
  PathResult result;
  std::uint64_t expandedSoFar = 0;
  std::size_t refineIndex = 0;   // the abstract path's next step to refine
  bool refineSearching = false;  // AA* re-planning that step is under way

  // Loop removal in smoothing: cell -> index in the path, a hash table sized by the path
  // (open addressing; a slot holds (map index + 1) << 32 | path index, 0 when empty). Arrays
  // over the map held 8 bytes a cell (32 MB at 2048²) and missed the cache at every cell.
  std::vector<std::uint64_t> visits;

  void begin(std::size_t nodes) {
    if (stamp.size() != nodes + 2) {
      stamp.assign(nodes + 2, 0);
      g.assign(nodes + 2, 0.0);
      parent.assign(nodes + 2, kNone);
      parentEdge.assign(nodes + 2, nullptr);
      parentIsLevelTwo.assign(nodes + 2, 0);
      goalLinkStamp.assign(nodes + 2, 0);
      goalLinkCost.assign(nodes + 2, 0.0);
      generation = 0;
    }
    if (++generation >= (1u << 30)) {
      std::fill(stamp.begin(), stamp.end(), 0);
      std::fill(goalLinkStamp.begin(), goalLinkStamp.end(), 0);
      generation = 1;
    }
    open.clear();
    startLinks.clear();
    abstractPath.clear();
    pathEdges.clear();
  }
};

HierarchicalAStar::HierarchicalAStar(const ClusterAbstraction& abstraction, HaaOptions options)
    : abstraction_(abstraction),
      options_(options),
      gridSearch_(abstraction.grid()),
      jumpSearch_(abstraction.grid()),
      scratch_(std::make_unique<Scratch>()) {
  // Their queries are parts of this one's, which times itself.
  gridSearch_.stopTimingPhases();
  jumpSearch_.stopTimingPhases();
}

HierarchicalAStar::~HierarchicalAStar() = default;

InsertionTables* HierarchicalAStar::tablesFor(Agent agent) {
  if (options_.insertion != InsertionMode::Tables || abstraction_.costs() ||
      !abstraction_.supports(agent))
    return nullptr;
  for (const auto& tables : tables_) {
    if (tables->agent() == agent) return tables.get();
  }
  return tables_.emplace_back(std::make_unique<InsertionTables>(abstraction_, agent)).get();
}

void HierarchicalAStar::prepare(Agent agent) {
  if (InsertionTables* tables = tablesFor(agent)) tables->prepareAll();
}

std::size_t HierarchicalAStar::insertionTableBytes() const {
  std::size_t bytes = 0;
  for (const auto& tables : tables_)
    bytes += tables->bytes();
  return bytes;
}

std::uint64_t HierarchicalAStar::expandedSoFar() const {
  return scratch_->expandedSoFar;
}

std::uint64_t HierarchicalAStar::nextStepExpansions() const {
  const Scratch& s = *scratch_;
  if (s.result.status != PathStatus::Pending ||
      (s.phase != Phase::InsertStart && s.phase != Phase::InsertGoal))
    return 1;
  if (s.tables) return s.tables->lookupExpansions(s.phase == Phase::InsertGoal ? s.goal : s.start);
  // The Dijkstra settles each cell of the cluster at most once.
  const CellRect bounds = abstraction_.clusterBounds(
      abstraction_.clusterOf(s.phase == Phase::InsertGoal ? s.goal : s.start));
  return static_cast<std::uint64_t>(bounds.width) * static_cast<std::uint64_t>(bounds.height);
}

PathStatus HierarchicalAStar::beginGridSearch(Agent agent, Cell start, Cell goal,
                                              const SearchLimits& limits, bool uniform) {
  const CostField* costs = uniform ? nullptr : abstraction_.costs();
  gridJumping_ = options_.gridSearch == GridSearch::JumpPoints && !costs;
  if (gridJumping_) return jumpSearch_.beginPath(agent, start, goal, limits);
  if (costs) return gridSearch_.beginPath(agent, start, goal, *costs, limits);
  return gridSearch_.beginPath(agent, start, goal, limits);
}

std::uint64_t HierarchicalAStar::stepGridSearch(std::uint64_t budget, bool& done) {
  const auto advance = [&](auto& search) {
    const std::uint64_t before = search.expandedSoFar();
    done = search.updatePath(budget) != PathStatus::Pending;
    return search.expandedSoFar() - before;
  };
  return gridJumping_ ? advance(jumpSearch_) : advance(gridSearch_);
}

PathResult HierarchicalAStar::finalizeGridSearch(std::vector<Cell>* path) {
  return gridJumping_ ? jumpSearch_.finalizePath(path) : gridSearch_.finalizePath(path);
}

namespace {

// Straight connections for smoothing: the octile-shortest walks from a to b that keep to a
// simple shape (all diagonal moves first, all straight moves first, or the two interleaved
// as evenly as a line), tried in turn; the first legal one for the agent that costs less
// than `budget` (its length, or with costs its travel time) is appended.
class StraightWalker {
 public:
  StraightWalker(const GridMap& map, const AgentLayer& layer, const CostField* costs)
      : map_(map), layer_(layer), costs_(costs) {}

  // The legal moves in a row from each cell of a path in each direction, up to `cap`, found at
  // first ask. A walk's shape opens with a run of one direction and the two-run shapes close
  // with one, and moves are legal both ways, so a walk whose opening run is longer than the
  // ray from its start, or closing run longer than the ray back from its end, is illegal
  // without walking it. On winding paths (mazes) nearly every candidate shortcut is, and
  // walking them was most of a query's time.
  class Rays {
   public:
    Rays(const StraightWalker& walker, std::span<const Cell> cells, int cap,
         std::vector<std::int16_t>& lengths)
        : walker_(walker), cells_(cells), cap_(cap), lengths_(lengths) {
      lengths_.assign(cells.size() * 8, -1);
    }
    int operator()(std::size_t at, int d) {
      std::int16_t& length = lengths_[at * 8 + static_cast<std::size_t>(d)];
      if (length >= 0) return length;
      const std::uint8_t* masks = walker_.layer_.moveMasks().data();
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      Cell c = cells_[at];
      int n = 0;
      while (n < cap_ && (masks[walker_.map_.indexOf(c)] & (1u << d)) != 0) {
        c = {c.x + dir.dx, c.y + dir.dy};
        ++n;
      }
      length = static_cast<std::int16_t>(n);
      return n;
    }

   private:
    const StraightWalker& walker_;
    std::span<const Cell> cells_;
    int cap_;
    std::vector<std::int16_t>& lengths_;
  };

  // A shortcut from path cell i to path cell j; `rays` over the path, with a cap of at least
  // the walk's moves.
  bool tryAppend(std::size_t i, std::size_t j, std::span<const Cell> cells, double budget,
                 Rays& rays, std::vector<Cell>* out) const {
    const Cell a = cells[i];
    const Cell b = cells[j];
    const int dx = b.x - a.x;
    const int dy = b.y - a.y;
    const int ax = std::abs(dx);
    const int ay = std::abs(dy);
    const int diagonals = std::min(ax, ay);
    const int straights = std::max(ax, ay) - diagonals;
    const int sx = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
    const int sy = dy > 0 ? 1 : (dy < 0 ? -1 : 0);
    const int diagonal = directionOf(sx, sy);
    const int straight = ax >= ay ? directionOf(sx, 0) : directionOf(0, sy);
    const int total = diagonals + straights;
    // A walk of one direction has one shape.
    const int shapes = diagonals == 0 || straights == 0 ? 1 : 3;
    for (int shape = 0; shape < shapes; ++shape) {
      // The opening run: shape 0 the diagonals, shape 1 the straights, the interleaved shape
      // ceil(straights / diagonals) straights before its first diagonal. Shapes 0 and 1 of
      // two directions close with a run of the other.
      const bool diagonalFirst = straights == 0 || (shape == 0 && diagonals > 0);
      const int opening = straights == 0   ? diagonals
                          : diagonals == 0 ? straights
                          : shape == 0     ? diagonals
                          : shape == 1     ? straights
                                           : (straights + diagonals - 1) / diagonals;
      if (rays(i, diagonalFirst ? diagonal : straight) < opening) continue;
      // The moves known legal from the rays: the opening run, or both runs of shapes 0 and 1.
      int certified = opening;
      if (shapes == 3 && shape < 2) {
        const int closingDirection = oppositeDirection(shape == 0 ? straight : diagonal);
        if (rays(j, closingDirection) < (shape == 0 ? straights : diagonals)) continue;
        certified = total;
      }
      const Moves moves{.shape = shape,
                        .diagonals = diagonals,
                        .total = total,
                        .diagonal = diagonal,
                        .straight = straight};
      // Uniform costs: a legal walk costs the octile distance, which the caller found below
      // the budget, so only legality is left to walk. (Summed move by move the walk's cost
      // differs from the octile formula by rounding alone, some 1e-13: the two tests disagree
      // only for a budget inside that sliver, which no path of the golden runs meets.)
      const bool accepted = costs_ ? walkCost(a, moves, certified, budget) < budget
                                   : walkIsLegal(a, moves, certified);
      if (accepted) {
        Moves::Cursor cursor;
        Cell at = a;
        for (int k = 0; k < total; ++k) {
          const Direction& dir = kDirections[static_cast<std::size_t>(moves.next(cursor))];
          at = {at.x + dir.dx, at.y + dir.dy};
          out->push_back(at);
        }
        return true;
      }
    }
    return false;
  }

 private:
  // The moves of a walk of one shape, in order (next() from a fresh cursor).
  struct Moves {
    int shape;
    int diagonals;
    int total;
    int diagonal;
    int straight;
    struct Cursor {
      int k = 0;
      int share = 0;  // k * diagonals mod total, for the interleaved shape
    };
    int next(Cursor& c) const {
      const int k = c.k++;
      if (diagonals == 0) return straight;
      if (diagonals == total) return diagonal;
      if (shape == 0) return k < diagonals ? diagonal : straight;
      if (shape == 1) return k < total - diagonals ? straight : diagonal;
      // Interleaved: step k is diagonal when the running share of diagonals crosses an
      // integer (floor((k + 1) d / t) > floor(k d / t)), like a line drawn from a to b.
      c.share += diagonals;
      if (c.share < total) return straight;
      c.share -= total;
      return diagonal;
    }
  };

  // Whether every move of the walk is legal for the agent; the first `certified` are known to be.
  bool walkIsLegal(Cell from, const Moves& moves, int certified) const {
    const std::uint8_t* masks = layer_.moveMasks().data();
    Moves::Cursor cursor;
    Cell at = from;
    for (int k = 0; k < moves.total; ++k) {
      const int d = moves.next(cursor);
      if (k >= certified && (masks[map_.indexOf(at)] & (1u << d)) == 0) return false;
      at = {at.x + kDirections[static_cast<std::size_t>(d)].dx,
            at.y + kDirections[static_cast<std::size_t>(d)].dy};
    }
    return true;
  }

  // The walk's cost under the costs, or infinity when a move of it is illegal for the agent;
  // stops early, with what it has summed, once that reaches `budget`. Its first `certified`
  // moves are known legal.
  double walkCost(Cell from, const Moves& moves, int certified, double budget) const {
    const std::uint8_t* masks = layer_.moveMasks().data();
    Moves::Cursor cursor;
    Cell at = from;
    double cost = 0.0;
    for (int k = 0; k < moves.total; ++k) {
      const int d = moves.next(cursor);
      if (k >= certified && (masks[map_.indexOf(at)] & (1u << d)) == 0)
        return std::numeric_limits<double>::infinity();
      cost += costs_->moveCost(at, d);
      if (cost >= budget) return cost;
      at = {at.x + kDirections[static_cast<std::size_t>(d)].dx,
            at.y + kDirections[static_cast<std::size_t>(d)].dy};
    }
    return cost;
  }

  const GridMap& map_;
  const AgentLayer& layer_;
  const CostField* costs_;
};

// Which cells a walk from one cell might reach when each of its moves is legal for the agent
// and advances one step along the walk's major axis and one or none along its minor axis. Every
// shape StraightWalker tries is such a walk, so a cell ruled out here needs no shape tried: the
// same shortcuts are taken, and on winding paths (mazes) nearly every candidate is ruled out at
// a comparison (maze512-4-0: 97 % of those past the cost bound).
//
// Per family of walks (which axis is major, its sign, the minor axis's sign) and number of
// moves k, it keeps an interval of minor offsets holding every offset such walks reach in k
// moves: the next interval runs from the lowest offset one legal move from the interval to the
// highest, found by scanning in from its ends (two reads a step in the open). Offsets inside it
// that no walk reaches make it weaker, never wrong. It is found at first ask, as far as asked,
// and ends at the first step no walk gets past (a wall across every way).
class MonotoneReach {
 public:
  // Cells farther than this are not ruled on.
  static constexpr int kMaxMoves = 63;

  MonotoneReach(const GridMap& map, const AgentLayer& layer)
      : map_(map), masks_(layer.moveMasks().data()) {}

  void from(Cell origin) {
    origin_ = origin;
    originIndex_ = map_.indexOf(origin);
    computedTo_.fill(-1);
    deadFrom_.fill(kMaxMoves + 1);
  }

  // False when no such walk from the origin reaches `to`; true when one might, or when `to` is
  // more than kMaxMoves moves away.
  bool mayReach(Cell to) {
    const int dx = to.x - origin_.x;
    const int dy = to.y - origin_.y;
    const int ax = std::abs(dx);
    const int ay = std::abs(dy);
    const bool xMajor = ax >= ay;
    const int moves = xMajor ? ax : ay;
    if (moves > kMaxMoves) return true;
    const bool majorPositive = (xMajor ? dx : dy) >= 0;
    const bool minorPositive = (xMajor ? dy : dx) >= 0;
    const std::size_t family =
        (xMajor ? 4u : 0u) + (majorPositive ? 2u : 0u) + (minorPositive ? 1u : 0u);
    if (computedTo_[family] < moves) extend(family, moves);
    if (moves >= deadFrom_[family]) return false;
    const Span& span = spans_[family][static_cast<std::size_t>(moves)];
    const int offset = xMajor ? ay : ax;
    return span.low <= offset && offset <= span.high;
  }

 private:
  struct Span {
    std::int8_t low;
    std::int8_t high;
  };

  void extend(std::size_t family, int moves) {
    const bool xMajor = family >= 4;
    const int major = (family & 2u) != 0 ? 1 : -1;
    const int minor = (family & 1u) != 0 ? 1 : -1;
    std::array<Span, kMaxMoves + 1>& spans = spans_[family];
    int& k = computedTo_[family];
    if (k < 0) {
      spans[0] = {0, 0};
      k = 0;
    }
    const std::int64_t width = map_.width();
    const std::int64_t majorStep = xMajor ? major : major * width;
    const std::int64_t minorStep = xMajor ? minor * width : minor;
    const unsigned straightBit = 1u << directionOf(xMajor ? major : 0, xMajor ? 0 : major);
    const unsigned diagonalBit = 1u << directionOf(xMajor ? major : minor, xMajor ? minor : major);
    for (; k < moves; ++k) {
      const Span span = spans[static_cast<std::size_t>(k)];
      // Cells between two cells of the map on one line are on it too, so every read is.
      const std::uint8_t* column = masks_ + static_cast<std::int64_t>(originIndex_) + k * majorStep;
      int low = -1;
      for (int m = span.low; m <= span.high && low < 0; ++m) {
        const unsigned mask = column[m * minorStep];
        if ((mask & straightBit) != 0) {
          low = m;
        } else if ((mask & diagonalBit) != 0) {
          low = m + 1;
        }
      }
      if (low < 0) {  // no walk gets past this step
        deadFrom_[family] = k + 1;
        k = kMaxMoves;
        return;
      }
      int high = low;
      for (int m = span.high; m >= span.low; --m) {
        const unsigned mask = column[m * minorStep];
        if ((mask & diagonalBit) != 0) {
          high = m + 1;
          break;
        }
        if ((mask & straightBit) != 0) {
          high = m;
          break;
        }
      }
      spans[static_cast<std::size_t>(k) + 1] = {static_cast<std::int8_t>(low),
                                                static_cast<std::int8_t>(high)};
    }
  }

  const GridMap& map_;
  const std::uint8_t* masks_;
  Cell origin_{};
  std::uint32_t originIndex_ = 0;
  std::array<int, 8> computedTo_{};
  std::array<int, 8> deadFrom_{};  // the first step no walk of the family reaches
  std::array<std::array<Span, kMaxMoves + 1>, 8> spans_{};
};

}  // namespace

PathResult HierarchicalAStar::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                                       const EdgeSurcharge* surcharge) {
  return timing_.whole([&] {
    beginPath(agent, start, goal, surcharge);
    updatePath(kUnboundedExpansions);
    return finalizePath(path);
  });
}

PathStatus HierarchicalAStar::beginPath(Agent agent, Cell start, Cell goal,
                                        const EdgeSurcharge* surcharge) {
  const QueryClock clock = timing_.phaseClock();
  Scratch& s = *scratch_;
  s.result = PathResult{};
  s.result.status = PathStatus::Pending;
  s.surcharge = surcharge;
  s.agent = agent;
  s.start = start;
  s.goal = goal;
  s.expandedSoFar = 0;
  s.refined.clear();
  s.tables = nullptr;
  const AnnotatedGrid& grid = abstraction_.grid();
  if (const auto answer = screenEndpoints(grid, agent, start, goal)) {
    s.result.status = *answer;
  } else if (!abstraction_.supports(agent)) {
    // A weighted graph's costs are its one agent's: any other is planned in the uniform model.
    s.phase = Phase::GridOnly;
    beginGridSearch(agent, start, goal, {}, true);
  } else if (start == goal) {
    s.refined.push_back(start);
    s.result.status = PathStatus::Found;
  } else {
    s.layer = &grid.layer(agent);
    s.tables = tablesFor(agent);
    const int cluster = abstraction_.clusterOf(start);
    s.phase = Phase::InsertStart;
    if (cluster == abstraction_.clusterOf(goal)) {
      // A path inside the shared cluster, when there is one, is found by AA* at local cost
      // (counted as insertion effort).
      SearchLimits inCluster;
      inCluster.region = abstraction_.clusterBounds(cluster);
      beginGridSearch(agent, start, goal, inCluster);
      s.phase = Phase::SameCluster;
    }
  }
  s.result.metrics.microseconds += clock.elapsedMicroseconds();
  return s.result.status;
}

PathStatus HierarchicalAStar::updatePath(std::uint64_t maxExpansions) {
  return advance(maxExpansions, true);
}

PathStatus HierarchicalAStar::advance(std::uint64_t maxExpansions, bool mayOverrun) {
  Scratch& s = *scratch_;
  if (s.result.status != PathStatus::Pending || maxExpansions == 0) return s.result.status;
  const QueryClock clock = timing_.phaseClock();
  for (std::uint64_t left = maxExpansions; s.result.status == PathStatus::Pending && left > 0;) {
    if (nextStepExpansions() > left && !(mayOverrun && left == maxExpansions)) break;
    const std::uint64_t spent = step(left);
    s.expandedSoFar += spent;
    left -= std::min(left, spent);
  }
  s.result.metrics.microseconds += clock.elapsedMicroseconds();
  return s.result.status;
}

PathResult HierarchicalAStar::finalizePath(std::vector<Cell>* path) {
  const QueryClock clock = timing_.phaseClock();
  Scratch& s = *scratch_;
  if (path) path->clear();
  if (s.result.status == PathStatus::Found && path)
    path->assign(s.refined.begin(), s.refined.end());
  s.result.metrics.microseconds += clock.elapsedMicroseconds();
  return s.result;
}

std::uint64_t HierarchicalAStar::step(std::uint64_t budget) {
  Scratch& s = *scratch_;
  SearchMetrics& metrics = s.result.metrics;
  bool done = false;
  switch (s.phase) {
    case Phase::GridOnly: {
      const std::uint64_t spent = stepGridSearch(budget, done);
      if (done) {
        const double microseconds = metrics.microseconds;
        const PathResult r = finalizeGridSearch(&s.refined);
        s.result = r;
        metrics.microseconds = microseconds;
        metrics.gridExpanded = r.metrics.expanded;
        metrics.usedGridSearch = true;
      }
      return spent;
    }
    case Phase::SameCluster: {
      const std::uint64_t spent = stepGridSearch(budget, done);
      if (done) {
        const PathResult local = finalizeGridSearch(&s.refined);
        metrics.insertionExpanded += local.metrics.expanded;
        metrics.generated += local.metrics.generated;
        if (local.found()) {
          complete();
        } else {
          s.phase = Phase::InsertStart;
        }
      }
      return spent;
    }
    case Phase::InsertStart:
      s.begin(abstraction_.nodeCount());
      insertEndpoint(false);
      s.phase = Phase::InsertGoal;
      return s.inserted;
    case Phase::InsertGoal:
      insertEndpoint(true);
      beginAbstract();
      return s.inserted;
    case Phase::Abstract:
      return searchAbstract(budget);
    case Phase::Refine:
      return refine(budget);
  }
  return 0;
}

void HierarchicalAStar::complete() {
  Scratch& s = *scratch_;
  std::vector<Cell>& cells = s.refined;
  [[maybe_unused]] const AnnotatedGrid& grid = abstraction_.grid();
  if (options_.smooth) {
    smooth(*s.layer);
    WARPATH_INVARIANT(
        cells.front() == s.start && cells.back() == s.goal && isLegalWalk(grid, *s.layer, cells),
        "HAA* smoothing must keep a path from start to goal of moves legal for the agent");
  }
  const CostField* costs = abstraction_.costs();
  SearchMetrics& metrics = s.result.metrics;
  s.result.cost = costs ? costs->pathCost(cells) : pathCost(cells);
  metrics.expanded = metrics.insertionExpanded + metrics.abstractExpanded +
                     metrics.refinementExpanded + metrics.gridExpanded;
  s.result.status = PathStatus::Found;
}

// Insertion: one Dijkstra from an end over its cluster reaches every node there. Leaves the
// start's links (node, cost) in `startLinks` and the goal's in `goalLinkStamp/Cost`, and both
// search trees for refinement.
void HierarchicalAStar::insertEndpoint(bool goalSide) {
  Scratch& s = *scratch_;
  const GridMap& map = abstraction_.grid().map();
  const Cell end = goalSide ? s.goal : s.start;
  if (s.tables) {
    s.inserted = s.tables->links(end, &s.links);
    for (const auto& [n, cost] : s.links) {
      if (goalSide) {
        s.goalLinkStamp[n] = s.generation;
        s.goalLinkCost[n] = cost;
      } else {
        s.startLinks.push_back({n, cost});
      }
    }
    s.result.metrics.insertionExpanded += s.inserted;
    s.result.metrics.generated += s.links.size();
    return;
  }
  const int cluster = abstraction_.clusterOf(end);
  ClusterDijkstra& search = goalSide ? s.goalSearch : s.startSearch;
  s.clusterCells.clear();
  for (std::uint32_t n : abstraction_.nodesInCluster(cluster))
    s.clusterCells.push_back(abstraction_.nodeCell(n));
  search.run(map, *s.layer, abstraction_.clusterBounds(cluster), end, s.clusterCells,
             abstraction_.costs());
  for (std::uint32_t n : abstraction_.nodesInCluster(cluster)) {
    const Cell c = abstraction_.nodeCell(n);
    if (!search.reached(c)) continue;
    if (goalSide) {
      s.goalLinkStamp[n] = s.generation;
      s.goalLinkCost[n] = search.cost(c);
    } else {
      s.startLinks.push_back({n, search.cost(c)});
    }
  }
  s.inserted = search.expanded();
  s.result.metrics.insertionExpanded += search.expanded();
  s.result.metrics.generated += search.generated();
}

// Abstract A* with the octile heuristic over the edges this agent may use, from the start
// (node nodeCount()) to the goal (nodeCount() + 1) through their links.
void HierarchicalAStar::beginAbstract() {
  Scratch& s = *scratch_;
  const std::uint32_t startNode = abstraction_.nodeCount();
  const double scale = abstraction_.costs() ? abstraction_.costs()->cheapest() : 1.0;
  s.stamp[startNode] = s.generation * 2;
  s.g[startNode] = 0.0;
  s.parent[startNode] = Scratch::kNone;
  s.open.push(
      OpenList::makeKey(scale * octileDistance(s.goal.x - s.start.x, s.goal.y - s.start.y), 0.0),
      startNode);
  if (abstraction_.hasLevelTwo()) {
    s.startBlock = abstraction_.levelTwoClusterOf(s.start);
    s.goalBlock = abstraction_.levelTwoClusterOf(s.goal);
    const auto blocks = static_cast<std::size_t>(abstraction_.levelTwoClusterCount());
    if (s.blockFree.size() != blocks || s.generation == 1) s.blockFree.assign(blocks, 0);
  }
  s.phase = Phase::Abstract;
}

// When the goal is reached, leaves the node sequence start..goal in `abstractPath` and moves on
// to refinement; stops between two expansions once `budget` are spent.
std::uint64_t HierarchicalAStar::searchAbstract(std::uint64_t budget) {
  Scratch& s = *scratch_;
  SearchMetrics& metrics = s.result.metrics;
  const Agent agent = s.agent;
  const Cell goal = s.goal;
  const std::uint32_t startNode = abstraction_.nodeCount();
  const std::uint32_t goalNode = startNode + 1;
  const double scale = abstraction_.costs() ? abstraction_.costs()->cheapest() : 1.0;
  const auto heuristic = [&](Cell c) { return scale * octileDistance(goal.x - c.x, goal.y - c.y); };
  const std::uint32_t openStamp = s.generation * 2;
  const std::uint32_t closedStamp = openStamp + 1;
  const auto relax = [&](std::uint32_t from, std::uint32_t to, double cost,
                         const AbstractEdge* edge, Cell toCell, bool levelTwo = false) {
    const double ng = s.g[from] + cost;
    if (s.stamp[to] == closedStamp || (s.stamp[to] == openStamp && ng >= s.g[to])) return;
    s.stamp[to] = openStamp;
    s.g[to] = ng;
    s.parent[to] = from;
    s.parentEdge[to] = edge;
    s.parentIsLevelTwo[to] = levelTwo ? 1 : 0;
    s.open.push(OpenList::makeKey(ng + heuristic(toCell), ng), to);
    ++metrics.generated;
  };
  std::uint64_t spent = 0;
  while (!s.open.empty()) {
    if (spent >= budget) return spent;
    const std::uint32_t u = s.open.pop();
    if (s.stamp[u] == closedStamp) continue;
    s.stamp[u] = closedStamp;
    ++metrics.abstractExpanded;
    ++spent;
    if (u == goalNode) {
      tracePath();
      s.refined.push_back(s.start);
      s.refineIndex = 1;
      s.refineSearching = false;
      s.phase = Phase::Refine;
      return spent;
    }
    if (u == startNode) {
      for (const auto& [n, cost] : s.startLinks)
        relax(u, n, cost, nullptr, abstraction_.nodeCell(n));
      continue;
    }
    if (abstraction_.hasLevelTwo()) {
      // Inside a level-2 cluster of neither end (entered at a level-2 node): its level-2
      // edges, and the level-1 edges that leave it.
      const int block = abstraction_.levelTwoClusterOfNode(u);
      // Surcharges price level-1 edges one by one: level-2 edges only where none is charged.
      const auto chargeFree = [&] {
        if (!s.surcharge) return true;
        std::uint32_t& known = s.blockFree[static_cast<std::size_t>(block)];
        if (known / 2 != s.generation)
          known = s.generation * 2 + (s.surcharge->freeWithin(abstraction_, block) ? 1 : 0);
        return known % 2 == 1;
      };
      if (block != s.startBlock && block != s.goalBlock && chargeFree()) {
        for (const AbstractEdge& e : abstraction_.levelTwoEdgesOf(u)) {
          if (e.usableBy(agent))
            relax(u, e.target, e.cost, &e, abstraction_.nodeCell(e.target), true);
        }
        for (const AbstractEdge& e : abstraction_.edgesOf(u)) {
          if (!e.intra && e.usableBy(agent) &&
              abstraction_.levelTwoClusterOfNode(e.target) != block)
            relax(u, e.target, e.cost, &e, abstraction_.nodeCell(e.target));
        }
        continue;
      }
    }
    for (const AbstractEdge& e : abstraction_.edgesOf(u)) {
      if (!e.usableBy(agent)) continue;
      const double cost =
          s.surcharge ? e.cost + s.surcharge->on(abstraction_, u, e, s.g[u]) : e.cost;
      relax(u, e.target, cost, &e, abstraction_.nodeCell(e.target));
    }
    if (s.goalLinkStamp[u] == s.generation) relax(u, goalNode, s.goalLinkCost[u], nullptr, goal);
  }
  // The grid's components say a path exists and the abstraction is complete, so this is a bug
  // (checked as an invariant). Release builds answer Unreachable rather than a path that is not
  // there.
  WARPATH_INVARIANT(false, "HAA* abstract search must reach a goal in the start's component");
  s.result.status = PathStatus::Unreachable;
  return spent;
}

// The abstract path found, start to goal, in `abstractPath` and `pathEdges`, its level-2 edges
// replaced by the level-1 edges they stand for.
void HierarchicalAStar::tracePath() {
  Scratch& s = *scratch_;
  const std::uint32_t goalNode = abstraction_.nodeCount() + 1;
  for (std::uint32_t at = goalNode; at != Scratch::kNone; at = s.parent[at]) {
    const std::uint32_t from = s.parent[at];
    if (from == Scratch::kNone || !s.parentIsLevelTwo[at]) {
      s.abstractPath.push_back(at);
      s.pathEdges.push_back(s.parentEdge[at]);
      continue;
    }
    s.levelOneSteps.clear();
    abstraction_.appendLevelOneSteps(from, *s.parentEdge[at], s.agent, &s.levelOneSteps);
    std::uint32_t to = at;
    for (auto it = s.levelOneSteps.rbegin(); it != s.levelOneSteps.rend(); ++it) {
      WARPATH_INVARIANT(it->second->target == to, "level 2: steps must join its ends");
      s.abstractPath.push_back(to);
      s.pathEdges.push_back(it->second);
      to = it->first;
    }
  }
  std::reverse(s.abstractPath.begin(), s.abstractPath.end());
  std::reverse(s.pathEdges.begin(), s.pathEdges.end());
}

// Refinement: the start link (the start's Dijkstra tree), each abstract edge's cached path
// (or, without cached paths, AA* re-planned inside its cluster, sliced), the goal link (the
// goal's tree, walked backwards). Fills `refined` from start to goal and completes the query;
// re-planning an edge fails only through a bug (answered Unreachable, as above).
std::uint64_t HierarchicalAStar::refine(std::uint64_t budget) {
  Scratch& s = *scratch_;
  SearchMetrics& metrics = s.result.metrics;
  const std::uint32_t startNode = abstraction_.nodeCount();
  const std::uint32_t goalNode = startNode + 1;
  std::vector<Cell>& cells = s.refined;
  for (; s.refineIndex < s.abstractPath.size(); ++s.refineIndex) {
    const std::uint32_t from = s.abstractPath[s.refineIndex - 1];
    const std::uint32_t to = s.abstractPath[s.refineIndex];
    const AbstractEdge* pathEdge = s.pathEdges[s.refineIndex];
    if (from == startNode && s.tables) {
      s.tables->appendWayToNode(s.start, to, &cells);
    } else if (to == goalNode && s.tables) {
      s.tables->appendWayFromNode(from, s.goal, &cells);
    } else if (from == startNode) {
      s.steps.clear();
      s.startSearch.appendSteps(abstraction_.nodeCell(to), &s.steps);
      appendWalk(s.start, s.steps, &cells);
    } else if (to == goalNode) {
      s.steps.clear();
      s.goalSearch.appendSteps(abstraction_.nodeCell(from), &s.steps);
      Cell at = abstraction_.nodeCell(from);
      for (auto it = s.steps.rbegin(); it != s.steps.rend(); ++it) {
        const Direction& dir = kDirections[static_cast<std::size_t>(oppositeDirection(*it))];
        at = {at.x + dir.dx, at.y + dir.dy};
        cells.push_back(at);
      }
    } else {
      const AbstractEdge& edge = *pathEdge;
      if (!edge.intra || edge.path != AbstractEdge::kNoPath) {
        abstraction_.appendEdgeCells(from, edge, &cells);
        continue;
      }
      // Paths not cached: the edge promises a path inside the cluster for this agent.
      if (!s.refineSearching) {
        SearchLimits inCluster;
        inCluster.region =
            abstraction_.clusterBounds(abstraction_.clusterOf(abstraction_.nodeCell(from)));
        beginGridSearch(s.agent, abstraction_.nodeCell(from), abstraction_.nodeCell(to), inCluster);
        s.refineSearching = true;
      }
      bool done = false;
      const std::uint64_t spent = stepGridSearch(budget, done);
      if (!done) return spent;
      s.refineSearching = false;
      std::vector<Cell>& piece = s.smoothed;
      const PathResult r = finalizeGridSearch(&piece);
      metrics.refinementExpanded += r.metrics.expanded;
      metrics.generated += r.metrics.generated;
      WARPATH_INVARIANT(r.found(), "an abstract edge the agent may use must refine in its cluster");
      if (!r.found()) {
        s.result.status = PathStatus::Unreachable;
        return spent;
      }
      cells.insert(cells.end(), piece.begin() + 1, piece.end());
      ++s.refineIndex;
      return spent;  // the next edge in the next step, with what is left of the slice
    }
  }
  WARPATH_INVARIANT(cells.front() == s.start && cells.back() == s.goal &&
                        isLegalWalk(abstraction_.grid(), *s.layer, cells),
                    "HAA* refinement must join start to goal by moves legal for the agent");
  complete();
  return 0;
}

// Smoothing keeps every step legal: (1) cut loops (a cell visited twice), then (2) greedily
// replace stretches of the path by straight octile walks that are legal for the agent and
// cheaper (shorter, or under costs faster), looking up to a few clusters ahead.
void HierarchicalAStar::smooth(const AgentLayer& layer) {
  Scratch& s = *scratch_;
  const GridMap& map = abstraction_.grid().map();
  std::vector<Cell>& cells = s.refined;

  // (1) Loops: keep the first visit of a cell and drop everything up to its last visit.
  const std::size_t slots = std::bit_ceil(std::max<std::size_t>(2 * cells.size(), 16));
  s.visits.assign(slots, 0);
  const std::size_t slotMask = slots - 1;
  const int shift = 64 - std::countr_zero(slots);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::uint64_t key = std::uint64_t{map.indexOf(cells[i])} + 1;
    // Fibonacci hashing: neighbouring cells land far apart.
    std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift);
    while (s.visits[slot] != 0 && (s.visits[slot] >> 32) != key)
      slot = (slot + 1) & slotMask;
    const auto first = static_cast<std::uint32_t>(s.visits[slot]);
    if (s.visits[slot] != 0 && first < kept && cells[first] == cells[i]) {
      kept = first;  // back to the first visit; the loop is dropped
    } else {
      cells[kept] = cells[i];
      s.visits[slot] = key << 32 | kept;
    }
    ++kept;
  }
  cells.resize(kept);

  // (2) Straight shortcuts.
  const std::size_t n = cells.size();
  if (n < 3) return;
  const CostField* costs = abstraction_.costs();
  s.prefixCost.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const int d = directionOf(cells[i].x - cells[i - 1].x, cells[i].y - cells[i - 1].y);
    s.prefixCost[i] = s.prefixCost[i - 1] + (costs ? costs->moveCost(cells[i - 1], d)
                                                   : kDirections[static_cast<std::size_t>(d)].cost);
  }
  // Octile distance times the cheapest cost bounds every walk from below: most candidate
  // shortcuts are rejected on it without walking them.
  const double scale = costs ? costs->cheapest() : 1.0;
  const std::size_t lookahead = static_cast<std::size_t>(abstraction_.spec().clusterSize) * 3;
  const StraightWalker walker(map, layer, costs);
  StraightWalker::Rays rays(walker, cells, static_cast<int>(lookahead), s.rayLengths);
  MonotoneReach reach(map, layer);
  std::vector<Cell>& out = s.smoothed;
  out.clear();
  out.push_back(cells[0]);
  std::size_t i = 0;
  while (i + 1 < n) {
    std::size_t next = i + 1;
    // Shortcuts start only where the path turns (or at its start): from the middle of a
    // straight stretch they rarely gain, and trying them was most of a query's time on
    // winding paths (8room_000: long-query median 1080 -> 574 us, error unchanged; on the
    // game maps +/- 0.1 point of error, 10-40 % faster).
    const auto turnsAt = [&](std::size_t k) {
      return k == 0 || k + 1 == n || cells[k].x - cells[k - 1].x != cells[k + 1].x - cells[k].x ||
             cells[k].y - cells[k - 1].y != cells[k + 1].y - cells[k].y;
    };
    const std::size_t farthest = turnsAt(i) ? std::min(n - 1, i + lookahead) : i + 1;
    // The reach is asked only once a shortcut from here failed: in the open the first one
    // tried usually succeeds, and finding the reach of long walks would cost more than it saves.
    bool ruling = false;
    for (std::size_t j = farthest; j >= i + 2; --j) {
      // Under costs shortcuts also end only where the path turns: a weighted path turns at
      // most terrain edges, and walking every candidate in between was a third of a query's
      // time on the patchwork map (docs/benchmarks.md).
      if ((costs && !turnsAt(j)) || (ruling && !reach.mayReach(cells[j]))) continue;
      const double budget = s.prefixCost[j] - s.prefixCost[i] - 1e-9;
      const double direct =
          scale * octileDistance(cells[j].x - cells[i].x, cells[j].y - cells[i].y);
      if (direct >= budget) continue;
      if (walker.tryAppend(i, j, cells, budget, rays, &out)) {
        next = j;
        break;
      }
      if (!ruling) reach.from(cells[i]);
      ruling = true;
    }
    if (next == i + 1) out.push_back(cells[i + 1]);
    i = next;
  }
  cells.swap(out);
}

std::string problemWith(const HybridOptions& options) {
  if (options.tau < 1) return limits::atLeast("tau", 1, 0);
  return {};
}

HybridPlanner::HybridPlanner(const ClusterAbstraction& abstraction, HybridOptions hybrid,
                             HaaOptions haa)
    : options_((limits::require(problemWith(hybrid)), hybrid)),
      shortQueryDistance_(std::sqrt(static_cast<double>(hybrid.tau)) / 2.0),
      hierarchical_(abstraction, haa),
      jumps_(abstraction.grid(), JumpDistances::Precomputed) {
  // Their queries are parts of this one's, which times itself.
  hierarchical_.stopTimingPhases();
  jumps_.stopTimingPhases();
}

template <typename F>
decltype(auto) HybridPlanner::withAttempt(F&& f) {
  return jumping_ ? f(jumps_) : f(hierarchical_.gridSearch_);
}

template <typename F>
decltype(auto) HybridPlanner::withAttempt(F&& f) const {
  return jumping_ ? f(jumps_) : f(hierarchical_.gridSearch_);
}

PathResult HybridPlanner::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                                   const EdgeSurcharge* surcharge) {
  return timing_.whole([&] {
    beginPath(agent, start, goal, surcharge);
    updatePath(kUnboundedExpansions);
    return finalizePath(path);
  });
}

bool HybridPlanner::attemptsJumpPoints() const {
  return options_.attempt == HybridAttempt::JumpPoints &&
         hierarchical_.abstraction_.costs() == nullptr;
}

void HybridPlanner::prepare(Agent agent) {
  if (attemptsJumpPoints()) jumps_.prepare(agent);
  hierarchical_.prepare(agent);
}

PathStatus HybridPlanner::beginPath(Agent agent, Cell start, Cell goal,
                                    const EdgeSurcharge* surcharge) {
  const QueryClock clock = timing_.phaseClock();
  microseconds_ = 0.0;
  const PathStatus status = begin(agent, start, goal, surcharge);
  microseconds_ += clock.elapsedMicroseconds();
  return status;
}

PathStatus HybridPlanner::begin(Agent agent, Cell start, Cell goal,
                                const EdgeSurcharge* surcharge) {
  surcharge_ = surcharge;
  agent_ = agent;
  start_ = start;
  goal_ = goal;
  attempt_ = PathResult{};
  attempt_.status = PathStatus::Pending;
  jumping_ = attemptsJumpPoints();
  const double dx = goal.x - start.x;
  const double dy = goal.y - start.y;
  if (!jumping_ && std::sqrt(dx * dx + dy * dy) > shortQueryDistance_) {
    stage_ = Stage::Hierarchical;
    return hierarchical_.beginPath(agent, start, goal, surcharge);
  }
  SearchLimits budget;
  budget.maxExpanded = options_.tau;
  stage_ = Stage::Attempt;
  if (jumping_) return afterAttempt(jumps_.beginPath(agent, start, goal, budget));
  return afterAttempt(hierarchical_.abstraction_.supports(agent)
                          ? hierarchical_.beginGridSearch(agent, start, goal, budget)
                          : hierarchical_.gridSearch_.beginPath(agent, start, goal, budget));
}

PathStatus HybridPlanner::afterAttempt(PathStatus status) {
  if (status == PathStatus::Pending) return status;
  if (status != PathStatus::BudgetExhausted) {
    stage_ = Stage::Answered;
    attemptStatus_ = status;
    return status;
  }
  attempt_ = withAttempt([](auto& search) { return search.finalizePath(nullptr); });
  stage_ = Stage::Hierarchical;
  return hierarchical_.beginPath(agent_, start_, goal_, surcharge_);
}

PathStatus HybridPlanner::updatePath(std::uint64_t maxExpansions) {
  const QueryClock clock = timing_.phaseClock();
  const PathStatus status = update(maxExpansions);
  microseconds_ += clock.elapsedMicroseconds();
  return status;
}

PathStatus HybridPlanner::update(std::uint64_t maxExpansions) {
  if (stage_ == Stage::Answered) return attemptStatus_;
  if (stage_ == Stage::Attempt) {
    std::uint64_t spent = 0;
    const PathStatus attemptStatus = withAttempt([&](auto& attempt) {
      const std::uint64_t before = attempt.expandedSoFar();
      const PathStatus s = attempt.updatePath(maxExpansions);
      spent = attempt.expandedSoFar() - before;
      return s;
    });
    const PathStatus status = afterAttempt(attemptStatus);  // may begin HAA*
    if (stage_ != Stage::Hierarchical || spent >= maxExpansions) return status;
    // The rest of the slice: no insertion larger than it (the attempt spent part of it).
    return hierarchical_.advance(maxExpansions - spent, spent == 0);
  }
  return hierarchical_.updatePath(maxExpansions);
}

std::uint64_t HybridPlanner::nextStepExpansions() const {
  return stage_ == Stage::Hierarchical ? hierarchical_.nextStepExpansions() : 1;
}

std::uint64_t HybridPlanner::expandedSoFar() const {
  if (stage_ != Stage::Hierarchical)
    return withAttempt([](const auto& search) { return search.expandedSoFar(); });
  return attempt_.metrics.expanded + hierarchical_.expandedSoFar();
}

PathResult HybridPlanner::finalizePath(std::vector<Cell>* path) {
  const QueryClock clock = timing_.phaseClock();
  PathResult result;
  if (stage_ != Stage::Hierarchical) {
    result = withAttempt([&](auto& search) { return search.finalizePath(path); });
    result.metrics.gridExpanded = result.metrics.expanded;
    result.metrics.usedGridSearch = true;
  } else {
    result = hierarchical_.finalizePath(path);
    result.metrics.gridExpanded += attempt_.metrics.expanded;
    result.metrics.expanded += attempt_.metrics.expanded;
    result.metrics.generated += attempt_.metrics.generated;
  }
  result.metrics.microseconds = microseconds_ + clock.elapsedMicroseconds();
  return result;
}

}  // namespace warpath::pathing
