// Orders: what a unit was told (move, attack-move, attack, hold, stop), the goal cell it was
// handed, the path it asked for and what it holds on the goal board; and a unit's death.

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/src/world/phases.h"
#include "pathing/invariant.h"
#include "pathing/lanes.h"
#include "pathing/moves.h"

namespace warpath::engine::world {

using namespace pathing;

const units::UnitType& Refs::typeOf(const Unit& unit) const {
  return catalogue[static_cast<std::size_t>(unit.type)];
}

units::Combatant Refs::combatantOf(const Unit& unit) const {
  const units::UnitType& type = typeOf(unit);
  return {unit.id.index, unit.team, type.armour, type.size, unit.position, unit.hp};
}

Unit& Refs::unit(UnitId id) {
  return const_cast<Unit&>(std::as_const(*this).unit(id));
}

const Unit& Refs::unit(UnitId id) const {
  WARPATH_INVARIANT(state.find(id) != nullptr, "a unit handle the world did not give out");
  return state.units[id.index];
}

void Refs::log(EventKind kind, const Unit& u, int detail) {
  events.push_back({state.tick, kind, u.id, detail});
}

int chebyshev(Cell a, Cell b) {
  return std::max(std::abs(a.x - b.x), std::abs(a.y - b.y));
}

namespace {

bool livingKnown(const Refs& w, UnitId id) {
  const Unit* unit = w.state.find(id);
  return unit != nullptr && unit->alive();
}

std::vector<Cell> shuffledStandable(Refs& w, Agent agent, const CellRect& area) {
  // Every cell of the area the agent can stand on, in an order drawn from the world RNG.
  std::vector<Cell> cells;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      if (w.grid.canStand(agent, {x, y})) cells.push_back({x, y});
    }
  }
  for (std::size_t i = cells.size(); i > 1; --i)
    std::swap(cells[i - 1], cells[w.state.rng.below(static_cast<std::uint32_t>(i))]);
  return cells;
}

std::uint32_t componentOf(const Refs& w, const Unit& unit) {
  const auto& components = w.grid.layer(w.typeOf(unit).agent()).components();
  return components[w.map().indexOf(nearestStandable(w, unit))];
}

void beginMove(Refs& w, Unit& unit, const CellRect& area, const std::vector<Cell>& candidates,
               std::size_t& cursor) {
  const GridMap& map = w.map();
  const units::UnitType& type = w.typeOf(unit);
  const auto& components = w.grid.layer(type.agent()).components();
  const std::uint32_t component = componentOf(w, unit);
  const auto fits = [&](Cell c, bool strict) {
    if (components[map.indexOf(c)] != component) return false;
    return !strict || (w.state.goals.freeFor(GoalLayer::Claimed, c, type.size, {}) &&
                       w.state.goals.freeFor(GoalLayer::Parked, c, type.size, {}));
  };
  // Prefer a footprint nobody else was given; when the area is full, share one.
  std::optional<Cell> goal;
  for (bool strict : {true, false}) {
    for (std::size_t k = 0; k < candidates.size() && !goal; ++k) {
      const Cell c = candidates[(cursor + k) % candidates.size()];
      if (fits(c, strict)) {
        goal = c;
        cursor = (cursor + k + 1) % candidates.size();
      }
    }
    if (goal) break;
  }
  unit.goalArea = area;
  unit.orderTick = w.state.tick;
  unit.arrivalTick = -1;
  unit.plannedTicks = -1;
  unit.waitedTicks = 0;
  unit.progress.reset(unit.position, w.state.tick);
  if (!goal) {
    unit.state = UnitState::NoPath;
    w.log(EventKind::PathFailed, unit, static_cast<int>(PathStatus::Unreachable));
    return;
  }
  unit.goalCell = *goal;
  w.state.goals.take(GoalLayer::Claimed, unit.goalCell, type.size, unit.id);
  unit.state = UnitState::WaitingPath;
  requestPath(w, unit);
}

