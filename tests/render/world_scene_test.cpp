// The World -> FrameScene adapter on a small world.

#include "render/world_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "engine/world.h"
#include "render/palette.h"
#include "render/renderer.h"

namespace warpath::render {
namespace {

using pathing::Terrain;

TEST(WorldScene, ShowsUnitsTheirOrdersAndCounts) {
  units::UnitType tank;
  tank.name = "tank";
  tank.size = 2;
  tank.capability = pathing::Capability::of({Terrain::Ground});
  tank.setSpeed(3.0);
  tank.radius = 0.9;
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(24, 24));
  engine::World world(grid, {tank}, engine::WorldSettings{});
  const engine::UnitId id = world.spawn(0, 1, 0, {3, 3});

  FrameScene scene = sceneOf(world, 3);
  ASSERT_EQ(scene.units.size(), 1u);
  EXPECT_EQ(scene.units[0].size, 2);
  EXPECT_EQ(scene.units[0].team, 1);
  EXPECT_FLOAT_EQ(scene.units[0].centre.x, 4.0f);  // anchor 3,3 + size/2
  EXPECT_FLOAT_EQ(scene.units[0].centre.y, 4.0f);
  EXPECT_FLOAT_EQ(scene.units[0].hp, 1.0f);
  EXPECT_EQ(scene.units[0].state, UnitState::Alive);
  ASSERT_EQ(scene.teams.size(), 3u);  // as asked, though only team 1 has units
  EXPECT_EQ(scene.teams[1].alive, 1);
  EXPECT_TRUE(scene.arrivalZones.empty());

  world.orderMove({id}, {16, 16, 4, 4});
  for (int i = 0; i < 10; ++i)
    world.step();
  scene = sceneOf(world);
  EXPECT_EQ(scene.tick, 10);
  ASSERT_EQ(scene.arrivalZones.size(), 1u);
  EXPECT_EQ(scene.arrivalZones[0].team, 1);
  EXPECT_EQ(scene.arrivalZones[0].area.x, 16);
  const UnitView& unit = scene.units[0];
  ASSERT_FALSE(unit.path.empty());
  // The last waypoint is the centre of a goal anchor inside the area.
  EXPECT_GE(unit.path.back().x, 17.0f);
  EXPECT_GE(unit.path.back().y, 17.0f);
  // Heading south-east, towards the goal.
  EXPECT_GT(std::cos(unit.facing), 0.0f);
  EXPECT_GT(std::sin(unit.facing), 0.0f);
}

// A gunner that kills in one shot, fired one cooldown (1 s) after spawning.
units::UnitType gunner(double projectileSpeed) {
  units::UnitType t;
  t.name = "gunner";
  t.capability = pathing::Capability::of({Terrain::Ground});
  t.setSpeed(2.0);
  t.hp = 10;
  units::Weapon w;
  w.name = "gun";
  w.damage = 10;
  w.range = 6.0;
  w.cooldown = 1.0;
  w.projectileSpeed = projectileSpeed;
  t.weapon = w;
  return t;
}

units::UnitType sandbag() {
  units::UnitType t;
  t.name = "sandbag";
  t.capability = pathing::Capability::of({Terrain::Ground});
  t.setSpeed(1.0);
  t.hp = 10;
  return t;
}

// An instant shot is a tracer from shooter to target in the frame after it was fired; the dead
// unit is a wreck while its wreck stands (1 s here) and gone from the picture afterwards, still
// counted dead.
TEST(WorldScene, TracersAndWrecksThatClear) {
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(24, 24));
  engine::WorldSettings settings;
  settings.combat.wreckSeconds = 1.0;
  engine::World world(grid, {gunner(0.0), sandbag()}, settings);
  world.spawn(0, 0, 0, {3, 3});
  world.spawn(1, 1, 1, {6, 3});
  while (world.tick() < 31)
    world.step();
  const engine::Unit& dead = world.units()[1];
  ASSERT_FALSE(dead.alive());
  ASSERT_EQ(dead.deathTick, 30);
  ASSERT_EQ(dead.wreckUntilTick, 60);

