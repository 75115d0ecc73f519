// Unit definitions, steering and the stuck rule: pure logic, no world.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "units/steering.h"
#include "units/stuck.h"
#include "units/unit_type.h"

namespace warpath::units {
namespace {

using pathing::Capability;
using pathing::Cell;
using pathing::Terrain;

UnitType tank() {
  UnitType t;
  t.name = "tank";
  t.size = 3;
  t.capability = Capability::of({Terrain::Ground});
  t.setSpeed(2.0);
  t.radius = 1.4;
  return t;
}

TEST(UnitType, SpeedOnlyOnTerrainsOfTheCapability) {
  UnitType t = tank();
  EXPECT_EQ(t.speedOn(Terrain::Ground), 2.0);
  EXPECT_EQ(t.speedOn(Terrain::Water), 0.0);
  EXPECT_EQ(t.speedOn(Terrain::Blocked), 0.0);
  EXPECT_EQ(t.maxSpeed(), 2.0);
  EXPECT_EQ(problemWith(t), "");
}

TEST(UnitType, CostsAreSecondsPerCellOnItsTerrains) {
  const pathing::TerrainCosts costs = tank().terrainCosts();
  EXPECT_DOUBLE_EQ(costs.perCell[static_cast<std::size_t>(Terrain::Ground)], 0.5);
  EXPECT_EQ(costs.perCell[static_cast<std::size_t>(Terrain::Water)], 0.0);  // not entered
  EXPECT_EQ(costs.capability(), tank().capability);
}

TEST(UnitType, ProblemsAreNamed) {
  UnitType t = tank();
  t.radius = 1.6;  // wider than the 3-cell footprint
  EXPECT_NE(problemWith(t).find("radius"), std::string::npos);
  t = tank();
  t.speed[static_cast<std::size_t>(Terrain::Ground)] = 0.0;
  EXPECT_NE(problemWith(t).find("speed on ground"), std::string::npos);
  t = tank();
  t.capability = {};
  EXPECT_NE(problemWith(t).find("capability"), std::string::npos);
}

TEST(Steering, AnchorAndCentreConvertBothWays) {
  for (int size = 1; size <= 4; ++size) {
    for (Cell c : {Cell{0, 0}, Cell{5, 7}, Cell{100, 3}}) {
      const Vec2 centre = anchorToCentre(c, size);
      EXPECT_EQ(centre.x, c.x + size / 2.0);
      EXPECT_EQ(centreToAnchor(centre, size), c);
      // Anywhere within half a cell of the centre rounds to the same anchor.
      EXPECT_EQ(centreToAnchor(centre + Vec2{0.49, -0.49}, size), c);
    }
  }
}

TEST(Steering, HeadsForTheNextWaypointAtFullSpeed) {
  const std::vector<Cell> path{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}};
  const SteeringResult r = steer(path, 0, 1, {0.5, 0.5}, 2.0);
  EXPECT_EQ(r.next, 1u);  // the first waypoint is where the unit stands
  EXPECT_NEAR(r.desiredVelocity.x, 2.0, 1e-12);
  EXPECT_NEAR(r.desiredVelocity.y, 0.0, 1e-12);
  EXPECT_FALSE(r.reachedEnd);
}

TEST(Steering, SlowsDownOnArrivalAndStops) {
  const std::vector<Cell> path{{0, 0}, {1, 0}, {2, 0}};
  SteeringParams params;
  const SteeringResult near = steer(path, 2, 1, {2.5 - 0.75, 0.5}, 2.0, params);
  EXPECT_NEAR(near.desiredVelocity.x, 2.0 * 0.75 / params.slowdownDistance, 1e-12);
  const SteeringResult at = steer(path, 2, 1, {2.5 - 0.1, 0.5}, 2.0, params);
  EXPECT_TRUE(at.reachedEnd);
  EXPECT_EQ(at.desiredVelocity, Vec2{});
}

TEST(Steering, SkipsWaypointsTheUnitWasPushedPast) {
  const std::vector<Cell> path{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}};
  const SteeringResult r = steer(path, 1, 1, {3.6, 0.5}, 1.0);
  EXPECT_EQ(r.next, 4u);
  EXPECT_GT(r.desiredVelocity.x, 0.0);
}