std::optional<Cell> approachCell(const Refs& w, const Unit& unit, const Unit& target) {
  // The standable cell in the unit's own component nearest the target's centre, searched in
  // square rings around it out to the weapon's reach: the target may stand where the unit
  // cannot (infantry in a forest, an amphibious unit afloat).
  const units::UnitType& type = w.typeOf(unit);
  const GridMap& map = w.map();
  const auto& components = w.grid.layer(type.agent()).components();
  const std::uint32_t component = componentOf(w, unit);
  const Cell centre = units::centreToAnchor(target.position, type.size);
  const int reach =
      static_cast<int>(std::ceil(type.weapon ? type.weapon->range : 0.0)) + w.typeOf(target).size;
  for (int r = 0; r <= reach; ++r) {
    std::optional<Cell> best;
    double bestDistance = INFINITY;
    for (int y = centre.y - r; y <= centre.y + r; ++y) {
      for (int x = centre.x - r; x <= centre.x + r; ++x) {
        if (std::max(std::abs(x - centre.x), std::abs(y - centre.y)) != r) continue;
        if (!w.grid.canStand(type.agent(), {x, y})) continue;
        if (components[map.indexOf({x, y})] != component) continue;
        const double d = (units::anchorToCentre({x, y}, type.size) - target.position).length();
        if (d < bestDistance) {
          bestDistance = d;
          best = Cell{x, y};
        }
      }
    }
    if (best) return best;
  }
  return std::nullopt;
}

}  // namespace

Cell nearestStandable(const Refs& w, const Unit& unit) {
  const units::UnitType& type = w.typeOf(unit);
  const Cell anchor = units::centreToAnchor(unit.position, type.size);
  if (w.grid.canStand(type.agent(), anchor)) return anchor;
  // Pushed against an edge, the rounded anchor may straddle it: take the nearest cell where
  // the footprint fits (row-major order breaks ties).
  constexpr int kReach = 2;
  Cell best = anchor;
  double bestDistance = INFINITY;
  for (int y = anchor.y - kReach; y <= anchor.y + kReach; ++y) {
    for (int x = anchor.x - kReach; x <= anchor.x + kReach; ++x) {
      if (!w.grid.canStand(type.agent(), {x, y})) continue;
      const double d = (units::anchorToCentre({x, y}, type.size) - unit.position).length();
      if (d < bestDistance) {
        bestDistance = d;
        best = {x, y};
      }
    }
  }
  return best;
}

std::size_t placeOnPath(const Refs& w, const Unit& unit, bool rewind) {
  std::size_t next = unit.next;
  if (rewind && w.settings.pathing.cooperative && w.settings.pathing.rewindPushedBack) {
    next = units::rewoundWaypoint(unit.path->cells, next, w.typeOf(unit).size, unit.position,
                                  w.settings.steering.waypointRadius);
  }
  return next > 0 ? next - 1 : 0;
}

void leaveOrder(Refs& w, Unit& unit) {
  const int size = w.typeOf(unit).size;
  if (unit.state == UnitState::Parked)
    w.state.goals.release(GoalLayer::Parked, unit.goalCell, size, unit.id);
  w.state.goals.release(GoalLayer::Claimed, unit.goalCell, size, unit.id);
  unit.path.reset();
  unit.next = 0;
  if (unit.plan) releaseReservations(w, unit);  // it holds where it stands until it moves
  if (unit.order == OrderKind::Hold && w.settings.pathing.cooperative)
    w.state.physics->setBraced(unit.body, false);
  unit.waitSince = -1;
  unit.attackTargets.clear();
  unit.engaged = false;
  ++unit.pathSerial;  // answers to requests of the old order are stale
}

