#include "units/stuck.h"

namespace warpath::units {

bool ProgressMonitor::update(Vec2 position, std::int64_t tick, double ticksPerSecond,
                             const StuckRule& rule) {
  if ((position - origin_).length() >= rule.minProgress) {
    origin_ = position;
    originTick_ = tick;
    stuckWindows_ = 0;
    return false;
  }
  if (static_cast<double>(tick - originTick_) < rule.windowSeconds * ticksPerSecond) return false;
  origin_ = position;
  originTick_ = tick;
  ++stuckWindows_;
  return true;
}

}  // namespace warpath::units
