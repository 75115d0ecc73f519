// Rules after the physics step: wrecks cleared, arrivals, attack pursuit, goal cells taken by
// others, units pushed off their path, and the stuck rule.

#include "engine/src/world/phases.h"

namespace warpath::engine::world {

using pathing::Cell;

namespace {

// [Unit: cells] From the unit's body to waypoint `next` of its path.
units::Vec2 toNextWaypoint(const Unit& unit, int size) {
  return units::anchorToCentre(unit.path->cells[unit.next], size) - unit.position;
}

// [Unit: cells] What is left of the unit's path: from its body to waypoint `next`, then along
// the path.
double remainingAlong(const Unit& unit, int size) {
  return toNextWaypoint(unit, size).length() + unit.path->remaining[unit.next];
}

// The unit stands right behind another going its way whose last progress window made progress
// (or was a wait its plan held it to): it is in a queue, not in a jam. A jam at the queue's head
// still counts there, and from the next window on behind it too. Asked only when a window closes
// without progress, so a scan of every unit costs little.
bool queuedBehindMover(const Refs& w, const Unit& unit, int size) {
  const units::Vec2 toNext = toNextWaypoint(unit, size);
  const double toNextLength = toNext.length();
  if (toNextLength <= 0.0) return false;
  // Within 60 degrees of the way the unit wants to go.
  const auto alongWay = [&](units::Vec2 v) {
    return toNext.dot(v) >= 0.5 * toNextLength * v.length();
  };
  for (const Unit& other : w.state.units) {
    if (other.id == unit.id || !other.alive() || other.state != UnitState::Moving || !other.path ||
        other.progress.stuckWindows() > 0)
      continue;
    const int otherSize = w.typeOf(other).size;
    const units::Vec2 gap = other.position - unit.position;
    // Footprints (size by size) touching, or within half a cell of it.
    if (gap.length() > 0.5 * (size + otherSize) + 0.5 || !alongWay(gap)) continue;
    const units::Vec2 otherToNext = toNextWaypoint(other, otherSize);
    if (otherToNext.length() > 0.0 && alongWay(otherToNext)) return true;
  }
  return false;
}

// A moving unit's checks, in order; at most one repath a tick.
void checkProgress(Refs& w, Unit& unit, Cell anchor, FullGoalAreas& fullGoalAreas) {
  const units::UnitType& type = w.typeOf(unit);
  const std::vector<Cell>& path = unit.path->cells;
  const bool movingToArea = unit.order != OrderKind::Attack;
  // The goal cell was taken by a unit that parked there first: pick the nearest free one.
  const bool nearEnd = unit.next + static_cast<std::size_t>(type.size) + 2 >= path.size();
  if (movingToArea && nearEnd &&
      !w.state.goals.freeFor(GoalLayer::Parked, unit.goalCell, type.size, unit.id)) {
    if (reassignGoal(w, unit, &fullGoalAreas)) {
      w.log(EventKind::Repath, unit, 2);
      requestPath(w, unit);
      return;
    }
    // None is free for it. With cooperation it would not park on the other's cell (steering)
    // and would push into the parked crowd for good; inside its area it parks where it stands.
    if (w.settings.pathing.cooperative && w.settings.pathing.parkWhenAreaFull &&
        unit.goalArea.contains(anchor)) {
      moveGoalCell(w, unit, nearestStandable(w, unit));
      arrive(w, unit, type);
      return;
    }
  }
  // A unit keeping to a timed window re-plans the window instead (traffic.cpp), and asks for a
  // new path when it leaves its corridor; otherwise it follows its path like any unit.
  const bool cooperative = w.settings.pathing.cooperative && unit.plan && unit.plan->timed;
  // Pushed off its path: the next waypoint is more than a step away, and steering straight
  // at it could cut a corner the path went around. (A cooperative unit re-plans its window
  // instead, and asks for a new path when it leaves its corridor.)
  if (!cooperative && chebyshev(anchor, path[unit.next]) > 2) {
    w.log(EventKind::Repath, unit, 1);
    requestPath(w, unit);
    unit.state = UnitState::WaitingPath;
    return;
  }
  const WorldSettings& settings = w.settings;
  bool stuck = false;
  if (!settings.pathing.cooperative) {
    stuck = unit.progress.update(unit.position, w.state.tick, settings.tickRate, settings.stuck);
  } else if (w.settings.pathing.cooperative &&
             (!unit.plan || keptOut(*unit.plan) ||
              (cooperative && waitingAt(*unit.plan, w.state.tick) && onSchedule(w, unit)))) {
    // A wait its window holds it to, waiting for a window or for its turn at a passage is not
    // a jam; moving, it must make progress like anyone else.
    unit.progress.restartWindow(unit.position, w.state.tick);
  } else {
    stuck = unit.progress.updateAlong(unit.position, remainingAlong(unit, type.size), w.state.tick,
                                      settings.tickRate, settings.stuck);
    // Queued: not flagged for it, but it still looks for a way round below (measured: holding
    // queued units to their paths instead left more of `demo`'s infantry late).
    if (stuck && settings.pathing.queuesExcused && queuedBehindMover(w, unit, type.size))
      unit.progress.excuseWindow();
  }
  if (stuck) {
    ++unit.repaths;
    if (unit.progress.stuckWindows() == settings.stuck.flagAfter) {
      unit.everStuck = true;
      w.log(EventKind::StuckFlagged, unit);
    }
    w.log(EventKind::Repath, unit, 0);
    // Units standing for good on the path ahead would jam it again: a way around them
    // (detours). With detoursToGoal it is asked for first, unless only teammates of its kind
    // stand there, and may lead to the goal itself when they stand just before it. Else, near
    // the goal, a crowd is the likely cause: a free goal cell resolves it. Else the traffic
    // jammed it: a unit keeping to a window plans a new one against today's reservations (at
    // the same place at a passage's gate); one following its path asks for it again, which
    // plans its window anew too.
    const bool detours = settings.pathing.cooperative && settings.pathing.jamDetours;
    if (detours && settings.pathing.detoursToGoal && requestDetour(w, unit, true)) return;
    const bool newGoal = movingToArea && nearEnd && reassignGoal(w, unit, &fullGoalAreas);
    if (cooperative) {
      if (!detours || newGoal || !requestDetour(w, unit)) expireWindow(w, unit);
    } else if (!detours || newGoal || !requestDetour(w, unit)) {
      requestPath(w, unit);
    }
  }
}

}  // namespace

void applyRules(Refs& w, FullGoalAreas& fullGoalAreas) {
  const std::int64_t tick = w.state.tick;
  std::vector<Unit>& all = w.state.units;
  for (std::size_t i = 0; i < all.size(); ++i) {
    prefetchPaths(all, i);
    Unit& unit = all[i];
    if (!unit.alive()) {
      if (unit.wreckUntilTick >= 0 && tick >= unit.wreckUntilTick) {
        w.state.physics->removeBody(unit.body);
        unit.wreckUntilTick = -1;
        clearWreck(w, unit);
        w.log(EventKind::WreckCleared, unit);
      }
      continue;
    }
    const Cell anchor = units::centreToAnchor(unit.position, w.typeOf(unit).size);
    if (unit.orderTick >= 0 && unit.arrivalTick < 0 && unit.goalArea.contains(anchor)) {
      unit.arrivalTick = tick;
      w.log(EventKind::Arrived, unit);
    }
    if (unit.order == OrderKind::Attack) {
      // Follow the target as it moves, about once a second (staggered by id).
      const auto second = static_cast<std::int64_t>(std::max(1.0, std::round(w.settings.tickRate)));
      if (!unit.engaged && (tick + unit.id.index) % second == 0) pursue(w, unit, false);
      if (unit.order != OrderKind::Attack) continue;
    }
    if (unit.state != UnitState::Moving || unit.engaged) continue;
    checkProgress(w, unit, anchor, fullGoalAreas);
  }
}

}  // namespace warpath::engine::world
