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

// Tracks one unit's progress; plain data so that it can be hashed and copied with the unit.
class ProgressMonitor {
 public:
  // Starts a new window at `position` (on a new order or path).
  void reset(Vec2 position, std::int64_t tick) {
    origin_ = position;
    originTick_ = tick;
    stuckWindows_ = 0;
  }
  // Call once a tick while the unit is moving somewhere. True when this tick closes a window
  // without progress; stuckWindows() then tells how many such windows came in a row.
  bool update(Vec2 position, std::int64_t tick, double ticksPerSecond, const StuckRule& rule);

  int stuckWindows() const { return stuckWindows_; }

 private:
  Vec2 origin_;
  std::int64_t originTick_ = 0;
  int stuckWindows_ = 0;
};

}  // namespace warpath::units
