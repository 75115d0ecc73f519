#pragma once
// The stuck rule: a unit with somewhere to go that moves less than `minProgress` cells within
// `windowSeconds` is stuck. The engine repaths it; after `flagAfter` stuck windows in a row
// it is also reported as stuck.

#include <cstdint>

#include "units/steering.h"

namespace warpath::units {

struct StuckRule {
  double windowSeconds = 3.0;  // [Unit: s] [Limit: > 0]
  double minProgress = 0.5;    // [Unit: cells] [Limit: >= 0]
  int flagAfter = 3;           // [Limit: >= 1] consecutive stuck windows before a unit is flagged
};

// Tracks one unit's progress; plain data (an aggregate, so the engine's state description can
// be checked field by field) that is changed through its methods only.
struct ProgressMonitor {
  // Starts afresh at `position` (a new order).
  void reset(Vec2 position, std::int64_t tick) {
    restartWindow(position, tick);
    stuckInARow = 0;
  }
  // Starts a new window at `position` but keeps the count of stuck windows in a row (a new
  // path for the same order: a repath that does not help still ends in a flag).
  void restartWindow(Vec2 position, std::int64_t tick) {
    origin = position;
    originTick = tick;
    originRemaining = kUnknownRemaining;
  }
  // Call once a tick while the unit is moving somewhere. True when this tick closes a window
  // without progress; stuckWindows() then tells how many such windows came in a row.
  bool update(Vec2 position, std::int64_t tick, double ticksPerSecond, const StuckRule& rule);

  // The same rule with progress measured along the unit's path, not as displacement:
  // `remaining` [Unit: cells] is what is left of the path. A unit that circles a waypoint or is
  // shoved sideways moves without progress; one pushed back loses it.
  bool updateAlong(Vec2 position, double remaining, std::int64_t tick, double ticksPerSecond,
                   const StuckRule& rule);

  // The window that update/updateAlong just closed without progress was spent queued behind a
  // unit that is making progress: it does not count toward the flag (the queue's head answers
  // for a jam), though the engine may still look for a way round.
  void excuseWindow() {
    if (stuckInARow > 0) --stuckInARow;
  }

  int stuckWindows() const { return stuckInARow; }

  // A restarted window has no distance yet: the first updateAlong counts as progress and
  // records one.
  static constexpr double kUnknownRemaining = 1e300;

  Vec2 origin;                                 // [Unit: cells] where the current window started
  std::int64_t originTick = 0;                 // [Unit: ticks] when it started
  int stuckInARow = 0;                         // windows without progress in a row
  double originRemaining = kUnknownRemaining;  // [Unit: cells] updateAlong: path left at origin
};

}  // namespace warpath::units