TEST(Steering, ARewoundWaypointIsTheNextFromWhereAPushedBackUnitStands) {
  // A corridor along x, then a turn south: pushed back from waypoint 5 to x = 1.7, the unit has
  // passed (1, 0) and would head for (2, 0).
  const std::vector<Cell> path{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}, {5, 1}};
  EXPECT_EQ(rewoundWaypoint(path, 5, 1, {1.7, 0.5}, 0.5), 2u);
  // Within the radius of the waypoint before, or beside the path rather than behind: no change.
  EXPECT_EQ(rewoundWaypoint(path, 5, 1, {4.2, 0.5}, 0.5), 5u);
  EXPECT_EQ(rewoundWaypoint(path, 6, 1, {5.5, 0.2}, 0.5), 6u);
  EXPECT_EQ(rewoundWaypoint(path, 3, 1, {2.6, 2.5}, 0.5), 3u);
  // Never before the path's start.
  EXPECT_EQ(rewoundWaypoint(path, 5, 1, {-3.0, 0.5}, 0.5), 0u);
}

TEST(Steering, LargeUnitsSteerTheirCentreToTheFootprintCentre) {
  const std::vector<Cell> path{{10, 10}, {10, 11}};
  const SteeringResult r = steer(path, 1, 3, anchorToCentre({10, 10}, 3), 1.0);
  EXPECT_NEAR(r.desiredVelocity.x, 0.0, 1e-12);
  EXPECT_NEAR(r.desiredVelocity.y, 1.0 / SteeringParams{}.slowdownDistance, 1e-12);
}

TEST(Steering, VelocityLimitedByTurnRateAndAcceleration) {
  const double dt = 0.1;
  // Reversing: the heading turns by at most turnRate·dt.
  const Vec2 v = limitVelocity({1.0, 0.0}, {-1.0, 0.0}, 100.0, std::numbers::pi / 2, dt);
  EXPECT_NEAR(std::atan2(v.y, v.x), std::numbers::pi / 2 * dt, 1e-9);
  // From rest: speed grows by at most acceleration·dt, in the desired direction.
  const Vec2 w = limitVelocity({}, {0.0, 5.0}, 2.0, 1.0, dt);
  EXPECT_NEAR(w.y, 0.2, 1e-12);
  EXPECT_NEAR(w.x, 0.0, 1e-12);
  // Braking to a stop.
  EXPECT_EQ(limitVelocity({0.1, 0.0}, {}, 2.0, 1.0, dt), Vec2{});
  const Vec2 b = limitVelocity({1.0, 0.0}, {}, 2.0, 1.0, dt);
  EXPECT_NEAR(b.x, 0.8, 1e-12);
}

// A unit turns the shorter way round unless told which way (the engine's choice when the shorter
// way is into a wall).
TEST(Steering, TurnsTheWayItIsToldOrElseTheShorterWay) {
  const double dt = 0.1;
  const double step = std::numbers::pi / 2 * dt;
  // Heading +x, wanting 135° to negative angles: the shorter way is negative.
  const Vec2 desired{-1.0, -1.0};
  EXPECT_EQ(shorterTurn({1.0, 0.0}, desired), -1);
  EXPECT_EQ(shorterTurn({1.0, 0.0}, {-1.0, 1.0}), 1);
  EXPECT_EQ(shorterTurn({1.0, 0.0}, {-1.0, 0.0}), 1);  // straight behind: as atan2 turns
  EXPECT_EQ(shorterTurn({1.0, 0.0}, {2.0, 0.0}), 0);
  EXPECT_EQ(shorterTurn({}, desired), 0);
  const auto angle = [&](int side) {
    const Vec2 v = limitVelocity({1.0, 0.0}, desired, 100.0, std::numbers::pi / 2, dt, side);
    return std::atan2(v.y, v.x);
  };
  EXPECT_NEAR(angle(0), -step, 1e-9);
  EXPECT_NEAR(angle(-1), -step, 1e-9);
  EXPECT_NEAR(angle(1), step, 1e-9);  // the long way round, 225°
}