void applyCommand(Refs& w, const Command& command) {
  std::vector<Cell> candidates;
  int candidatesType = -1;
  std::size_t cursor = 0;
  for (UnitId id : command.units) {
    if (!livingKnown(w, id)) continue;
    Unit& unit = w.unit(id);
    leaveOrder(w, unit);
    unit.order = command.kind;
    w.log(EventKind::Ordered, unit, static_cast<int>(command.kind));
    switch (command.kind) {
      case OrderKind::Move:
      case OrderKind::AttackMove:
        if (unit.type != candidatesType) {
          candidates = shuffledStandable(w, w.typeOf(unit).agent(), command.area);
          candidatesType = unit.type;
          cursor = 0;
        }
        beginMove(w, unit, command.area, candidates, cursor);
        break;
      case OrderKind::Attack:
        for (UnitId t : command.targets) {
          if (livingKnown(w, t) && w.unit(t).team != unit.team) unit.attackTargets.push_back(t);
        }
        unit.target = {};
        unit.state = UnitState::Idle;
        pursue(w, unit, true);
        break;
      case OrderKind::Hold:
        // Holding a spot is parking where the unit stands: steering brings it back when shoved.
        unit.goalCell = nearestStandable(w, unit);
        unit.state = UnitState::Parked;
        w.state.goals.take(GoalLayer::Parked, unit.goalCell, w.typeOf(unit).size, unit.id);
        if (w.settings.pathing.cooperative) w.state.physics->setBraced(unit.body, true);
        break;
      case OrderKind::Stop:
        unit.state = UnitState::Idle;
        break;
    }
  }
}

void pursue(Refs& w, Unit& unit, bool force) {
  // The living attack target nearest the unit (gap, then the order listed).
  const units::Combatant self = w.combatantOf(unit);
  const Unit* chase = nullptr;
  double chaseGap = INFINITY;
  std::erase_if(unit.attackTargets, [&](UnitId t) { return !w.unit(t).alive(); });
  for (UnitId t : unit.attackTargets) {
    const double gap = units::gapSquared(self, w.combatantOf(w.unit(t)));
    if (gap < chaseGap) {
      chaseGap = gap;
      chase = &w.unit(t);
    }
  }
  if (chase == nullptr) {
    // Every target is dead: the order is done.
    leaveOrder(w, unit);
    unit.order = OrderKind::Stop;
    unit.state = UnitState::Idle;
    return;
  }
  const std::optional<Cell> cell = approachCell(w, unit, *chase);
  if (!cell) {
    unit.state = UnitState::NoPath;
    return;
  }
  if (!force && unit.state != UnitState::NoPath && chebyshev(*cell, unit.goalCell) <= 2) return;
  unit.goalCell = *cell;
  unit.progress.reset(unit.position, w.state.tick);
  unit.state = UnitState::WaitingPath;
  requestPath(w, unit);
}

namespace {

// The unit's next request for a path from `start` to its goal cell.
PathRequest nextRequest(const Refs& w, Unit& unit, Cell start) {
  ++unit.pathSerial;
  return {unit.id,
          unit.pathSerial,
          w.typeOf(unit).agent(),
          start,
          unit.goalCell,
          w.settings.pathing.terrainCosts ? unit.type : -1,
          w.typeOf(unit).maxSpeed()};
}

}  // namespace

void requestPath(Refs& w, Unit& unit) {
  w.state.paths->request(nextRequest(w, unit, nearestStandable(w, unit)));
}

void startPathAfresh(Refs& w, Unit& unit) {
  if (unit.plan) releaseReservations(w, unit);
  unit.path.reset();
  unit.next = 0;
  unit.state = UnitState::WaitingPath;
  unit.progress.reset(unit.position, w.state.tick);
  requestPath(w, unit);
}

namespace {

// The same type and team sent to the same area: teammates of one order's kind.
bool sentAlike(const Unit& a, const Unit& b) {
  return a.type == b.type && a.team == b.team && a.goalArea == b.goalArea;
}

}  // namespace

