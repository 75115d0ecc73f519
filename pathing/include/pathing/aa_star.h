#pragma once
// Annotated A* (Harabor & Botea 2008): optimal 8-connected search for an agent of any size
// and capability, with octile distance as heuristic. A query object owns its scratch memory
// and reuses it, so after the first query on a map it allocates nothing (given a `path`
// vector whose capacity is reused too). One query object per thread; the AnnotatedGrid may
// be shared.

#include <cstdint>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/open_list.h"
#include "pathing/search.h"
#include "pathing/terrain_costs.h"

namespace warpath::pathing {

class AnnotatedAStar {
 public:
  explicit AnnotatedAStar(const AnnotatedGrid& grid);

  // Finds a shortest path for `agent` from `start` to `goal` (anchor cells). When found and
  // `path` is not null, it receives every cell from start to goal inclusive.
  PathResult findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                      const SearchLimits& limits = {});
  // The same under terrain costs (pathing/terrain_costs.h, built for this agent on this grid):
  // a cheapest path, result.cost in the costs' unit; moves onto an anchor without a cost are
  // not taken. The heuristic is octile distance times costs.cheapest().
  PathResult findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                      const CostField& costs, const SearchLimits& limits = {});

  // The same query sliced (search.h): stops after at most `maxExpansions` expansions per
  // updatePath and resumes where it stopped. `costs` must outlive the query.
  PathStatus beginPath(Agent agent, Cell start, Cell goal, const SearchLimits& limits = {});
  PathStatus beginPath(Agent agent, Cell start, Cell goal, const CostField& costs,
                       const SearchLimits& limits = {});
  PathStatus updatePath(std::uint64_t maxExpansions);
  PathResult finalizePath(std::vector<Cell>* path);
  std::uint64_t expandedSoFar() const { return result_.metrics.expanded; }
  std::uint64_t nextStepExpansions() const { return 1; }
  // For a planner that runs this one's queries inside its own and times them (PhaseTiming).
  void stopTimingPhases() { timing_.stopTimingPhases(); }

 private:
  // Per-cell search state, split so that the common checks touch 4 bytes a cell: the stamp
  // holds the query generation (upper 28 bits), a closed flag (bit 3) and the direction the
  // cell was reached by (bits 0-2); g is read only for open cells of this query.
  static constexpr std::uint32_t kClosedBit = 8;
  static constexpr int kGenerationShift = 4;

  void resetScratch();
  PathStatus begin(Agent agent, Cell start, Cell goal, const CostField* costs,
                   const SearchLimits& limits);
  // Expands until done or `maxExpansions` more were expanded (then Pending).
  template <bool kInRegion, bool kWeighted, bool kAvoiding>
  PathStatus search(std::uint64_t maxExpansions);
  // The dispatch of search() on the query's limits and costs.
  template <bool kAvoiding>
  PathStatus searchAvoiding(std::uint64_t maxExpansions);

  const AnnotatedGrid& grid_;
  // The query under way: its arguments and its result so far (status Pending until done).
  const AgentLayer* layer_ = nullptr;
  int agentSize_ = 1;
  Cell start_;
  Cell goal_;
  const CostField* costs_ = nullptr;
  SearchLimits limits_;
  PathResult result_;
  std::vector<std::uint32_t> stamps_;
  std::vector<double> g_;
  OpenList open_;
  std::uint32_t generation_ = 0;
  PhaseTiming timing_;
};

}  // namespace warpath::pathing
