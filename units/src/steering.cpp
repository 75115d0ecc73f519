#include "units/steering.h"

#include <algorithm>
#include <numbers>

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

Vec2 limitVelocity(Vec2 current, Vec2 desired, double acceleration, double turnRate, double dt) {
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
    const double maxTurn = turnRate * dt;
    heading = from + std::clamp(turn, -maxTurn, maxTurn);
  }
  const double speed = std::clamp(desiredSpeed, currentSpeed - maxDelta, currentSpeed + maxDelta);
  return {std::cos(heading) * speed, std::sin(heading) * speed};
}

}  // namespace warpath::units