bool requestDetour(Refs& w, Unit& unit, bool beforeNewGoal) {
  const int size = w.typeOf(unit).size;
  const std::vector<Cell>& path = unit.path->cells;
  // The stretch looked at: four footprints and four cells ahead, as the footprint sweeps it.
  const std::size_t from = std::min(unit.next, path.size() - 1);
  const std::size_t to = std::min(path.size(), from + static_cast<std::size_t>(4 * size + 4));
  const auto footprint = [&](std::size_t i) { return CellRect{path[i].x, path[i].y, size, size}; };
  CellRect swept = footprint(from);
  for (std::size_t i = from + 1; i < to; ++i)
    swept = swept.joinedWith(footprint(i));
  // The footprint of another unit standing for good: parked, holding, waiting for orders. Units
  // on their way are traffic, for the windows and steering: going round crawling ones too made
  // crowds worse (docs/cooperative.md, "Detours").
  const auto standing = [&](const Unit& other) -> std::optional<CellRect> {
    if (!other.alive() || other.id == unit.id || other.state == UnitState::Moving) return {};
    const int otherSize = w.typeOf(other).size;
    const Cell at = units::centreToAnchor(other.position, otherSize);
    return CellRect{at.x, at.y, otherSize, otherSize};
  };
  auto detour = std::make_shared<Detour>();
  std::size_t last = from;    // the last cell of the stretch that meets one of them
  bool onlyTeammates = true;  // of the same kind, sent to the same area
  for (const Unit& other : w.state.units) {
    const std::optional<CellRect> standsAt = standing(other);
    if (!standsAt || !swept.overlaps(*standsAt)) continue;
    const CellRect& body = *standsAt;
    bool inTheWay = false;
    for (std::size_t i = from; i < to; ++i) {
      if (!footprint(i).overlaps(body)) continue;
      inTheWay = true;
      last = std::max(last, i);
    }
    if (!inTheWay) continue;
    detour->avoid.push_back(body);
    onlyTeammates = onlyTeammates && sentAlike(other, unit);
  }
  if (beforeNewGoal && onlyTeammates) return false;
  // Standing at the end of the path, on the goal, a way around them leads nowhere (a goal cell
  // taken is the goal rule's to change); with detoursToGoal a way to a goal they stand just
  // before is sought, unless only teammates of its kind stand there, as in a goal area filling
  // up, where a new goal cell serves (before it, standing that near the end refused a detour).
  if (detour->avoid.empty()) return false;
  if (last + static_cast<std::size_t>(size + 2) >= path.size() - 1) {
    if (!w.settings.pathing.detoursToGoal || onlyTeammates) return false;
    const CellRect goal = footprint(path.size() - 1);
    for (const CellRect& body : detour->avoid)
      if (body.overlaps(goal)) return false;
  }
  // Back onto the path a footprint and two cells past the last of them, through a block around
  // them all with room to go round.
  detour->rest = unit.path;
  detour->rejoin = static_cast<std::uint32_t>(
      std::min(path.size() - 1, last + static_cast<std::size_t>(size + 2)));
  const Cell start = nearestStandable(w, unit);
  CellRect around = CellRect{start.x, start.y, size, size}.joinedWith(footprint(detour->rejoin));
  for (const CellRect& body : detour->avoid)
    around = around.joinedWith(body);
  const int margin = 2 * size + 4;
  around = {around.x - margin, around.y - margin, around.width + 2 * margin,
            around.height + 2 * margin};
  detour->region = w.map().clip(around);
  if (w.settings.pathing.detoursToGoal) {
    // The way around keeps clear of every unit standing in the region, not only of those on
    // the stretch: it went round one parked jeep through the next one beside it.
    detour->avoid.clear();
    for (const Unit& other : w.state.units) {
      const std::optional<CellRect> standsAt = standing(other);
      if (standsAt && detour->region.overlaps(*standsAt)) detour->avoid.push_back(*standsAt);
    }
  }
  PathRequest request = nextRequest(w, unit, start);
  request.detour = std::move(detour);
  w.state.paths->request(request);
  return true;
}

namespace {

// A unit parked on its goal cell, as an order to the area left it there (not holding a spot).
bool parkedByMove(const Unit& unit) {
  return unit.alive() && unit.state == UnitState::Parked &&
         (unit.order == OrderKind::Move || unit.order == OrderKind::AttackMove);
}

}  // namespace

