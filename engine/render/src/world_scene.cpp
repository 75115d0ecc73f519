#include "render/world_scene.h"

#include <algorithm>
#include <cmath>

namespace warpath::render {

FrameScene sceneOf(const engine::World& world, int teamCount) {
  FrameScene scene;
  scene.tick = world.tick();
  scene.seconds = world.seconds();
  scene.terrain = &world.grid().map();
  scene.terrainRevision = world.grid().revision();
  int teams = std::max(teamCount, 0);
  for (const engine::Unit& u : world.units())
    teams = std::max(teams, u.team + 1);
  scene.teams.resize(static_cast<std::size_t>(teams));

  const auto& catalogue = world.catalogue();
  scene.units.reserve(world.units().size());
  for (const engine::Unit& u : world.units()) {
    const units::UnitType& type = catalogue[static_cast<std::size_t>(u.type)];
    TeamCounts& counts = scene.teams[static_cast<std::size_t>(u.team)];
    if (!u.alive()) {
      ++counts.dead;
      // A wreck is drawn while it stands; once cleared the unit is gone from the picture.
      if (u.wreckUntilTick <= world.tick()) continue;
    }
    UnitView view;
    view.centre = {static_cast<float>(u.position.x), static_cast<float>(u.position.y)};
    view.size = type.size;
    view.team = u.team;
    view.type = u.type;
    view.hp = static_cast<float>(u.hp) / static_cast<float>(std::max(type.hp, 1));
    view.state = !u.alive()           ? UnitState::Wreck
                 : u.arrivalTick >= 0 ? UnitState::Arrived
                                      : UnitState::Alive;
    view.stuck = u.progress.stuckWindows() > 0;
    // Path cells are anchors; the drawing wants centres (anchor + size/2).
    const float half = static_cast<float>(type.size) / 2.0f;
    if (u.path) {
      for (std::size_t i = u.next; i < u.path->cells.size(); ++i) {
        const pathing::Cell c = u.path->cells[i];
        view.path.push_back({static_cast<float>(c.x) + half, static_cast<float>(c.y) + half});
      }
    }
    if (u.plan) {
      // What is left of the window: from the step under way to the last.
      const std::vector<pathing::TimedCell>& steps = u.plan->steps;
      for (std::size_t i = 0; i < steps.size(); ++i) {
        if (i + 1 < steps.size() && steps[i + 1].tick <= world.tick()) continue;
        const pathing::Cell c = steps[i].cell;
        view.window.push_back({static_cast<float>(c.x) + half, static_cast<float>(c.y) + half});
        view.windowSeconds.push_back(static_cast<float>(
            static_cast<double>(std::max<std::int64_t>(0, steps[i].tick - world.tick())) /
            world.tickRate()));
      }
    }
    double dx = u.velocity.x, dy = u.velocity.y;
    if (dx * dx + dy * dy < 1e-6 && !view.path.empty()) {
      dx = view.path.front().x - view.centre.x;
      dy = view.path.front().y - view.centre.y;
    }
    if (dx != 0.0 || dy != 0.0) view.facing = static_cast<float>(std::atan2(dy, dx));

    if (view.state != UnitState::Wreck) {
      ++counts.alive;
      if (view.state == UnitState::Arrived) ++counts.arrived;
    }
    if (view.state != UnitState::Wreck && u.orderTick >= 0 && u.goalArea.width > 0 &&
        u.goalArea.height > 0) {
      const bool known = std::any_of(
          scene.arrivalZones.begin(), scene.arrivalZones.end(), [&](const ArrivalZone& z) {
            return z.team == u.team && z.area.x == u.goalArea.x && z.area.y == u.goalArea.y &&
                   z.area.width == u.goalArea.width && z.area.height == u.goalArea.height;
          });
      if (!known) scene.arrivalZones.push_back({u.goalArea, u.team});
    }
    scene.units.push_back(std::move(view));
  }

  const auto teamOf = [&](engine::UnitId shooter) {
    const engine::Unit* u = world.find(shooter);
    return u != nullptr ? u->team : 0;
  };
  const auto point = [](units::Vec2 v) {
    return Point{static_cast<float>(v.x), static_cast<float>(v.y)};
  };
  // Instant shots of the last step: the whole line.
  for (const engine::Shot& shot : world.shotsLastTick()) {
    if (shot.landTick != shot.firedTick) continue;
    scene.shots.push_back({point(shot.from), point(shot.to), teamOf(shot.shooter), false});
  }
  // Shells in flight: a streak of at most a cell ending where the shell is now.
  for (const engine::Shot& shot : world.shotsInFlight()) {
    if (shot.landTick <= shot.firedTick) continue;
    const double t = std::clamp(static_cast<double>(world.tick() - shot.firedTick) /
                                    static_cast<double>(shot.landTick - shot.firedTick),
                                0.0, 1.0);
    const units::Vec2 d = shot.to - shot.from;
    const double length = d.length();
    if (length <= 0.0) continue;
    const units::Vec2 head = shot.from + d * t;
    const units::Vec2 tail = head - d * (std::min(1.0, length * t) / length);
    scene.shots.push_back({point(tail), point(head), teamOf(shot.shooter), true});
  }
  return scene;
}

}  // namespace warpath::render
