#include "units/steering.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace warpath::units {

SteeringResult steer(std::span<const pathing::Cell> path, std::size_t next, int size, Vec2 centre,
                     double maxSpeed, const SteeringParams& params) {
  const auto distanceTo = [&](std::size_t i) {
    return (anchorToCentre(path[i], size) - centre).length();
  };
  const std::size_t last = path.size() - 1;
  while (next < last) {
    const double here = distanceTo(next);
    // Passed, or pushed nearer to the following waypoint than to this one.
    if (here <= params.waypointRadius || distanceTo(next + 1) <= here)
      ++next;
    else
      break;
  }
  SteeringResult result;
  result.next = next;
  const Vec2 offset = anchorToCentre(path[next], size) - centre;
  const double distance = offset.length();
  if (next == last && distance <= params.arrivalRadius) {
    result.reachedEnd = true;
    return result;
  }
  double speed = maxSpeed;
  if (next == last) speed *= std::min(1.0, distance / params.slowdownDistance);
  result.desiredVelocity = offset * (speed / distance);
  return result;
}

std::size_t rewoundWaypoint(std::span<const pathing::Cell> path, std::size_t next, int size,
                            Vec2 centre, double radius) {
  while (next > 0) {
    const Vec2 before = anchorToCentre(path[next - 1], size);
    const Vec2 from = centre - before;
    if (from.length() <= radius || from.dot(anchorToCentre(path[next], size) - before) >= 0.0)
      break;
    --next;
  }
  return next;
}

double turnLimitedSpeed(Vec2 velocity, Vec2 offset, double turnRate, double within) {
  const double speed = velocity.length();
  const double distance = offset.length();
  if (speed < 1e-6 || distance < 1e-9) return INFINITY;
  const double cross = velocity.x * offset.y - velocity.y * offset.x;
  const double sinTheta = std::abs(cross) / (speed * distance);
  const bool ahead = velocity.dot(offset) > 0.0;
  // Behind the unit the needed circle is the tightest one (θ near 180° has sin near 0).
  const double s = ahead ? sinTheta : 1.0;
  // (At within = 0 this is the formula below, which is kept apart: older replays' state hashes
  // hold its rounding and its one-degree dead zone.)
  if (within > 0.0) {
    if (distance <= within || distance * s <= within) return INFINITY;
    return turnRate * (distance * distance - within * within) / (2.0 * (distance * s - within));
  }
  if (s < 0.0175) return INFINITY;  // within a degree of straight ahead
  return turnRate * distance / (2.0 * s);
}

std::span<const pathing::TimedCell>::iterator nextStep(std::span<const pathing::TimedCell> steps,
                                                       double tick) {
  if (steps.empty()) return steps.end();
  return std::upper_bound(
      steps.begin() + 1, steps.end(), tick,
      [](double t, const pathing::TimedCell& step) { return t < static_cast<double>(step.tick); });
}

namespace {

// Where the plan puts the body centre at `tick` (fractional), and whether that is a hold.
std::pair<Vec2, bool> scheduledAt(std::span<const pathing::TimedCell> steps, double tick,
                                  int size) {
  if (tick <= static_cast<double>(steps.front().tick))
    return {anchorToCentre(steps.front().cell, size), steps.size() == 1};
  const auto next = nextStep(steps, tick);
  if (next == steps.end()) return {anchorToCentre(steps.back().cell, size), true};
  const pathing::TimedCell& from = *(next - 1);
  const double t0 = static_cast<double>(from.tick);
  const double t1 = static_cast<double>(next->tick);
  const Vec2 a = anchorToCentre(from.cell, size);
  const Vec2 b = anchorToCentre(next->cell, size);
  return {a + (b - a) * ((tick - t0) / (t1 - t0)), from.cell == next->cell};
}

}  // namespace

ScheduleResult followPlan(std::span<const pathing::TimedCell> steps, std::int64_t tick, int size,
                          Vec2 centre, double maxSpeed, double ticksPerSecond,
                          double lookaheadSeconds) {
  ScheduleResult result;
  const double now = static_cast<double>(tick);
  const auto [here, waiting] = scheduledAt(steps, now, size);
  result.scheduled = here;
  result.waiting = waiting;
  result.finished = tick >= steps.back().tick;
  const Vec2 ahead = scheduledAt(steps, now + lookaheadSeconds * ticksPerSecond, size).first;
  const Vec2 offset = ahead - centre;
  // Closer than a hair to where it should be: stand still rather than jitter.
  if (offset.length() < 0.02) return result;
  Vec2 desired = offset * (1.0 / lookaheadSeconds);
  const double speed = desired.length();
  if (speed > maxSpeed) desired = desired * (maxSpeed / speed);
  result.desiredVelocity = desired;
  return result;
}

int shorterTurn(Vec2 current, Vec2 desired) {
  const double cross = current.x * desired.y - current.y * desired.x;
  if (cross > 0.0) return 1;
  if (cross < 0.0) return -1;
  // Straight behind: either way is as short.
  return current.dot(desired) < 0.0 ? 1 : 0;
}

Vec2 limitVelocity(Vec2 current, Vec2 desired, double acceleration, double turnRate, double dt,
                   int turnSide) {
  const double currentSpeed = current.length();
  const double desiredSpeed = desired.length();
  const double maxDelta = acceleration * dt;
  constexpr double kAtRest = 1e-6;
  if (desiredSpeed < kAtRest) {
    // Brake along the current heading.
    if (currentSpeed <= maxDelta) return {};
    return current * ((currentSpeed - maxDelta) / currentSpeed);
  }
  double heading = std::atan2(desired.y, desired.x);
  if (currentSpeed >= kAtRest) {
    const double from = std::atan2(current.y, current.x);
    double turn = heading - from;
    if (turn > std::numbers::pi) turn -= 2.0 * std::numbers::pi;
    if (turn < -std::numbers::pi) turn += 2.0 * std::numbers::pi;
    if (turnSide > 0 && turn < 0.0) turn += 2.0 * std::numbers::pi;
    if (turnSide < 0 && turn > 0.0) turn -= 2.0 * std::numbers::pi;
    const double maxTurn = turnRate * dt;
    heading = from + std::clamp(turn, -maxTurn, maxTurn);
  }
  const double speed = std::clamp(desiredSpeed, currentSpeed - maxDelta, currentSpeed + maxDelta);
  return {std::cos(heading) * speed, std::sin(heading) * speed};
}

}  // namespace warpath::units
