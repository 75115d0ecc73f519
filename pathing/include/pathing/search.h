#pragma once
// What every path query returns: a status and the effort it took.

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "pathing/enum_names.h"
#include "pathing/grid_map.h"

namespace warpath::pathing {

enum class PathStatus : std::uint8_t {
  Found,
  Unreachable,      // start and goal are valid but not connected for this agent
  InvalidStart,     // outside the map, or the agent cannot stand there
  InvalidGoal,      // outside the map, or the agent cannot stand there
  BudgetExhausted,  // the search stopped at its expansion limit before reaching the goal
  Pending,          // a sliced query not finished yet (updatePath it again)
};

inline constexpr EnumNames<PathStatus, 6> kPathStatusNames{{{
    {PathStatus::Found, "found"},
    {PathStatus::Unreachable, "unreachable"},
    {PathStatus::InvalidStart, "invalid-start"},
    {PathStatus::InvalidGoal, "invalid-goal"},
    {PathStatus::BudgetExhausted, "budget-exhausted"},
    {PathStatus::Pending, "pending"},
}}};
// The name from kPathStatusNames ("found", "invalid-start", …).
std::string_view toString(PathStatus status);

struct SearchMetrics {
  std::uint64_t expanded = 0;   // nodes taken off the open list and expanded (all phases)
  std::uint64_t generated = 0;  // nodes pushed onto the open list (all phases)
  double microseconds = 0.0;    // wall time of the query (a measurement, never an input)
  // Hierarchical planners split `expanded` by phase (the four add up to it); plain AA*
  // counts only in `expanded`.
  std::uint64_t insertionExpanded = 0;   // grid: linking start and goal to the graph, and the
                                         // in-cluster AA* tried when both share a cluster
  std::uint64_t abstractExpanded = 0;    // abstract nodes, searching the cluster graph
  std::uint64_t refinementExpanded = 0;  // grid: re-planning edges whose paths are not cached
  std::uint64_t gridExpanded = 0;  // grid: AA* on the whole map (hybrid's short-query attempt,
                                   // agents the graph does not serve)
  bool usedGridSearch = false;     // answered by AA* on the grid (hybrid short query, fallback)
};

// Caller-set bounds on one search. Query-time arguments: a search never throws on them.
struct SearchLimits {
  // Stop with BudgetExhausted after this many expansions; 0 answers BudgetExhausted at once
  // (after the checks of start and goal), without expanding anything.
  std::uint64_t maxExpanded = UINT64_MAX;
  // When set, the agent's anchor never leaves this block (start and goal must lie in it);
  // a goal not reachable inside it is Unreachable.
  std::optional<CellRect> region;
  // Footprints to keep off where a way around costs less: a move onto an anchor whose footprint
  // overlaps one of them costs `avoidPenalty` more (in the search's cost unit), so the path
  // goes around them unless every way around costs more than the penalties it saves (a jammed
  // unit's detour around the units standing in its way). The result's cost is the path's own,
  // without penalties. Honoured by AnnotatedAStar; the areas must outlive the query.
  std::span<const CellRect> avoid;
  double avoidPenalty = 0.0;  // [Limit: >= 0]
};
// Limits of expansions and region alone.
inline SearchLimits limitsOf(std::uint64_t maxExpanded, std::optional<CellRect> region) {
  SearchLimits limits;
  limits.maxExpanded = maxExpanded;
  limits.region = region;
  return limits;
}

struct PathResult {
  PathStatus status = PathStatus::Unreachable;
  // [Unit: cells] path length with diagonal steps counted as √2; under terrain costs
  // (terrain_costs.h) the costs' unit instead: seconds for a unit type's 1 / speed
  double cost = 0.0;
  SearchMetrics metrics;

  bool found() const { return status == PathStatus::Found; }
};

// Sliced queries (Detour's init / update / finalize), offered by every planner's query object:
//   beginPath(agent, start, goal, ...)  starts a query, abandoning any unfinished one, and
//                                       answers at once what needs no search;
//   updatePath(maxExpansions)           advances it by at most that many expansions
//                                       [Limit: >= 1; 0 advances nothing], but for a step
//                                       that cannot be split (an HAA* insertion) larger than
//                                       that, taken whole when it is the update's first, so
//                                       that every slice makes progress;
//   finalizePath(path)                  its result: what findPath returns for the same query
//                                       (status, cells, cost, metrics; microseconds sums the
//                                       calls' wall time).
// beginPath and updatePath return PathStatus::Pending until the query is done, then its final
// status (again on later calls, without work); finalizePath answers Pending and no cells while
// it is unfinished. expandedSoFar() is the query's expansions so far, for budgets spread over
// calls; nextStepExpansions() the most the query's next unsplittable step may spend (1 but
// before an insertion), so that a caller with less budget left can wait for the next one. findPath
// is begin, one unbounded update and finalize. Nothing the query reads may change while it is
// unfinished (the grid's terrain, a graph repair): begin it again after.
inline constexpr std::uint64_t kUnboundedExpansions = UINT64_MAX;

// The expansion count at which a slice of `maxExpansions` begun at `expanded` ends (saturating).
// Slices end between two expansions, so a sliced query expands exactly what an unsliced one does.
constexpr std::uint64_t sliceEnd(std::uint64_t expanded, std::uint64_t maxExpansions) {
  return maxExpansions >= UINT64_MAX - expanded ? UINT64_MAX : expanded + maxExpansions;
}

// Wall time since construction, for SearchMetrics::microseconds (a measurement only). A clock
// made not running reads no time and measures 0.
class QueryClock {
 public:
  QueryClock() : QueryClock(true) {}
  explicit QueryClock(bool running)
      : running_(running),
        began_(running ? std::chrono::steady_clock::now()
                       : std::chrono::steady_clock::time_point{}) {}
  double elapsedMicroseconds() const {
    if (!running_) return 0.0;
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - began_)
        .count();
  }

 private:
  bool running_;
  std::chrono::steady_clock::time_point began_;
};

// Whether a query object's phases (begin, update, finalize) time themselves, as sliced queries
// need. A query run whole (findPath) is timed once instead, and so are the queries a planner
// runs inside its own (it stops its inner objects timing their phases): a query on a small map
// takes a hundred or a few hundred ns, and each clock read is a share of that.
class PhaseTiming {
 public:
  QueryClock phaseClock() const { return QueryClock(timed_); }
  // For a query object another planner owns and times.
  void stopTimingPhases() { timed_ = false; }
  // Runs a query's phases (`run` returns its result) under one clock: the result's
  // microseconds are the whole query's.
  template <typename Run>
  PathResult whole(Run&& run) {
    const QueryClock clock;
    const bool timed = timed_;
    timed_ = false;
    PathResult result = run();
    timed_ = timed;
    result.metrics.microseconds = clock.elapsedMicroseconds();
    return result;
  }

 private:
  bool timed_ = true;
};

}  // namespace warpath::pathing
