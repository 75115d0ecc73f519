// Steering: each living unit's desired velocity (following its path, holding its parking spot,
// or halted to fight) limited by what it can do in a tick, handed to physics; and the physics
// step itself, whose positions and velocities are read back into the units.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "engine/src/world/phases.h"

namespace warpath::engine::world {

using pathing::Cell;
using units::Vec2;

void arrive(Refs& w, Unit& unit, const units::UnitType& type) {
  if (unit.order == OrderKind::Attack) {
    unit.state = UnitState::Idle;
    return;
  }
  unit.state = UnitState::Parked;
  w.state.goals.overwrite(GoalLayer::Parked, unit.goalCell, type.size, unit.id);
  w.log(EventKind::Parked, unit);
}

namespace {

// [Unit: rad] How far from its course a vehicle veers to pass a slower unit going its way.
constexpr double kOvertakeRadians = 0.5;
// [Unit: rad] How far to its right a vehicle veers from a vehicle it meets head on (about 63°).
// At 0.6, 0.8, 1.1, 1.4 and 1.57 rad 25, 21, 17, 13 and 19 of 2,600 bench runs failed (34
// without; docs/cooperative.md, "Head on in the open"); 1.2 and more lose bridge_two_way's own
// seed.
constexpr double kHeadOnRadians = 1.1;

// `v` turned by `radians`, toward its right for positive angles (y grows downward).
Vec2 rotated(Vec2 v, double radians) {
  const double c = std::cos(radians);
  const double s = std::sin(radians);
  return {v.x * c - v.y * s, v.x * s + v.y * c};
}

// Whether `other`, following a path, steers toward its next waypoint against `heading` (more
// than 120° from it): a vehicle that wants to come our way, however it moves (stopped nose to
// nose with us, or pushed back by us).
bool headsAt(const Refs& w, const Unit& other, Vec2 heading) {
  if (other.state != UnitState::Moving || !other.path || other.next >= other.path->cells.size())
    return false;
  const Vec2 toWaypoint =
      units::anchorToCentre(other.path->cells[other.next], w.typeOf(other).size) - other.position;
  const double length = toWaypoint.length();
  return length > 1e-9 && toWaypoint.dot(heading) < -0.5 * length;
}

// Cooperative movement: a unit pushing into another goes no faster than that one can walk,
// so a jeep does not drive infantry ahead of it at three times their speed. Who touches whom
// is Box2D's (its contacts after the last step, `touching`). A vehicle (heavier than
// `lightest`) outside a timed window that meets another head on veers to its right
// (PathServiceSettings::headOnKeepRight), as both do, so they pass instead of pushing nose to
// nose and sliding off together sideways; in a timed window the reservations keep them apart.
// It veers too from a lighter vehicle that steers its way however that one moves
// (headOnByIntent): a jeep, faster by kind, does not veer from a tank, and a column of tanks
// pushed one back over a bridge for 20 s instead of passing it.
Vec2 limitPushing(const Refs& w, std::span<const std::uint32_t> touching, const Unit& unit,
                  Vec2 desired, double lightest) {
  const double speed = desired.length();
  if (speed < 1e-9) return desired;
  const Vec2 heading = desired * (1.0 / speed);
  const bool keepRight = w.settings.pathing.headOnKeepRight && !(unit.plan && unit.plan->timed);
  bool headOn = false;
  double cap = speed;
  double side = 0.0;  // which way to pass slower units going our way: > 0 to the left
  // Slower units going our way (or parked): the direction to each and its walking speed.
  std::array<std::pair<Vec2, double>, 8> passing{};
  std::size_t passed = 0;
  for (const std::uint32_t index : touching) {
    if (index >= w.state.units.size()) continue;
    const Unit& other = w.state.units[index];
    if (!other.alive()) continue;
    const units::UnitType& otherType = w.typeOf(other);
    const Vec2 offset = other.position - unit.position;
    const double distance = offset.length();
    // Only what lies ahead (within 60° of the heading) is pushed.
    if (distance < 1e-9 || offset.dot(heading) < 0.5 * distance) continue;
    const Cell under{static_cast<int>(std::floor(other.position.x)),
                     static_cast<int>(std::floor(other.position.y))};
    double walk = w.map().contains(under) ? otherType.speedOn(w.map().at(under)) : 0.0;
    if (!(walk > 0.0)) walk = otherType.maxSpeed();
    if (walk >= speed) {
      const double oncoming = other.velocity.length();
      headOn = headOn || (keepRight && otherType.radius > lightest && oncoming > 0.3 &&
                          other.velocity.dot(heading) < -0.5 * oncoming);
      headOn = headOn || (keepRight && otherType.radius > lightest &&
                          otherType.radius < w.typeOf(unit).radius &&
                          w.settings.pathing.headOnByIntent && headsAt(w, other, heading));
      continue;
    }
    // A slower unit walking our way, or parked, is passed rather than followed at its pace: the
    // vehicle veers round it, pressing on it no faster than it walks.
    const Vec2 v = other.velocity;
    if ((other.state == UnitState::Parked || v.dot(heading) > 0.5 * walk) &&
        passed < passing.size()) {
      side -= heading.x * offset.y - heading.y * offset.x;
      passing[passed++] = {offset * (1.0 / distance), walk};
      continue;
    }
    cap = std::min(cap, walk);
  }
  Vec2 out = desired * (cap / speed);
  if (headOn) out = rotated(out, kHeadOnRadians);
  if (passed == 0) return out;
  out = rotated(out, side >= 0.0 ? kOvertakeRadians : -kOvertakeRadians);
  for (std::size_t i = 0; i < passed; ++i) {
    const auto& [toward, walk] = passing[i];
    const double pressing = out.dot(toward);
    if (pressing > walk) out = out - toward * (pressing - walk);
  }
  return out;
}

// Whether `vehicle` drives into `unit` (they touch): it moves, and the unit lies within 60° of
// its course.
bool drivesInto(const Unit& vehicle, const Unit& unit) {
  const Vec2 v = vehicle.velocity;
  const double speed = v.length();
  const Vec2 offset = unit.position - vehicle.position;
  const double distance = offset.length();
  return speed >= 0.3 && distance > 1e-9 && v.dot(offset) >= 0.5 * speed * distance;
}

// Sideways off a course heading along `heading` (a unit vector), to the `side` (+1: left of
// it, -1: right) at the unit's top speed, keeping the unit's own motion along the course.
Vec2 stepAside(const Refs& w, const Unit& unit, Vec2 heading, double side, Vec2 desired) {
  const Vec2 left{heading.y, -heading.x};
  const double along = desired.dot(heading);
  return heading * along + left * (side * w.typeOf(unit).maxSpeed());
}

// [Unit: cells] Room a unit stepping off a vehicle's course needs beyond its own body.
constexpr double kStepAsideMargin = 0.2;

// The side (+1 left of the course, -1 right) a unit steps to off a vehicle's course through
// `through` along `heading` (a unit vector): the side it is on, unless (stepAsideToRoom) it
// could not stand there beside the vehicle's body (of `vehicleRadius`, on the course level
// with the unit) and could on the other.
double sideToStep(const Refs& w, const Unit& unit, Vec2 through, Vec2 heading,
                  double vehicleRadius) {
  const Vec2 left{heading.y, -heading.x};
  const Vec2 offset = unit.position - through;
  const double side = offset.dot(left) >= 0.0 ? 1.0 : -1.0;
  if (!w.settings.pathing.stepAsideToRoom) return side;
  const Vec2 abreast = through + heading * offset.dot(heading);
  const units::UnitType& type = w.typeOf(unit);
  const double clear = vehicleRadius + 2.0 * type.radius + kStepAsideMargin;
  const auto roomOn = [&](double s) {
    return w.grid.canStand(type.agent(),
                           units::centreToAnchor(abreast + left * (s * clear), type.size));
  };
  return !roomOn(side) && roomOn(-side) ? -side : side;
}

// Cooperative movement: a moving unit of the lightest kind that a heavier unit drives into
// steps off the vehicle's course at its own top speed, keeping what it was doing along it:
// vehicles are not held to infantry's pace by infantry that would let them by. (Parked units
// steer back to their cells; vehicles veer round them.) It steps to the side it already is on,
// unless it could not stand there clear of the vehicle's body (a wall, water) and could on the
// other (PathServiceSettings::stepAsideToRoom, replay format 12): at the crossroads a rifleman
// between a tank keeping right and the arm's wall stepped into the wall, and the tank pushed it
// back down the arm 20 cells.
Vec2 stepAside(const Refs& w, const Unit& unit, const Unit& vehicle, Vec2 desired) {
  const Vec2 heading = vehicle.velocity * (1.0 / vehicle.velocity.length());
  return stepAside(w, unit, heading,
                   sideToStep(w, unit, vehicle.position, heading, w.typeOf(vehicle).radius),
                   desired);
}

// Each vehicle's contacts (Box2D's, after the last step) into s.touching, and for each moving
// unit of the lightest kind the first vehicle (by id) that drives into it; with
// PathServiceSettings::lighterVehiclesStepAside (replay format 26), for each moving vehicle too
// the first heavier one that drives into it. At bridge16_mixed a jeep a few cells from its goal
// met the other side's tank column leaving its area and was pushed back 20 cells onto the
// bridge, driving at the tank in front all the way (its failing seeds of 1-200: 11 without the
// rule, 6 with).
void findContacts(const Refs& w, double lightest, SteeringScratch& s) {
  const std::vector<Unit>& all = w.state.units;
  const bool lighterVehicles = w.settings.pathing.lighterVehiclesStepAside;
  s.start.assign(all.size() + 1, 0);
  s.touching.clear();
  s.stepAsideFor.assign(all.size(), SteeringScratch::kNone);
  for (std::size_t i = 0; i < all.size(); ++i) {
    s.start[i] = static_cast<std::uint32_t>(s.touching.size());
    const Unit& vehicle = all[i];
    if (!vehicle.alive() || !(w.typeOf(vehicle).radius > lightest)) continue;
    w.state.physics->touching(vehicle.body, s.contact);
    s.touching.insert(s.touching.end(), s.contact.begin(), s.contact.end());
    for (const std::uint32_t index : s.contact) {
      if (index >= all.size() || s.stepAsideFor[index] != SteeringScratch::kNone) continue;
      const Unit& other = all[index];
      const double radius = w.typeOf(other).radius;
      if (other.alive() && other.state == UnitState::Moving && !other.engaged &&
          (!(radius > lightest) || (lighterVehicles && radius < w.typeOf(vehicle).radius)) &&
          drivesInto(vehicle, other))
        s.stepAsideFor[index] = static_cast<std::uint32_t>(i);
    }
  }
  s.start[all.size()] = static_cast<std::uint32_t>(s.touching.size());
}

// [Unit: s] How far ahead a vehicle's lane reaches at its top speed.
constexpr double kLaneSeconds = 3.0;
// [Unit: cells] How far ahead a walking unit looks for a vehicle's lane, and the room it keeps.
constexpr double kLaneLookahead = 2.0;
constexpr double kLaneMargin = 0.3;
// [Unit: cells] Side of the buckets walking units are sorted into.
constexpr int kWalkerBucket = 8;

// Cooperative movement: the lane of a moving vehicle is its path over the next kLaneSeconds,
// as wide as its body and a walker's. A moving unit of the lightest kind of another team
// - about to walk into such a lane across it (within kLaneLookahead) stops short of it until
//   the vehicle has gone by;
// - in the lane ahead of the vehicle, walking toward it, steps out of it sideways.
// One crossing the lane already walks on (and steps aside if the vehicle reaches it), and one
// going the vehicle's way follows it. A stream of infantry across a bridge's exit otherwise
// holds a tank there until the whole stream has passed (bridge_two_way, crossroads). Giving
// way to one's own team's vehicles too made convoys' riflemen wait for their vehicles at every
// merge (measured: river_ambush's ambush then met only the rearguard). A vehicle stopped in
// the traffic claims its lane too (its lane ahead is where it would go), unless its window
// holds it or a passage's gate keeps it out: the walkers coming at it would otherwise stop it
// for good, a stream of them at a bridge's mouth until the last has passed. Walkers firing on
// the move, and vehicles waiting their turn or chasing a target, are not traffic here. Vehicles
// never wait for walkers here, so no cycle of waits forms. Decided from the state at the start
// of the tick.
void findVehicleLanes(const Refs& w, double lightest, SteeringScratch& s) {
  const std::vector<Unit>& all = w.state.units;
  s.giveWayWithin.assign(all.size(), std::numeric_limits<double>::infinity());
  s.laneHeading.assign(all.size(), Vec2{});
  s.laneSide.assign(all.size(), 0.0);
  const auto walks = [&](const Unit& u) {
    return u.alive() && u.state == UnitState::Moving && !u.engaged && !u.target.valid() && u.path &&
           !(w.typeOf(u).radius > lightest);
  };
  // Walking units by bucket of kWalkerBucket² cells (a counting sort, in id order within a
  // bucket), to find those near a vehicle without looking at all of them. Units off the map
  // count in the nearest bucket.
  const int columns = std::max(1, (w.map().width() + kWalkerBucket - 1) / kWalkerBucket);
  const int rows = std::max(1, (w.map().height() + kWalkerBucket - 1) / kWalkerBucket);
  // (Truncation is floor here: the value is not negative.)
  const auto bucketAt = [](double v, int count) {
    return std::min(static_cast<int>(std::max(0.0, v) / kWalkerBucket), count - 1);
  };
  const auto bucketOf = [&](Vec2 p) {
    return static_cast<std::size_t>(bucketAt(p.y, rows)) * static_cast<std::size_t>(columns) +
           static_cast<std::size_t>(bucketAt(p.x, columns));
  };
  s.bucketStart.assign(static_cast<std::size_t>(rows) * static_cast<std::size_t>(columns) + 1, 0);
  s.bucketOfUnit.assign(all.size(), SteeringScratch::kNone);
  std::size_t walking = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (!walks(all[i])) continue;
    const std::size_t bucket = bucketOf(all[i].position);
    s.bucketOfUnit[i] = static_cast<std::uint32_t>(bucket);
    ++s.bucketStart[bucket + 1];
    ++walking;
  }
  if (walking == 0) return;
  for (std::size_t b = 1; b < s.bucketStart.size(); ++b)
    s.bucketStart[b] += s.bucketStart[b - 1];
  s.walkers.resize(walking);
  s.bucketFill.assign(s.bucketStart.begin(), s.bucketStart.end() - 1);
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (s.bucketOfUnit[i] != SteeringScratch::kNone)
      s.walkers[s.bucketFill[s.bucketOfUnit[i]]++] = all[i].id.index;
  }
  // Calls visit(walker index) for the walkers in the buckets that cover [x0, x1] × [y0, y1],
  // until it returns false; false when it did.
  const auto forWalkersIn = [&](double x0, double x1, double y0, double y1, auto visit) {
    const int bx0 = bucketAt(x0, columns);
    const int bx1 = bucketAt(x1, columns);
    const int by1 = bucketAt(y1, rows);
    for (int by = bucketAt(y0, rows); by <= by1; ++by) {
      const std::size_t row = static_cast<std::size_t>(by) * static_cast<std::size_t>(columns);
      for (std::uint32_t i = s.bucketStart[row + static_cast<std::size_t>(bx0)];
           i < s.bucketStart[row + static_cast<std::size_t>(bx1) + 1]; ++i) {
        if (!visit(s.walkers[i])) return false;
      }
    }
    return true;
  };
  for (const Unit& vehicle : all) {
    if (!vehicle.alive() || vehicle.state != UnitState::Moving || vehicle.engaged || !vehicle.path)
      continue;
    const units::UnitType& type = w.typeOf(vehicle);
    // A vehicle waiting its turn claims no lane yet, nor one chasing a target (its path follows
    // the target, re-planned every second). Replays before format 14: no stopped vehicle did.
    // (Asked of stopped vehicles only: most vehicles move, and a plan's wait is a bisection.)
    const auto waitsItsTurn = [&] {
      return !w.settings.pathing.standingVehicleLanes ||
             (vehicle.plan && vehicle.plan->timed &&
              (keptOut(*vehicle.plan) || waitingAt(*vehicle.plan, w.state.tick)));
    };
    if (!(type.radius > lightest) || (vehicle.velocity.length() < 0.25 && waitsItsTurn()) ||
        vehicle.order == OrderKind::Attack)
      continue;
    // The lane: the body, then the path's waypoints ahead.
    const double horizon = type.maxSpeed() * kLaneSeconds + type.size;
    const double far = horizon + type.radius + lightest + kLaneMargin + kLaneLookahead;
    if (forWalkersIn(vehicle.position.x - far, vehicle.position.x + far, vehicle.position.y - far,
                     vehicle.position.y + far, [](std::uint32_t) { return false; }))
      continue;  // nobody walking near
    const std::vector<Cell>& cells = vehicle.path->cells;
    s.coursePoints.assign(1, vehicle.position);
    double along = 0.0;
    double x0 = vehicle.position.x;
    double x1 = x0;
    double y0 = vehicle.position.y;
    double y1 = y0;
    for (std::size_t k = vehicle.next; k < cells.size() && along < horizon; ++k) {
      const Vec2 p = units::anchorToCentre(cells[k], type.size);
      along += (p - s.coursePoints.back()).length();
      s.coursePoints.push_back(p);
      x0 = std::min(x0, p.x);
      x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y);
      y1 = std::max(y1, p.y);
    }
    if (s.coursePoints.size() < 2) continue;
    const double reach = type.radius + lightest + kLaneMargin;
    // The lane point nearest `p` within `reach`, or none.
    const auto laneAt = [&](Vec2 p) -> std::optional<std::size_t> {
      std::optional<std::size_t> nearest;
      double best = reach * reach;
      for (std::size_t k = 0; k < s.coursePoints.size(); ++k) {
        const Vec2 gap = p - s.coursePoints[k];
        if (gap.dot(gap) < best) {
          best = gap.dot(gap);
          nearest = k;
        }
      }
      return nearest;
    };
    const double pad = reach + kLaneLookahead;
    forWalkersIn(x0 - pad, x1 + pad, y0 - pad, y1 + pad, [&](std::uint32_t index) {
      const Unit& walker = all[index];
      if (walker.team == vehicle.team) return true;
      const Vec2 p = walker.position;
      if (p.x < x0 - pad || p.x > x1 + pad || p.y < y0 - pad || p.y > y1 + pad) return true;
      const Vec2 v = walker.velocity;
      const double speed = v.length();
      if (speed < 1e-6) return true;
      const Vec2 heading = v * (1.0 / speed);
      if (const std::optional<std::size_t> k = laneAt(p)) {
        // In the lane ahead, walking toward the vehicle: out of it, on the side it is.
        if (*k == 0 || s.laneSide[walker.id.index] != 0.0) return true;
        const Vec2 way = s.coursePoints[*k] - s.coursePoints[*k - 1];
        const double length = way.length();
        if (length < 1e-9 || heading.dot(way) > -0.5 * length) return true;
        const Vec2 ahead = way * (1.0 / length);
        s.laneHeading[walker.id.index] = ahead;
        s.laneSide[walker.id.index] = sideToStep(w, walker, s.coursePoints[*k], ahead, type.radius);
        return true;
      }
      // Where along its way ahead the walker would step into the lane; one going the
      // vehicle's way joins its queue instead.
      for (double d = 0.25; d <= kLaneLookahead + 1e-9; d += 0.25) {
        const std::optional<std::size_t> k = laneAt(p + heading * d);
        if (!k) continue;
        const std::size_t to = std::max<std::size_t>(*k, 1);  // the lane's step at k
        const Vec2 way = s.coursePoints[to] - s.coursePoints[to - 1];
        if (heading.dot(way) <= 0.5 * way.length()) {
          double& within = s.giveWayWithin[walker.id.index];
          within = std::min(within, d);
        }
        break;
      }
      return true;
    });
  }
}

