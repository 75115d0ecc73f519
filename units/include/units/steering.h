#pragma once
// Steering along a planned path: from a unit's position and its waypoints to the velocity it
// wants, then limited by what the unit can do in one tick. Pure functions of their inputs.
//
// Positions here are body centres in cell units; the planner works with anchor cells (the
// upper-left cell of the footprint). anchorToCentre / centreToAnchor are the only conversion.

#include <cmath>
#include <cstddef>
#include <span>

#include "pathing/cooperative_search.h"
#include "pathing/grid_map.h"

namespace warpath::units {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator*(double k) const { return {x * k, y * k}; }
  constexpr double dot(Vec2 o) const { return x * o.x + y * o.y; }
  constexpr bool operator==(const Vec2&) const = default;
  double length() const { return std::sqrt(x * x + y * y); }
};

// [Unit: cells] The body centre of a size-s unit anchored at `anchor`: (x + s/2, y + s/2).
constexpr Vec2 anchorToCentre(pathing::Cell anchor, int size) {
  return {anchor.x + 0.5 * size, anchor.y + 0.5 * size};
}
// The anchor cell whose footprint is nearest to a body centre (inverse of anchorToCentre).
inline pathing::Cell centreToAnchor(Vec2 centre, int size) {
  return {static_cast<int>(std::floor(centre.x - 0.5 * size + 0.5)),
          static_cast<int>(std::floor(centre.y - 0.5 * size + 0.5))};
}

struct SteeringParams {
  double waypointRadius = 0.6;    // [Unit: cells] an intermediate waypoint counts as passed
  double arrivalRadius = 0.2;     // [Unit: cells] the last waypoint counts as reached
  double slowdownDistance = 1.5;  // [Unit: cells] speed falls linearly to 0 over this distance
};

struct SteeringResult {
  Vec2 desiredVelocity;  // [Unit: cells/s]
  std::size_t next = 0;  // index of the waypoint now steered to
  bool reachedEnd = false;
};

// Desired velocity toward waypoint `next` of `path` (anchor cells) for a unit of `size` whose
// centre is `centre` and whose top speed here is `maxSpeed`. Passed waypoints are skipped,
// including ones the unit was pushed beyond; the last one is approached with slow-down.
// [Limit: next < path.size()]
SteeringResult steer(std::span<const pathing::Cell> path, std::size_t next, int size, Vec2 centre,
                     double maxSpeed, const SteeringParams& params = {});

// For a unit pushed back along its path, the waypoint it should be heading for were it steering
// from where it stands: `next` moved back while the unit stands behind the waypoint before it (on
// the far side from `next`, and beyond `radius` of it [Unit: cells]). steer() only ever skips
// ahead (a vehicle turned about for a waypoint it was pushed a cell past would orbit it), so
// after a long push its `next` lies far ahead of it; with `radius` above the unit's length this
// is where it heads for again, and what is read along the path from the unit's place (the
// passage ahead, the stream it leaves) is read from here.
// [Limit: next < path.size()]
std::size_t rewoundWaypoint(std::span<const pathing::Cell> path, std::size_t next, int size,
                            Vec2 centre, double radius);

// [Unit: cells/s] The fastest a unit that turns at most `turnRate` [rad/s] can go, heading along
// `velocity`, and still pass through a point `offset` away: the circle tangent to the heading
// through the point has radius |offset| / (2 sin θ), θ the angle between heading and offset, and
// speed = turnRate · radius. Without this a vehicle whose turning circle is wider than the
// waypoint radius orbits its waypoint forever. +inf when at rest or heading at the point.
// With `within` > 0 [Unit: cells] the unit need only pass that near the point (a waypoint's
// radius): the circle may hold the point up to `within` inside its rim, so speed = turnRate ·
// (d² − within²) / (2 (d sin θ − within)), d = |offset|, and +inf where d sin θ <= within (the
// straight course passes near enough) or d <= within. Behind the unit θ counts as 90°.
double turnLimitedSpeed(Vec2 velocity, Vec2 offset, double turnRate, double within = 0.0);

// Following a cooperative plan (timed anchor cells, pathing/cooperative_search.h): the unit
// steers toward where the plan puts it `lookaheadSeconds` from now, at the speed that gets it
// there on time (at most maxSpeed), so it keeps to the times it reserved, waits included.
struct ScheduleResult {
  Vec2 desiredVelocity;   // [Unit: cells/s]
  Vec2 scheduled;         // [Unit: cells] where the plan puts the body centre now
  bool waiting = false;   // the plan holds the unit where it is now (a wait, or its end)
  bool finished = false;  // the plan's last tick has passed
};
// The first step after the first that a plan has not reached by `tick` (ticks strictly
// increase), found by bisection (every unit asks several times a tick); steps.end() when the
// plan has reached them all, or has one step. The move or wait under way runs from the step
// before it.
std::span<const pathing::TimedCell>::iterator nextStep(std::span<const pathing::TimedCell> steps,
                                                       double tick);
// [Limit: !steps.empty(), lookaheadSeconds > 0, ticksPerSecond > 0]
ScheduleResult followPlan(std::span<const pathing::TimedCell> steps, std::int64_t tick, int size,
                          Vec2 centre, double maxSpeed, double ticksPerSecond,
                          double lookaheadSeconds);

// The velocity a unit reaches in `dt` seconds going from `current` toward `desired`, turning
// by at most turnRate·dt and changing speed by at most acceleration·dt. It turns the shorter
// way round, unless `turnSide` (+1: toward positive angles, -1: negative) says which way: the
// caller's choice when the shorter way is into a wall.
Vec2 limitVelocity(Vec2 current, Vec2 desired, double acceleration, double turnRate, double dt,
                   int turnSide = 0);
// The way (+1: toward positive angles, -1: negative) that turns `current` toward `desired` the
// shorter way round (+1 when straight behind); 0 when either is zero or they point the same
// way.
int shorterTurn(Vec2 current, Vec2 desired);

}  // namespace warpath::units