bool takeGoalOfParkedTeammate(Refs& w, Unit& unit, Unit& parked) {
  // Of the same order's kind: the same type and team sent to the same area, so the one's goal
  // cell fits the other and counts the same for the report; and the goals apart, so that the
  // parked one has somewhere else to go.
  if (!parkedByMove(parked) || parked.id == unit.id || !sentAlike(parked, unit) ||
      (unit.order != OrderKind::Move && unit.order != OrderKind::AttackMove))
    return false;
  const int size = w.typeOf(unit).size;
  const Cell deeper = unit.goalCell;
  const Cell vacated = parked.goalCell;
  if (CellRect{deeper.x, deeper.y, size, size}.overlaps({vacated.x, vacated.y, size, size}) ||
      componentOf(w, parked) != componentOf(w, unit))
    return false;
  w.state.goals.release(GoalLayer::Parked, vacated, size, parked.id);
  w.state.goals.release(GoalLayer::Claimed, vacated, size, parked.id);
  w.state.goals.release(GoalLayer::Claimed, deeper, size, unit.id);
  parked.goalCell = deeper;
  w.state.goals.take(GoalLayer::Claimed, deeper, size, parked.id);
  unit.goalCell = vacated;
  w.state.goals.take(GoalLayer::Claimed, vacated, size, unit.id);
  // The parked one moves on (it keeps its arrival: it reached the area); the other plans for
  // the cell it vacates.
  w.log(EventKind::Repath, parked, 5);
  ++parked.repaths;
  startPathAfresh(w, parked);
  w.log(EventKind::Repath, unit, 2);
  requestPath(w, unit);
  return true;
}

std::uint64_t deliverPaths(Refs& w, std::vector<PathDelivery>& scratch) {
  scratch.clear();
  const std::uint64_t spent =
      w.state.paths->serve(scratch, static_cast<double>(w.state.tick) / w.settings.tickRate);
  for (const PathDelivery& delivery : scratch) {
    if (!(delivery.unit.index < w.state.units.size())) continue;
    Unit& unit = w.unit(delivery.unit);
    if (delivery.serial != unit.pathSerial || !unit.alive()) continue;  // superseded, or dead
    if (delivery.status == PathStatus::Found) {
      // A new path: the old window goes (the unit holds where it stands until it gets one).
      if (unit.plan) releaseReservations(w, unit);
      unit.path = delivery.path;
      // Cooperating vehicles keep to the right half of passages wide enough for two (lanes).
      // Infantry (size 1) slip past each other: lanes only bent their paths, and at the bundled
      // bridge and crossroads they did no better with them (docs/cooperative.md).
      if (w.settings.pathing.cooperative && w.typeOf(unit).size >= 2) {
        std::vector<Cell> lane = pathing::keepRight(
            w.grid, w.typeOf(unit).agent(), unit.path->cells, w.settings.pathing.laneRules());
        if (lane != unit.path->cells)
          unit.path = std::make_shared<const PlannedPath>(planned(std::move(lane)));
      }
      // The planned time is the path the unit follows, its lane included: a unit alone keeps
      // right too, and the delay measures what the traffic costs it.
      if (unit.plannedTicks < 0) {
        const bool withLane = w.settings.pathing.plannedTimeWithLanes;
        unit.plannedTicks =
            freeFlowTicks(w, unit, delivery, withLane ? *unit.path : *delivery.path);
      }
      unit.next = 0;
      unit.state = UnitState::Moving;
      unit.progress.restartWindow(unit.position, w.state.tick);
      w.log(EventKind::PathFound, unit);
    } else {
      unit.path.reset();
      unit.state = UnitState::NoPath;
      w.log(EventKind::PathFailed, unit, static_cast<int>(delivery.status));
    }
  }
  return spent;
}

namespace {

// [Unit: s] Each move of `path` at the unit's top speed on the terrain under the body's centre
// at its end, as steering drives it.
double walkedSeconds(const Refs& w, const Unit& unit, const std::vector<Cell>& path) {
  const units::UnitType& type = w.typeOf(unit);
  const int half = type.size / 2;
  double seconds = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Cell& c = path[i];
    double speed = type.speedOn(w.map().at({c.x + half, c.y + half}));
    if (!(speed > 0.0)) speed = type.maxSpeed();
    const bool diagonal = c.x != path[i - 1].x && c.y != path[i - 1].y;
    seconds += (diagonal ? kSqrt2 : 1.0) / speed;
  }
  return seconds;
}

}  // namespace