// How fast the unit may go where it is: the speed on the terrain under its centre or, under
// terrain costs, on the slowest terrain under its footprint (the speed its plan assumed, so
// that a plan's cost is its travel time; docs/terrain_costs.md). Its top speed where it
// stands on nothing it has a speed for (shoved half off its terrain).
double speedHere(const Refs& w, const Unit& unit, const units::UnitType& type) {
  const pathing::GridMap& map = w.map();
  double speed = 0.0;
  if (!w.settings.pathing.terrainCosts) {
    const Cell under{static_cast<int>(std::floor(unit.position.x)),
                     static_cast<int>(std::floor(unit.position.y))};
    speed = map.contains(under) ? type.speedOn(map.at(under)) : 0.0;
  } else {
    const Cell anchor = units::centreToAnchor(unit.position, type.size);
    speed = std::numeric_limits<double>::infinity();
    for (int dy = 0; dy < type.size; ++dy) {
      for (int dx = 0; dx < type.size; ++dx) {
        const Cell c{anchor.x + dx, anchor.y + dy};
        const double v = map.contains(c) ? type.speedOn(map.at(c)) : 0.0;
        if (v > 0.0) speed = std::min(speed, v);
      }
    }
  }
  return speed > 0.0 && std::isfinite(speed) ? speed : type.maxSpeed();
}

