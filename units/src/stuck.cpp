#include "units/stuck.h"

namespace warpath::units {

bool ProgressMonitor::update(Vec2 position, std::int64_t tick, double ticksPerSecond,
                             const StuckRule& rule) {
  if ((position - origin).length() >= rule.minProgress) {
    origin = position;
    originTick = tick;
    stuckInARow = 0;
    return false;
  }
  if (static_cast<double>(tick - originTick) < rule.windowSeconds * ticksPerSecond) return false;
  origin = position;
  originTick = tick;
  ++stuckInARow;
  return true;
}

}  // namespace warpath::units
