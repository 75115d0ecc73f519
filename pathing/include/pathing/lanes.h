#pragma once
// Two-way traffic in lanes: a path moved into the right half of the passage it runs through,
// so that units crossing a bridge, a road or a corridor wide enough for two pass each other
// instead of meeting head on on the one shortest line.

#include <span>
#include <vector>

#include "pathing/annotated_grid.h"

namespace warpath::pathing {

// The widest passage [Unit: cells] that gets lanes for a size-s agent: 16 cells, or four
// footprints for larger agents. Wider places are open ground, where local avoidance lets units
// slide past each other.
constexpr int laneWidth(int size) {
  return size * 4 > 16 ? size * 4 : 16;
}

// Which of keepRight's rules apply. Each came with a replay format of the engine, whose older
// files play back without it.
struct LaneRules {
  // A lane goes on through a junction, a stretch of at most laneWidth() cells too wide for
  // lanes between two lane runs of one direction, along the line it entered on; without, the
  // path comes back to its own line there.
  bool throughJunctions = true;
  // A lane's full shift holds for two footprints beyond each end of its run, so that the
  // approach and the way out keep right too; without, the shift tapers from the run's ends.
  bool holdBeyond = true;
  // With holdBeyond: five footprints where the passage is at least five footprints across, room
  // for two each way and more, where crowds queue at the mouths.
  bool holdFartherWhereWide = true;
  // A lane's detour may cost its largest shift there and back (twice the shift) where that is
  // more than the fixed allowance (two cells per cell of footprint side plus one): a jeep moved
  // 8 cells over on a bridge 16 wide pays 6-9 cells for the steps there and back, more than its
  // fixed 6. Without, such a lane was dropped and the jeep kept to the edge the other way's
  // traffic drives along (bridge16_mixed).
  bool detourByShift = true;
};

// `path` (legal single moves for the agent, start to goal) kept to the right: where the path
// runs along a row or a column, the passage across the direction of travel (the standable
// anchors to either side) is split in two halves of its cells, and a footprint in the left half
// moves over to the nearest anchor whose footprint lies in the right half; where the passage is
// narrower than two footprints or wider than laneWidth(), the path stays. A lane begins before
// its passage and ends after it (`rules`), then a shift carries to the cells around, a cell less
// each. Shifts grow and shrink by at most a cell per step (so the start and the goal stay where
// they are) and the shifted cells are joined by legal single moves; if they cannot be, the path
// comes back unchanged. The result is legal for the agent and runs from path.front() to
// path.back().
std::vector<Cell> keepRight(const AnnotatedGrid& grid, Agent agent, std::span<const Cell> path,
                            LaneRules rules = {});

}  // namespace warpath::pathing
