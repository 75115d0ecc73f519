#include "render/world_scene.h"

#include <algorithm>
#include <cmath>

namespace warpath::render {

FrameScene sceneOf(const engine::World& world, int teamCount) {
  FrameScene scene;
  scene.tick = world.tick();
  scene.seconds = world.seconds();
  int teams = std::max(teamCount, 0);
  for (const engine::Unit& u : world.units())
    teams = std::max(teams, u.team + 1);
  scene.teams.resize(static_cast<std::size_t>(teams));

  const auto& catalogue = world.catalogue();
  scene.units.reserve(world.units().size());
  for (const engine::Unit& u : world.units()) {
    const units::UnitType& type = catalogue[static_cast<std::size_t>(u.type)];
    UnitView view;
    view.centre = {static_cast<float>(u.position.x), static_cast<float>(u.position.y)};
    view.size = type.size;
    view.team = u.team;
    view.type = u.type;
    view.hp = static_cast<float>(u.hp) / static_cast<float>(std::max(type.hp, 1));
    view.state = u.hp <= 0            ? UnitState::Wreck
                 : u.arrivalTick >= 0 ? UnitState::Arrived
                                      : UnitState::Alive;
    view.stuck = u.progress.stuckWindows() > 0;
    // Path cells are anchors; the drawing wants centres (anchor + size/2).
    const float half = static_cast<float>(type.size) / 2.0f;
    if (u.path) {
      for (std::size_t i = u.next; i < u.path->size(); ++i) {
        const pathing::Cell c = (*u.path)[i];
        view.path.push_back({static_cast<float>(c.x) + half, static_cast<float>(c.y) + half});
      }
    }
    double dx = u.velocity.x, dy = u.velocity.y;
    if (dx * dx + dy * dy < 1e-6 && !view.path.empty()) {
      dx = view.path.front().x - view.centre.x;
      dy = view.path.front().y - view.centre.y;
    }
    if (dx != 0.0 || dy != 0.0) view.facing = static_cast<float>(std::atan2(dy, dx));

    TeamCounts& counts = scene.teams[static_cast<std::size_t>(u.team)];
    if (view.state == UnitState::Wreck) {
      ++counts.dead;
    } else {
      ++counts.alive;
      if (view.state == UnitState::Arrived) ++counts.arrived;
    }
    if (u.orderTick >= 0 && u.goalArea.width > 0 && u.goalArea.height > 0) {
      const bool known = std::any_of(
          scene.arrivalZones.begin(), scene.arrivalZones.end(), [&](const ArrivalZone& z) {
            return z.team == u.team && z.area.x == u.goalArea.x && z.area.y == u.goalArea.y &&
                   z.area.width == u.goalArea.width && z.area.height == u.goalArea.height;
          });
      if (!known) scene.arrivalZones.push_back({u.goalArea, u.team});
    }
    scene.units.push_back(std::move(view));
  }
  return scene;
}

}  // namespace warpath::render