// The cap keeps the point outside the turning circle (through it, or within `within` of it):
// at the capped speed the circle of radius speed / turnRate tangent to the heading, on the
// point's side, passes exactly through the point (or exactly `within` from it).
TEST(Steering, TurnLimitedSpeedKeepsThePointOutsideTheTurningCircle) {
  const double turnRate = 2.0;  // [rad/s]
  const Vec2 heading{1.0, 0.0};
  // 45° off, √2 away: through it on a circle of radius 1; within 0.6 of it on one of 2.05.
  EXPECT_NEAR(turnLimitedSpeed(heading, {1.0, 1.0}, turnRate), 2.0, 1e-12);
  EXPECT_NEAR(turnLimitedSpeed(heading, {1.0, 1.0}, turnRate, 0.6), 4.1, 1e-12);
  // Behind: the tightest circle, whose diameter is the distance.
  EXPECT_NEAR(turnLimitedSpeed(heading, {-1.0, 0.0}, turnRate), 1.0, 1e-12);
  EXPECT_NEAR(turnLimitedSpeed(heading, {-1.0, 0.0}, turnRate, 0.6), 1.6, 1e-12);
  // No limit at rest, straight ahead, or where the straight course passes within `within`.
  EXPECT_TRUE(std::isinf(turnLimitedSpeed({}, {1.0, 1.0}, turnRate)));
  EXPECT_TRUE(std::isinf(turnLimitedSpeed(heading, {3.0, 0.0}, turnRate)));
  EXPECT_TRUE(std::isinf(turnLimitedSpeed(heading, {1.0, 0.5}, turnRate, 0.6)));
  EXPECT_TRUE(std::isinf(turnLimitedSpeed(heading, {-0.3, 0.4}, turnRate, 0.6)));
  EXPECT_NEAR(turnLimitedSpeed(heading, {1.0, 0.5}, turnRate), 2.5, 1e-12);
  // The geometry, over points ahead and headings of any length (behind, the cap is that of a
  // point abeam: the tightest circle).
  for (int i = 0; i < 24; ++i) {
    const double angle = 0.3 + i * std::numbers::pi / 12;
    const Vec2 velocity{0.5 + 0.1 * i, 0.2};
    const Vec2 offset{2.0 * std::cos(angle), 2.0 * std::sin(angle)};
    if (velocity.dot(offset) <= 0.0) continue;
    for (const double within : {0.0, 0.2, 0.6}) {
      const double speed = turnLimitedSpeed(velocity, offset, turnRate, within);
      if (std::isinf(speed)) continue;
      const double radius = speed / turnRate;
      const Vec2 forward = velocity * (1.0 / velocity.length());
      const double side = forward.x * offset.y - forward.y * offset.x >= 0.0 ? 1.0 : -1.0;
      const Vec2 centre = Vec2{-forward.y, forward.x} * (side * radius);
      EXPECT_NEAR(radius - (offset - centre).length(), within, 1e-9) << i << " " << within;
    }
  }
}

TEST(Stuck, FiresAfterAWindowWithoutProgress) {
  StuckRule rule;
  rule.windowSeconds = 1.0;
  rule.minProgress = 0.5;
  ProgressMonitor m;
  m.reset({0, 0}, 0);
  for (int tick = 1; tick < 10; ++tick)
    EXPECT_FALSE(m.update({0.01 * tick, 0}, tick, 10.0, rule));
  EXPECT_TRUE(m.update({0.1, 0}, 10, 10.0, rule));
  EXPECT_EQ(m.stuckWindows(), 1);
  EXPECT_TRUE(m.update({0.1, 0}, 20, 10.0, rule));
  EXPECT_EQ(m.stuckWindows(), 2);
  // Progress clears the count.
  EXPECT_FALSE(m.update({1.0, 0}, 21, 10.0, rule));
  EXPECT_EQ(m.stuckWindows(), 0);
}

TEST(Stuck, AnExcusedWindowDoesNotCountTowardTheFlag) {
  StuckRule rule;
  rule.windowSeconds = 1.0;
  ProgressMonitor m;
  m.reset({0, 0}, 0);
  EXPECT_TRUE(m.update({0, 0}, 10, 10.0, rule));
  EXPECT_EQ(m.stuckWindows(), 1);
  // Queued: the window still closes without progress (the engine may look for a way round),
  // but the count stays where it was.
  EXPECT_TRUE(m.update({0, 0}, 20, 10.0, rule));
  m.excuseWindow();
  EXPECT_EQ(m.stuckWindows(), 1);
  EXPECT_TRUE(m.update({0, 0}, 30, 10.0, rule));
  EXPECT_EQ(m.stuckWindows(), 2);
  // Nothing to excuse after progress.
  EXPECT_FALSE(m.update({1.0, 0}, 31, 10.0, rule));
  m.excuseWindow();
  EXPECT_EQ(m.stuckWindows(), 0);
}

TEST(Stuck, MovingUnitsAreNeverStuck) {
  StuckRule rule;
  ProgressMonitor m;
  m.reset({0, 0}, 0);
  for (int tick = 1; tick < 1000; ++tick)
    EXPECT_FALSE(m.update({0.05 * tick, 0}, tick, 30.0, rule));
}

}  // namespace
}  // namespace warpath::units
