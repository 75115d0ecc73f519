// Terrain that changes during a run (docs/terrain_changes.md): wreck obstacles queued and
// cleared, and what the units do after a change — pushed off terrain they can no longer stand
// on, new paths for those whose route crosses the change.

#include <algorithm>
#include <cmath>

#include "engine/fnv1a.h"
#include "engine/src/world/phases.h"

namespace warpath::engine::world {

using namespace pathing;

namespace {

// The footprint of an agent of `size` anchored at `anchor` shares a cell with `area`.
bool footprintMeets(Cell anchor, int size, const CellRect& area) {
  return area.overlaps({anchor.x, anchor.y, size, size});
}

// What is left of the unit's path (from the waypoint it left: its place on the path, or with
// PathServiceSettings::routeFromPlaceOnPath off the waypoint before the one it steers to), or
// its window, crosses `area`.
bool routeCrosses(const Refs& w, const Unit& unit, int size, const CellRect& area) {
  if (unit.path) {
    const std::vector<Cell>& cells = unit.path->cells;
    const std::size_t from = placeOnPath(w, unit, w.settings.pathing.routeFromPlaceOnPath);
    for (std::size_t i = from; i < cells.size(); ++i) {
      if (footprintMeets(cells[i], size, area)) return true;
    }
  }
  if (unit.plan) {
    for (const TimedCell& step : unit.plan->steps) {
      if (footprintMeets(step.cell, size, area)) return true;
    }
  }
  return false;
}

// The anchor the rule pushes a unit to: in the nearest square ring around its anchor that has
// one where the footprint fits, the one whose centre is nearest the body (row-major order breaks
// ties). Nothing when no cell of the map fits it.
std::optional<Cell> pushTarget(const Refs& w, const Unit& unit) {
  const units::UnitType& type = w.typeOf(unit);
  const Agent agent = type.agent();
  const Cell anchor = units::centreToAnchor(unit.position, type.size);
  const int reach = std::max(w.map().width(), w.map().height());
  for (int r = 1; r <= reach; ++r) {
    std::optional<Cell> best;
    double bestDistance = INFINITY;
    for (int y = anchor.y - r; y <= anchor.y + r; ++y) {
      for (int x = anchor.x - r; x <= anchor.x + r; ++x) {
        if (chebyshev({x, y}, anchor) != r || !w.grid.canStand(agent, {x, y})) continue;
        const double d = (units::anchorToCentre({x, y}, type.size) - unit.position).length();
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

// A new goal cell when the old one is gone, and a new path (the rules' repath, detail 3).
void repath(Refs& w, Unit& unit, bool goalGone) {
  const units::UnitType& type = w.typeOf(unit);
  if (unit.state == UnitState::Parked) {
    w.state.goals.release(GoalLayer::Parked, unit.goalCell, type.size, unit.id);
    if (unit.order == OrderKind::Hold) {
      // Holding a spot that is gone: hold the nearest one instead.
      unit.goalCell = nearestStandable(w, unit);
      w.state.goals.take(GoalLayer::Parked, unit.goalCell, type.size, unit.id);
      return;
    }
  }
  w.log(EventKind::Repath, unit, 3);
  ++unit.repaths;
  if (unit.order == OrderKind::Attack) {
    pursue(w, unit, true);
    return;
  }
  if (goalGone) reassignGoal(w, unit);
  startPathAfresh(w, unit);
}

// A unit that found no way to its goal tries again: an attacker closes in anew, a moving unit
// takes the nearest free goal cell it can reach now. One that still reaches none stays NoPath.
void retry(Refs& w, Unit& unit) {
  if (unit.order == OrderKind::Attack) {
    pursue(w, unit, true);
    return;
  }
  if (unit.order != OrderKind::Move && unit.order != OrderKind::AttackMove) return;
  const Agent agent = w.typeOf(unit).agent();
  reassignGoal(w, unit);
  const auto& components = w.grid.layer(agent).components();
  const Cell at = nearestStandable(w, unit);
  if (!unit.goalArea.contains(unit.goalCell) || !w.grid.canStand(agent, unit.goalCell) ||
      components[w.map().indexOf(unit.goalCell)] != components[w.map().indexOf(at)])
    return;
  w.log(EventKind::Repath, unit, 4);
  ++unit.repaths;
  w.state.goals.take(GoalLayer::Claimed, unit.goalCell, w.typeOf(unit).size, unit.id);
  unit.state = UnitState::WaitingPath;
  unit.progress.reset(unit.position, w.state.tick);
  requestPath(w, unit);
}

}  // namespace

void placeWreck(Refs& w, Unit& unit) {
  const int size = w.typeOf(unit).size;
  if (!w.settings.combat.wrecksBlock || size < 2 || unit.wreckUntilTick < 0) return;
  const Cell anchor = units::centreToAnchor(unit.position, size);
  const CellRect area = w.map().clip({anchor.x, anchor.y, size, size});
  if (area.width <= 0 || area.height <= 0) return;
  unit.wreckArea = area;
  w.state.terrain.pending.push_back({TerrainEditKind::PlaceObstacle, unit.wreckArea, {}});
}

void clearWreck(Refs& w, Unit& unit) {
  if (unit.wreckArea.width <= 0) return;
  w.state.terrain.pending.push_back({TerrainEditKind::ClearObstacle, unit.wreckArea, {}});
  unit.wreckArea = {};
}

void afterTerrainChange(Refs& w, const CellRect& area, bool push, bool mayOpen) {
  for (Unit& unit : w.state.units) {
    if (!unit.alive()) continue;
    const units::UnitType& type = w.typeOf(unit);
    const Agent agent = type.agent();
    bool pushed = false;
    if (push) {
      const Cell anchor = units::centreToAnchor(unit.position, type.size);
      if (footprintMeets(anchor, type.size, area) && !w.grid.canStand(agent, anchor)) {
        const std::optional<Cell> to = pushTarget(w, unit);
        if (!to) {
          unit.hp = 0;  // nowhere on the map to stand
          kill(w, unit, {});
          continue;
        }
        unit.position = units::anchorToCentre(*to, type.size);
        unit.velocity = {};
        w.state.physics->moveBody(unit.body, unit.position);
        w.log(EventKind::Pushed, unit);
        pushed = true;
      }
    }
    if (unit.state == UnitState::NoPath && mayOpen) {
      retry(w, unit);
      continue;
    }
    if (unit.state != UnitState::Moving && unit.state != UnitState::WaitingPath &&
        unit.state != UnitState::Parked)
      continue;
    const bool goalGone =
        footprintMeets(unit.goalCell, type.size, area) && !w.grid.canStand(agent, unit.goalCell);
    if (unit.state == UnitState::Parked
            ? goalGone
            : pushed || goalGone || routeCrosses(w, unit, type.size, area))
      repath(w, unit, goalGone);
  }
}

std::uint64_t digestAfter(std::uint64_t digest, const TerrainEdit& edit) {
  Fnv1a h;
  h.add(digest);
  h.add(static_cast<std::uint64_t>(edit.kind), 1);
  h.add(static_cast<std::uint64_t>(static_cast<std::uint32_t>(edit.area.x)), 4);
  h.add(static_cast<std::uint64_t>(static_cast<std::uint32_t>(edit.area.y)), 4);
  h.add(static_cast<std::uint64_t>(static_cast<std::uint32_t>(edit.area.width)), 4);
  h.add(static_cast<std::uint64_t>(static_cast<std::uint32_t>(edit.area.height)), 4);
  h.add(static_cast<std::uint64_t>(edit.terrain), 1);
  return h.value();
}

}  // namespace warpath::engine::world