  FrameScene scene = sceneOf(world, 2);
  ASSERT_EQ(scene.shots.size(), 1u);
  EXPECT_EQ(scene.shots[0], (Tracer{{3.5f, 3.5f}, {6.5f, 3.5f}, 0, false}));
  ASSERT_EQ(scene.units.size(), 2u);
  EXPECT_EQ(scene.units[1].state, UnitState::Wreck);
  EXPECT_EQ(scene.teams[1].dead, 1);
  EXPECT_EQ(scene.teams[1].alive, 0);

  world.step();  // nothing fires at tick 31: no tracer
  EXPECT_TRUE(sceneOf(world, 2).shots.empty());
  while (world.tick() < 59)
    world.step();
  EXPECT_EQ(sceneOf(world, 2).units.size(), 2u);  // the wreck stands until tick 60
  world.step();
  scene = sceneOf(world, 2);
  EXPECT_EQ(world.units()[1].wreckUntilTick, -1);
  ASSERT_EQ(scene.units.size(), 1u);  // cleared: not drawn
  EXPECT_EQ(scene.units[0].team, 0);
  EXPECT_EQ(scene.teams[1].dead, 1);
}

// A shell in flight is a streak at most a cell long ending where the shell is.
TEST(WorldScene, ShellsInFlightAreStreaks) {
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(24, 24));
  engine::World world(grid, {gunner(3.0), sandbag()}, engine::WorldSettings{});
  world.spawn(0, 0, 0, {3, 3});
  world.spawn(1, 1, 1, {8, 3});  // a gap of 4 cells: 40 ticks of flight at 3 cells/s
  while (world.tick() < 50)
    world.step();
  ASSERT_EQ(world.shotsInFlight().size(), 1u);
  const engine::Shot& shell = world.shotsInFlight()[0];
  ASSERT_EQ(shell.firedTick, 30);
  ASSERT_EQ(shell.landTick, 70);
  const FrameScene scene = sceneOf(world);
  ASSERT_EQ(scene.shots.size(), 1u);
  const Tracer& t = scene.shots[0];
  EXPECT_TRUE(t.projectile);
  EXPECT_EQ(t.team, 0);
  EXPECT_FLOAT_EQ(t.to.x, 3.5f + 5.0f * 0.5f);  // half way at tick 50
  EXPECT_FLOAT_EQ(t.from.x, t.to.x - 1.0f);
  EXPECT_FLOAT_EQ(t.to.y, 3.5f);
  EXPECT_TRUE(world.units()[1].alive());
}

// Terrain that changes during a run shows in the next frame, exactly where it changed.
TEST(WorldScene, FramesShowTheTerrainAsItChanges) {
  const pathing::GridMap map(24, 24);
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(map);
  engine::WorldSettings settings;
  settings.terrainChanges = true;
  units::UnitType truck;
  truck.name = "truck";
  truck.capability = pathing::Capability::of({Terrain::Ground});
  engine::World world(grid, {truck}, settings);
  auto renderer = Renderer::create(map, fittedDef(map, 192));  // 8 pixels a cell
  ASSERT_TRUE(renderer) << renderer.error().describe();
  world.step();
  ASSERT_TRUE(renderer.value().render(sceneOf(world)));
  const Image before = renderer.value().image();
  const pathing::CellRect changed{12, 14, 4, 3};
  world.setTerrain(changed, Terrain::Water);
  world.step();
  FrameScene next = sceneOf(world);
  next.tick = 1;  // the HUD's clock as before: only the terrain differs
  next.seconds = world.seconds() - 1.0 / world.tickRate();
  ASSERT_TRUE(renderer.value().render(next));
  const Image& after = renderer.value().image();
  int inside = 0;
  int outside = 0;
  for (int y = 0; y < after.height; ++y) {
    for (int x = 0; x < after.width; ++x) {
      if (before.at(x, y) == after.at(x, y)) continue;
      const bool in = changed.contains({x / 8, y / 8});
      (in ? inside : outside) += 1;
    }
  }
  EXPECT_EQ(inside, changed.width * changed.height * 64);
  EXPECT_EQ(outside, 0);
  EXPECT_EQ(after.at(13 * 8 + 4, 15 * 8 + 4), palette::terrainColour(Terrain::Water));
}

}  // namespace
}  // namespace warpath::render
