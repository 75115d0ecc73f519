// Combat inside the world tick: duels whose outcome is worked out by hand, line of sight, the
// order semantics (move fires on the move, attack-move halts to fight, attack closes in, hold
// never moves), deaths (bodies, wrecks, path users) and determinism.

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "engine/world.h"
#include "pathing/map_io.h"
#include "support/event_history.h"
#include "units/combat.h"

namespace warpath::engine {
namespace {

using pathing::Cell;
using pathing::CellRect;

std::shared_ptr<const pathing::AnnotatedGrid> gridOf(const std::vector<std::string>& rows) {
  std::string text = "type octile\nheight " + std::to_string(rows.size()) + "\nwidth " +
                     std::to_string(rows[0].size()) + "\nmap\n";
  for (const std::string& row : rows)
    text += row + "\n";
  std::istringstream in(text);
  Result<pathing::GridMap> map = pathing::parseMap(in, "test map");
  EXPECT_TRUE(map) << map.error().describe();
  return std::make_shared<const pathing::AnnotatedGrid>(std::move(map).value());
}

// The four catalogue types with the default weapons and armour of docs/combat.md.
units::UnitType armed(const std::string& name, int size, const std::string& capability, int hp,
                      double speed) {
  units::UnitType t;
  t.name = name;
  t.size = size;
  t.capability = pathing::parseCapability(capability).value();
  t.setSpeed(speed);
  t.acceleration = 20.0;
  t.turnRate = 30.0;
  t.radius = 0.4 * size;
  t.hp = hp;
  t.armour = *units::defaultArmourFor(name);
  t.weapon = units::defaultWeaponFor(name);
  return t;
}

std::vector<units::UnitType> catalogue() {
  return {armed("infantry", 1, "ground,trees", 100, 1.5), armed("jeep", 2, "ground", 200, 6.0),
          armed("tank", 3, "ground", 800, 2.0)};
}
constexpr int kInfantry = 0;
constexpr int kJeep = 1;
constexpr int kTank = 2;

std::vector<std::string> openField(int width, int height) {
  return std::vector<std::string>(static_cast<std::size_t>(height),
                                  std::string(static_cast<std::size_t>(width), '.'));
}

void stepUntil(World& world, std::int64_t tick) {
  while (world.tick() < tick)
    world.step();
}

// Two riflemen 3 cells apart: both weapons are ready at tick 30 (one cooldown after spawning)
// and fire every 30 ticks; 10 damage a shot against 100 hp is 10 shots, so the tenth volley, in
// the step that starts at tick 300, kills both: instant shots fired in one tick all land.
TEST(WorldCombat, EqualRiflemenKillEachOtherOnTheTenthVolley) {
  WorldSettings settings;
  settings.combat.wreckSeconds = 0.0;
  World world(gridOf(openField(12, 5)), catalogue(), settings);
  const UnitId a = world.spawn(kInfantry, 0, 0, {2, 2});
  const UnitId b = world.spawn(kInfantry, 1, 1, {5, 2});
  stepUntil(world, 300);
  EXPECT_EQ(world.find(a)->hp, 10);
  EXPECT_EQ(world.find(b)->hp, 10);
  EXPECT_EQ(world.find(a)->combat.shotsFired, 9);
  world.step();
  for (UnitId id : {a, b}) {
    const Unit& u = *world.find(id);
    EXPECT_EQ(u.state, UnitState::Dead);
    EXPECT_EQ(u.deathTick, 300);
    EXPECT_EQ(u.combat.shotsFired, 10);
    EXPECT_EQ(u.combat.hits, 10);
    EXPECT_EQ(u.combat.damageDealt, 100);
    EXPECT_EQ(u.combat.damageTaken, 100);
    EXPECT_EQ(u.combat.kills, 1);
  }
  EXPECT_EQ(world.find(a)->killedBy, b);
  EXPECT_EQ(world.find(b)->killedBy, a);
  EXPECT_EQ(testing::countEvents(world, EventKind::Killed), 2);
  EXPECT_EQ(world.aliveCount(0), 0);
  EXPECT_EQ(world.aliveCount(1), 0);
  EXPECT_EQ(world.physics().stats().bodies, 0);  // no wrecks: bodies removed at once
}

// A rifleman against a jeep. The machine gun (8 × 125 % = 10 against infantry, every 9 ticks,
// first at tick 9) fires its tenth shot at tick 90; the rifle (10 × 40 % = 4 against light
// armour, every 30 ticks) has fired at 30, 60 and 90 by then, and fires first at tick 90 (id
// order), so the jeep ends with 200 − 12 = 188 hp.
TEST(WorldCombat, JeepBeatsRiflemanByHand) {
  World world(gridOf(openField(14, 6)), catalogue(), {});
  const UnitId rifleman = world.spawn(kInfantry, 0, 0, {2, 2});
  const UnitId jeep = world.spawn(kJeep, 1, 1, {6, 2});
  stepUntil(world, 200);
  const Unit& r = *world.find(rifleman);
  const Unit& j = *world.find(jeep);
  EXPECT_EQ(r.deathTick, 90);
  EXPECT_EQ(r.combat.shotsFired, 3);
  EXPECT_EQ(r.combat.damageDealt, 12);
  EXPECT_EQ(j.hp, 188);
  EXPECT_EQ(j.combat.shotsFired, 10);
  EXPECT_EQ(j.combat.kills, 1);
  EXPECT_FALSE(j.target.valid());  // nothing left to shoot
}

// A tank shell flies at 15 cells/s: over a gap of 3 cells it takes 0.2 s = 6 ticks, so the
// damage lands 6 ticks after the shot.
TEST(WorldCombat, ShellsLandAfterTheirFlightTime) {
  World world(gridOf(openField(20, 8)), catalogue(), {});
  const UnitId tank = world.spawn(kTank, 0, 0, {2, 2});
  const UnitId jeep = world.spawn(kJeep, 1, 1, {8, 3});  // gap: 8 − (2 + 3) = 3 cells
  const std::int64_t ready = world.find(tank)->readyTick;
  stepUntil(world, ready + 1);
  ASSERT_EQ(world.find(tank)->combat.shotsFired, 1);
  ASSERT_EQ(world.shotsInFlight().size(), 1u);
  EXPECT_EQ(world.shotsInFlight()[0].landTick, ready + 6);
  EXPECT_EQ(world.find(jeep)->combat.damageTaken, 0);
  stepUntil(world, ready + 6);  // not yet: the step at tick ready + 6 lands it
  EXPECT_EQ(world.find(jeep)->hp, 200);
  stepUntil(world, ready + 7);
  // 150 × 150 % = 225 > 200 hp: one shell destroys the jeep.
  EXPECT_FALSE(world.find(jeep)->alive());
  EXPECT_EQ(world.find(tank)->combat.damageDealt, 200);  // capped at what the jeep had
  EXPECT_TRUE(world.shotsInFlight().empty());
}

TEST(WorldCombat, WallsBlockFireAndTeammatesAreNeverShot) {
  World world(gridOf({"..........", "....@.....", "....@.....", "....@.....", ".........."}),
              catalogue(), {});
  const UnitId a = world.spawn(kInfantry, 0, 0, {2, 2});
  const UnitId b = world.spawn(kInfantry, 1, 1, {6, 2});  // in range, behind the wall
  const UnitId c = world.spawn(kInfantry, 0, 0, {3, 2});  // a teammate beside a
  stepUntil(world, 200);
  for (UnitId id : {a, b, c}) {
    EXPECT_EQ(world.find(id)->combat.shotsFired, 0) << id.index;
    EXPECT_EQ(world.find(id)->hp, 100) << id.index;
  }
}

TEST(WorldCombat, DisabledCombatNeverFires) {
  WorldSettings settings;
  settings.combat.enabled = false;
  World world(gridOf(openField(12, 5)), catalogue(), settings);
  world.spawn(kInfantry, 0, 0, {2, 2});
  world.spawn(kInfantry, 1, 1, {5, 2});
  stepUntil(world, 200);
  for (const Unit& u : world.units())
    EXPECT_EQ(u.hp, 100);
}

// A tank drives past an enemy rifleman. On a move order it fires on the move and never stops;
// on an attack-move order it halts while the rifleman is in reach and goes on once it is dead.
TEST(WorldCombat, MoveFiresOnTheMoveAttackMoveHaltsToFight) {
  const auto run = [](OrderKind kind) {
    World world(gridOf(openField(40, 9)), catalogue(), {});
    const UnitId tank = world.spawn(kTank, 0, 0, {1, 3});
    const UnitId rifleman = world.spawn(kInfantry, 1, 1, {20, 0});
    world.order({kind, {tank}, CellRect{34, 3, 4, 4}, {}});
    bool halted = false;
    std::int64_t arrived = -1;
    while (world.tick() < 900 && arrived < 0) {
      world.step();
      halted = halted || world.find(tank)->engaged;
      arrived = world.find(tank)->arrivalTick;
    }
    return std::tuple{halted, arrived, world.find(rifleman)->alive(),
                      world.find(tank)->combat.shotsFired};
  };
  const auto [moveHalted, moveArrived, moveSurvivor, moveShots] = run(OrderKind::Move);
  const auto [fightHalted, fightArrived, fightSurvivor, fightShots] = run(OrderKind::AttackMove);
  EXPECT_FALSE(moveHalted);
  EXPECT_TRUE(fightHalted);
  EXPECT_GE(moveShots, 1);
  EXPECT_GE(moveArrived, 0);
  EXPECT_GE(fightArrived, 0);
  EXPECT_GT(fightArrived, moveArrived);  // the fight cost time
  EXPECT_FALSE(fightSurvivor);           // the halt lasted until the rifleman died
  (void)moveSurvivor;
  (void)fightShots;
}

// An attack order closes in on a target out of range, kills it, then the unit stops.
TEST(WorldCombat, AttackClosesInAndStopsWhenTheTargetIsDead) {
  World world(gridOf(openField(40, 10)), catalogue(), {});
  const UnitId jeep = world.spawn(kJeep, 0, 0, {1, 4});
  const UnitId victim = world.spawn(kInfantry, 1, 1, {32, 5});
  world.order({OrderKind::Attack, {jeep}, {}, {victim}});
  stepUntil(world, 600);
  EXPECT_FALSE(world.find(victim)->alive());
  EXPECT_EQ(world.find(jeep)->order, OrderKind::Stop);
  EXPECT_EQ(world.find(jeep)->combat.kills, 1);
  EXPECT_GT(world.find(jeep)->position.x, 20.0);  // it drove there
}

// Holding units never leave their spot, even with an enemy just out of reach.
TEST(WorldCombat, HoldNeverMoves) {
  World world(gridOf(openField(30, 6)), catalogue(), {});
  const UnitId holder = world.spawn(kInfantry, 0, 0, {2, 2});
  world.spawn(kInfantry, 1, 1, {20, 2});
  world.order({OrderKind::Hold, {holder}, {}, {}});
  const units::Vec2 start = world.find(holder)->position;
  stepUntil(world, 300);
  EXPECT_EQ(world.find(holder)->state, UnitState::Parked);
  EXPECT_LT((world.find(holder)->position - start).length(), 0.05);
  EXPECT_EQ(world.find(holder)->combat.shotsFired, 0);
}

// A wreck keeps its body (a fixed obstacle) for wreckSeconds, then it is cleared; a dead unit
// ignores orders and never asks for a path.
TEST(WorldCombat, WrecksStayForTheirTimeThenGo) {
  WorldSettings settings;
  settings.combat.wreckSeconds = 2.0;  // 60 ticks
  World world(gridOf(openField(20, 8)), catalogue(), settings);
  world.spawn(kTank, 0, 0, {2, 2});
  const UnitId jeep = world.spawn(kJeep, 1, 1, {8, 3});
  while (world.find(jeep)->alive())
    world.step();
  const std::int64_t death = world.find(jeep)->deathTick;
  EXPECT_EQ(world.find(jeep)->wreckUntilTick, death + 60);
  EXPECT_EQ(world.physics().stats().bodies, 2);
  const std::uint64_t requests = world.pathService().metrics().requests;
  world.order({OrderKind::Move, {jeep}, CellRect{15, 0, 4, 4}, {}});
  stepUntil(world, death + 59);
  EXPECT_EQ(world.physics().stats().bodies, 2);
  world.step();  // the step that brings the clock to wreckUntilTick removes the body
  EXPECT_EQ(world.physics().stats().bodies, 1);
  EXPECT_EQ(world.find(jeep)->wreckUntilTick, -1);
  EXPECT_EQ(testing::countEvents(world, EventKind::WreckCleared), 1);
  EXPECT_EQ(world.pathService().metrics().requests, requests);
  EXPECT_EQ(world.find(jeep)->state, UnitState::Dead);
}

// A unit that dies is dropped from the path service: its queued requests are never served.
TEST(WorldCombat, CancelDropsAUnitsQueuedRequests) {
  const auto grid = gridOf(openField(24, 8));
  const pathing::Capability ground = pathing::parseCapability("ground").value();
  PathService service(*grid, {}, {ground}, 1);
  const UnitId alive{0, 0};
  const UnitId dead{1, 0};
  service.request({alive, 1, {1, ground}, {0, 0}, {20, 5}});
  service.request({dead, 1, {1, ground}, {0, 1}, {20, 6}});
  service.request({dead, 2, {1, ground}, {0, 1}, {21, 6}});
  service.cancel(dead);
  EXPECT_EQ(service.queued(), 1u);
  std::vector<PathDelivery> out;
  service.serve(out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].unit, alive);
}

std::uint64_t battleHash(std::uint64_t seed) {
  WorldSettings settings;
  settings.seed = seed;
  World world(gridOf(openField(48, 24)), catalogue(), settings);
  std::vector<UnitId> blue;
  std::vector<UnitId> red;
  for (int i = 0; i < 6; ++i) {
    blue.push_back(world.spawn(kInfantry, 0, 0, {2, 2 + 3 * i}));
    red.push_back(world.spawn(kInfantry, 1, 1, {44, 2 + 3 * i}));
  }
  blue.push_back(world.spawn(kTank, 0, 0, {4, 10}));
  red.push_back(world.spawn(kJeep, 1, 1, {42, 10}));
  world.order({OrderKind::AttackMove, blue, CellRect{36, 0, 10, 24}, {}});
  world.order({OrderKind::AttackMove, red, CellRect{0, 0, 10, 24}, {}});
  stepUntil(world, 900);
  int dead = 0;
  for (const Unit& u : world.units())
    dead += u.alive() ? 0 : 1;
  EXPECT_GT(dead, 0);  // they did fight
  return world.stateHash();
}

TEST(WorldCombat, BattlesAreDeterministic) {
  EXPECT_EQ(battleHash(7), battleHash(7));
}

}  // namespace
}  // namespace warpath::engine
