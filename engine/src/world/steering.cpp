// Steering: each living unit's desired velocity (following its path, holding its parking spot,
// or halted to fight) limited by what it can do in a tick, handed to physics; and the physics
// step itself, whose positions and velocities are read back into the units.

#include "engine/src/world/phases.h"

namespace warpath::engine::world {

using pathing::Cell;
using units::Vec2;

void steerAll(Refs& w) {
  const double dt = 1.0 / w.settings.tickRate;
  const pathing::GridMap& map = w.map();
  for (Unit& unit : w.state.units) {
    if (!unit.alive()) continue;
    const units::UnitType& type = w.typeOf(unit);
    Vec2 desired;
    if (unit.engaged) {
      // Halted to fight: the stall is on purpose, not a jam.
      unit.progress.restartWindow(unit.position, w.state.tick);
    } else if (unit.state == UnitState::Parked) {
      // Hold the goal cell: a unit shoved off it steers back.
      const Cell goal[] = {unit.goalCell};
      const units::SteeringResult r =
          units::steer(goal, 0, type.size, unit.position, type.maxSpeed(), w.settings.steering);
      desired = r.desiredVelocity;
    } else if (unit.state == UnitState::Moving && unit.path) {
      const Cell under{static_cast<int>(std::floor(unit.position.x)),
                       static_cast<int>(std::floor(unit.position.y))};
      double speed = type.speedOn(map.at(under));
      if (!(speed > 0.0)) speed = type.maxSpeed();
      const units::SteeringResult r = units::steer(unit.path->cells, unit.next, type.size,
                                                   unit.position, speed, w.settings.steering);
      unit.next = r.next;
      desired = r.desiredVelocity;
      if (r.reachedEnd) {
        if (unit.order == OrderKind::Attack) {
          // At the approach cell: wait there for the target to come into sight or move.
          unit.state = UnitState::Idle;
        } else {
          unit.state = UnitState::Parked;
          w.state.goals.overwrite(GoalLayer::Parked, unit.goalCell, type.size, unit.id);
          w.log(EventKind::Parked, unit);
        }
      }
    }
    const Vec2 v =
        units::limitVelocity(unit.velocity, desired, type.acceleration, type.turnRate, dt);
    w.state.physics->setVelocity(unit.body, v);
  }
}

void stepPhysics(Refs& w) {
  w.state.physics->step(1.0 / w.settings.tickRate);
  for (Unit& unit : w.state.units) {
    if (!unit.alive()) continue;
    unit.position = w.state.physics->position(unit.body);
    unit.velocity = w.state.physics->velocity(unit.body);
  }
}

}  // namespace warpath::engine::world