// [Unit: cells] How far beside itself a unit turning about looks for ground to turn on.
constexpr double kTurnRoom = 1.0;

// The way a unit turning about (more than 90°) turns when the shorter way is into ground it
// cannot stand on and the other way is not (PathServiceSettings::turnAwayFromWalls, replay
// format 26); 0: the shorter way. Turned the shorter way, a tank pushed onto a river's bank
// with its waypoint behind it steered into the water, the bank cancelled the turn, and it drove
// along the bank at full speed away from its waypoint (bridge_two_way seed 11: 13 cells, 7 s).
int turnSideAway(const Refs& w, const Unit& unit, Vec2 desired) {
  if (!w.settings.pathing.turnAwayFromWalls || unit.velocity.dot(desired) >= 0.0) return 0;
  const int shorter = units::shorterTurn(unit.velocity, desired);
  if (shorter == 0) return 0;
  const units::UnitType& type = w.typeOf(unit);
  const double speed = unit.velocity.length();
  // The side the shorter turn swings toward: the velocity rotated a quarter turn that way.
  const Vec2 toward = Vec2{-unit.velocity.y, unit.velocity.x} * (shorter * kTurnRoom / speed);
  const auto roomAt = [&](Vec2 shift) {
    return w.grid.canStand(type.agent(), units::centreToAnchor(unit.position + shift, type.size));
  };
  return !roomAt(toward) && roomAt(toward * -1.0) ? -shorter : 0;
}

}  // namespace

