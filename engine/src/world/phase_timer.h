#pragma once
// Wall time per phase of the tick: measurement only, never read by the simulation.

#include <algorithm>
#include <array>
#include <chrono>

#include "engine/world.h"

namespace warpath::engine::world {

enum class Phase : std::uint8_t { Pathing, Combat, Steering, Physics, Bookkeeping };

class PhaseTimer {
 public:
  void beginTick() { tickStart_ = last_ = std::chrono::steady_clock::now(); }
  // Charges the time since the last mark to `phase`.
  void mark(Phase phase) {
    const auto now = std::chrono::steady_clock::now();
    sums_[static_cast<std::size_t>(phase)] +=
        std::chrono::duration<double, std::micro>(now - last_).count();
    last_ = now;
  }
  void endTick() {
    slowest_ =
        std::max(slowest_, std::chrono::duration<double, std::micro>(last_ - tickStart_).count());
    ++ticks_;
  }
  // Means per tick; the slowest tick whole.
  TickTiming mean() const {
    const double n = ticks_ > 0 ? static_cast<double>(ticks_) : 1.0;
    TickTiming t;
    t.pathingMicros = sums_[static_cast<std::size_t>(Phase::Pathing)] / n;
    t.combatMicros = sums_[static_cast<std::size_t>(Phase::Combat)] / n;
    t.steeringMicros = sums_[static_cast<std::size_t>(Phase::Steering)] / n;
    t.physicsMicros = sums_[static_cast<std::size_t>(Phase::Physics)] / n;
    t.bookkeepingMicros = sums_[static_cast<std::size_t>(Phase::Bookkeeping)] / n;
    t.slowestTickMicros = slowest_;
    t.ticks = ticks_;
    return t;
  }

 private:
  std::chrono::steady_clock::time_point tickStart_;
  std::chrono::steady_clock::time_point last_;
  std::array<double, 5> sums_{};
  double slowest_ = 0.0;
  std::int64_t ticks_ = 0;
};

}  // namespace warpath::engine::world
