#include "units/stuck.h"

namespace warpath::units {

namespace {

// One tick of the rule, however progress is measured: progress restarts the window and clears
// the count; a window that closes without it counts one more.
bool closeWindow(ProgressMonitor& m, bool progressed, Vec2 position, double remaining,
                 std::int64_t tick, double ticksPerSecond, const StuckRule& rule) {
  if (!progressed && static_cast<double>(tick - m.originTick) < rule.windowSeconds * ticksPerSecond)
    return false;
  m.origin = position;
  m.originTick = tick;
  m.originRemaining = remaining;
  if (progressed) {
    m.stuckInARow = 0;
    return false;
  }
  ++m.stuckInARow;
  return true;
}

}  // namespace

bool ProgressMonitor::update(Vec2 position, std::int64_t tick, double ticksPerSecond,
                             const StuckRule& rule) {
  const bool progressed = (position - origin).length() >= rule.minProgress;
  return closeWindow(*this, progressed, position, originRemaining, tick, ticksPerSecond, rule);
}

bool ProgressMonitor::updateAlong(Vec2 position, double remaining, std::int64_t tick,
                                  double ticksPerSecond, const StuckRule& rule) {
  const bool progressed = originRemaining - remaining >= rule.minProgress;
  return closeWindow(*this, progressed, position, remaining, tick, ticksPerSecond, rule);
}

}  // namespace warpath::units