void steerAll(Refs& w, SteeringScratch& scratch) {
  const double dt = 1.0 / w.settings.tickRate;
  const bool cooperative = w.settings.pathing.cooperative;
  double lightest = std::numeric_limits<double>::infinity();
  for (const units::UnitType& type : w.catalogue)
    lightest = std::min(lightest, type.radius);
  if (cooperative) {
    findContacts(w, lightest, scratch);
    findVehicleLanes(w, lightest, scratch);
  }
  std::vector<Unit>& all = w.state.units;
  for (std::size_t k = 0; k < all.size(); ++k) {
    prefetchPaths(all, k);
    Unit& unit = all[k];
    if (!unit.alive()) continue;
    const units::UnitType& type = w.typeOf(unit);
    Vec2 desired;
    Vec2 toward;  // where the unit heads, for the turning-circle limit
    // [Unit: cells] How near `toward` the unit must pass: its waypoint's radius (or the
    // arrival radius at the last one); 0 for a point of a timed window's schedule.
    double tolerance = 0.0;
    if (unit.engaged) {
      // Halted to fight: the stall is on purpose, not a jam.
      unit.progress.restartWindow(unit.position, w.state.tick);
    } else if (unit.state == UnitState::Parked) {
      // Hold the goal cell: a unit shoved off it steers back.
      const Cell goal[] = {unit.goalCell};
      const units::SteeringResult r =
          units::steer(goal, 0, type.size, unit.position, type.maxSpeed(), w.settings.steering);
      desired = r.desiredVelocity;
      toward = units::anchorToCentre(unit.goalCell, type.size) - unit.position;
      tolerance = w.settings.steering.arrivalRadius;
    } else if (unit.state == UnitState::Moving && unit.path) {
      const double speed = speedHere(w, unit, type);
      // Pushed back farther than its own length, it heads for its path again from there, not for
      // the waypoint it had reached (a shorter push, as at a corner taken wide, is steered out).
      if (cooperative && w.settings.pathing.rewindPushedBack) {
        unit.next = units::rewoundWaypoint(unit.path->cells, unit.next, type.size, unit.position,
                                           w.settings.steering.waypointRadius + type.size);
      }
      const units::SteeringResult r = units::steer(unit.path->cells, unit.next, type.size,
                                                   unit.position, speed, w.settings.steering);
      // `next` also tells the stuck rule how far along its path the unit is.
      unit.next = r.next;
      if (!cooperative || (unit.plan && !unit.plan->timed)) {
        desired = r.desiredVelocity;
        toward = units::anchorToCentre(unit.path->cells[r.next], type.size) - unit.position;
        tolerance = r.next + 1 == unit.path->cells.size() ? w.settings.steering.arrivalRadius
                                                          : w.settings.steering.waypointRadius;
        // With cooperation a unit that shoved its way onto a goal cell another holds does not
        // park on top of it: it goes on pushing, and the stuck rule reports it.
        if (r.reachedEnd && (!cooperative || w.state.goals.freeFor(GoalLayer::Parked, unit.goalCell,
                                                                   type.size, unit.id)))
          arrive(w, unit, type);
      } else if (unit.plan) {
        // Keep to the window's times; a unit still waiting for a window stands.
        const units::ScheduleResult s = followSchedule(w, unit, speed);
        // Kept out of a passage, a unit waits its turn where the stream coming out pushes it
        // rather than pushing back toward its place (it plans its next window from there).
        desired = s.waiting && keptOut(*unit.plan) ? Vec2{} : s.desiredVelocity;
        toward = desired * 0.3;
        const Vec2 goal = units::anchorToCentre(unit.goalCell, type.size);
        if (s.finished && unit.plan->status == pathing::CooperativeStatus::ReachedGoal &&
            (goal - unit.position).length() <= w.settings.steering.arrivalRadius + 0.3)
          arrive(w, unit, type);
      }
    }
    if (cooperative) {
      // (The cap, never negative, limits only a unit that wants to move.)
      if (const double speed = desired.length(); speed > 0.0) {
        const double within = w.settings.pathing.turnsWithinWaypoints ? tolerance : 0.0;
        const double turnCap =
            units::turnLimitedSpeed(unit.velocity, toward, type.turnRate, within);
        if (speed > turnCap) desired = desired * (turnCap / speed);
      }
      // Mass grows with area: only a unit heavier than the lightest kind can drive another.
      const std::size_t i = unit.id.index;
      if (type.radius > lightest) {
        const std::span<const std::uint32_t> touching(scratch.touching.data() + scratch.start[i],
                                                      scratch.start[i + 1] - scratch.start[i]);
        desired = limitPushing(w, touching, unit, desired, lightest);
        if (scratch.stepAsideFor[i] != SteeringScratch::kNone)
          desired = stepAside(w, unit, w.state.units[scratch.stepAsideFor[i]], desired);
      } else if (scratch.stepAsideFor[i] != SteeringScratch::kNone) {
        desired = stepAside(w, unit, w.state.units[scratch.stepAsideFor[i]], desired);
      } else if (scratch.laneSide[i] != 0.0) {
        desired = stepAside(w, unit, scratch.laneHeading[i], scratch.laneSide[i], desired);
      } else if (const double within = scratch.giveWayWithin[i]; std::isfinite(within)) {
        // Giving way to a vehicle: stop short of its lane; a wait on purpose, not a jam.
        const double cap = std::sqrt(2.0 * type.acceleration * std::max(0.0, within - kLaneMargin));
        const double speedNow = desired.length();
        if (speedNow > cap) desired = desired * (cap / speedNow);
        unit.progress.restartWindow(unit.position, w.state.tick);
      }
    }
    const Vec2 v = units::limitVelocity(unit.velocity, desired, type.acceleration, type.turnRate,
                                        dt, cooperative ? turnSideAway(w, unit, desired) : 0);
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
