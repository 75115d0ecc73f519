// The World -> FrameScene adapter on a small world.

#include "render/world_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "engine/world.h"

namespace warpath::render {
namespace {

using pathing::Terrain;

TEST(WorldScene, ShowsUnitsTheirOrdersAndCounts) {
  units::UnitType tank{
      .name = "tank", .size = 2, .capability = pathing::Capability::of({Terrain::Ground})};
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

}  // namespace
}  // namespace warpath::render