std::int64_t freeFlowTicks(const Refs& w, const Unit& unit, const PathDelivery& delivery,
                           const PlannedPath& followed) {
  double seconds = delivery.seconds;
  if (seconds < 0.0) {
    seconds = walkedSeconds(w, unit, followed.cells);
  } else if (&followed != delivery.path.get()) {
    // Under terrain costs the plan's cost is its travel time; a lane's detour adds its share.
    const double planned = walkedSeconds(w, unit, delivery.path->cells);
    if (planned > 0.0) seconds *= walkedSeconds(w, unit, followed.cells) / planned;
  }
  return std::llround(seconds * w.settings.tickRate);
}

namespace {

// What reassignGoal reads of the goal board: the footprints at the area's cells.
std::uint64_t goalBoardAround(const Refs& w, const Unit& unit) {
  const int reach = w.typeOf(unit).size - 1;
  const CellRect& a = unit.goalArea;
  return w.state.goals.digestAround({a.x, a.y, a.width + reach, a.height + reach});
}

}  // namespace

bool FullGoalAreas::stillFull(const Refs& w, const Unit& unit, std::uint32_t component) const {
  if (unit.id.index >= seen_.size()) return false;
  const Seen& s = seen_[unit.id.index];
  return s.full && s.board == goalBoardAround(w, unit) &&
         s.terrainChanges == w.state.terrain.applied && s.component == component &&
         s.area == unit.goalArea;
}

void FullGoalAreas::remember(const Refs& w, const Unit& unit, std::uint32_t component) {
  if (seen_.size() <= unit.id.index) seen_.resize(static_cast<std::size_t>(unit.id.index) + 1);
  seen_[unit.id.index] = {goalBoardAround(w, unit), w.state.terrain.applied, component,
                          unit.goalArea, true};
}

bool reassignGoal(Refs& w, Unit& unit, FullGoalAreas* full) {
  const units::UnitType& type = w.typeOf(unit);
  const Agent agent = type.agent();
  const GridMap& map = w.map();
  const auto& components = w.grid.layer(agent).components();
  const pathing::ClearanceField& clearance = w.grid.clearance(agent.capability);
  const std::uint32_t component = componentOf(w, unit);
  if (full != nullptr && full->stillFull(w, unit, component)) return false;
  std::optional<Cell> best;
  double bestDistance = INFINITY;
  const CellRect& area = unit.goalArea;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      if (clearance.at(c) < type.size || components[map.indexOf(c)] != component) continue;
      // The nearest free cell, the first of equals: the distance is the cheaper test.
      const double d = (units::anchorToCentre(c, type.size) - unit.position).length();
      if (d < bestDistance && w.state.goals.freeFor(GoalLayer::Parked, c, type.size, unit.id) &&
          w.state.goals.freeFor(GoalLayer::Claimed, c, type.size, unit.id)) {
        bestDistance = d;
        best = c;
      }
    }
  }
  if (!best && full != nullptr) full->remember(w, unit, component);
  if (!best || *best == unit.goalCell) return false;
  moveGoalCell(w, unit, *best);
  return true;
}

void moveGoalCell(Refs& w, Unit& unit, Cell cell) {
  const int size = w.typeOf(unit).size;
  w.state.goals.release(GoalLayer::Claimed, unit.goalCell, size, unit.id);
  unit.goalCell = cell;
  w.state.goals.take(GoalLayer::Claimed, unit.goalCell, size, unit.id);
}

void kill(Refs& w, Unit& unit, UnitId killer) {
  leaveOrder(w, unit);
  unit.state = UnitState::Dead;
  unit.order = OrderKind::Stop;
  unit.target = {};
  unit.deathTick = w.state.tick;
  unit.killedBy = killer;
  unit.velocity = {};
  w.state.paths->cancel(unit.id);
  const double wreck = w.settings.combat.wreckSeconds;
  if (wreck > 0.0) {
    w.state.physics->freeze(unit.body);
    unit.wreckUntilTick =
        w.state.tick + std::max<std::int64_t>(1, std::llround(wreck * w.settings.tickRate));
    placeWreck(w, unit);
  } else {
    w.state.physics->removeBody(unit.body);
  }
  w.log(EventKind::Killed, unit, static_cast<int>(killer.index));
}

}  // namespace warpath::engine::world
