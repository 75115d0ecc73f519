// Terrain that changes during a run (docs/terrain_changes.md): the bundled bridge demolition
// (the convoy re-routes by the ford; determinism; replays), units pushed off terrain that became
// impassable, wrecks of large units blocking planning, and runs that never change the
// scenario's grid for the next run.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/replay.h"
#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "pathing/map_io.h"
#include "support/event_history.h"
#include "support/scenario_files.h"

namespace warpath::engine {
namespace {

namespace fs = std::filesystem;
using pathing::Cell;
using pathing::CellRect;
using pathing::Terrain;

const std::string kDemolitionFile =
    std::string(WARPATH_SOURCE_DIR) + "/scenarios/bridge_demolition.yaml";
constexpr CellRect kBridge{28, 6, 8, 5};
constexpr CellRect kFord{28, 34, 8, 5};

std::string scenarioText() {
  std::ifstream in(kDemolitionFile);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Scenario loadDemolition(const std::string& text) {
  return testing::parsedScenario(text, kDemolitionFile);
}

// The bundled scenario without its demolition: the bridge stands.
std::string withoutDemolition() {
  std::string text = scenarioText();
  const std::size_t at = text.find("triggers:");
  const std::size_t end = text.find("expectations:");
  EXPECT_NE(at, std::string::npos);
  text.erase(at, end - at);
  return text;
}

bool footprintMeets(Cell anchor, int size, const CellRect& area) {
  return anchor.x < area.x + area.width && anchor.x + size > area.x &&
         anchor.y < area.y + area.height && anchor.y + size > area.y;
}

// Per unit, whether its footprint ever met `area` (after `from`, a tick).
struct Visits {
  std::vector<bool> ford;
  std::vector<bool> bridgeAfter;
};

Visits runAndWatch(const Scenario& s, std::int64_t& changeTick, Report& report) {
  ScenarioRun run(s);
  Visits v;
  changeTick = -1;
  while (!run.done()) {
    run.step();
    for (const IssuedOrder& o : run.issued()) {
      if (o.kind == IssuedKind::SetTerrain && changeTick < 0) changeTick = o.tick;
    }
    const std::vector<Unit>& units = run.world().units();
    v.ford.resize(units.size(), false);
    v.bridgeAfter.resize(units.size(), false);
    for (const Unit& u : units) {
      const int size = s.catalogue[static_cast<std::size_t>(u.type)].size;
      const Cell anchor = units::centreToAnchor(u.position, size);
      if (footprintMeets(anchor, size, kFord)) v.ford[u.id.index] = true;
      // The change applies at the start of the step after the trigger fired.
      if (changeTick >= 0 && run.world().tick() > changeTick + 1 &&
          footprintMeets(anchor, size, kBridge))
        v.bridgeAfter[u.id.index] = true;
    }
  }
  report = run.report();
  return v;
}

TEST(BridgeDemolition, TheConvoyReRoutesByTheFordAndArrives) {
  const Scenario s = loadDemolition(scenarioText());
  std::int64_t changeTick = -1;
  Report report;
  const Visits v = runAndWatch(s, changeTick, report);
  EXPECT_TRUE(report.passed());
  ASSERT_EQ(report.triggersFired, std::vector<std::string>{"demolition"});
  EXPECT_GT(changeTick, 0);  // mid-run, as the convoy approaches
  ASSERT_EQ(v.ford.size(), 6u);
  for (std::size_t i = 0; i < v.ford.size(); ++i) {
    EXPECT_TRUE(v.ford[i]) << "tank " << i << " never crossed the ford";
    EXPECT_FALSE(v.bridgeAfter[i]) << "tank " << i << " stood on the blown bridge";
  }
  EXPECT_GE(report.pathing.terrainChanges, 1u);
  // The scenario's grid is shared by every run and never changes: the run had its own.
  EXPECT_EQ(s.grid->revision(), 0u);
  EXPECT_EQ(s.grid->map().at({30, 8}), Terrain::Ground);
}

// Without the demolition the convoy takes the bridge: the ford test above can fail.
TEST(BridgeDemolition, WithTheBridgeStandingNoTankFords) {
  const Scenario s = loadDemolition(withoutDemolition());
  EXPECT_FALSE(s.settings.terrainChanges);
  std::int64_t changeTick = -1;
  Report report;
  const Visits v = runAndWatch(s, changeTick, report);
  EXPECT_TRUE(report.passed());
  EXPECT_EQ(changeTick, -1);
  EXPECT_EQ(std::count(v.ford.begin(), v.ford.end(), true), 0);
}

std::uint64_t finalHash(const Scenario& s) {
  ScenarioRun run(s);
  while (!run.done())
    run.step();
  return run.stateHash();
}

TEST(BridgeDemolition, DeterministicAndTheChangeReachesTheHash) {
  const Scenario s = loadDemolition(scenarioText());
  const std::uint64_t first = finalHash(s);
  EXPECT_EQ(finalHash(s), first);  // the second run starts from the unchanged shared grid
  EXPECT_NE(finalHash(loadDemolition(withoutDemolition())), first);
}

// Threads that search the graph's clusters (`rts run --threads`) build and repair the same
// graph, so the run, the blown bridge included, ends in the same state.
TEST(BridgeDemolition, TheSameRunOnAnyNumberOfBuildThreads) {
  Scenario s = loadDemolition(scenarioText());
  ASSERT_EQ(s.settings.pathing.buildThreads, 1);
  const std::uint64_t oneThread = finalHash(s);
  s.settings.pathing.buildThreads = 3;
  EXPECT_EQ(finalHash(s), oneThread);
}

// Two worlds that differ only in a change that touches no unit's route hash differently.
TEST(WorldTerrainChange, AChangeAloneChangesTheHash) {
  const Scenario s = loadDemolition(scenarioText());
  WorldSettings settings = s.settings;
  World a(s.grid, s.catalogue, settings);
  World b(s.grid, s.catalogue, settings);
  b.setTerrain({50, 40, 2, 2}, Terrain::Trees);
  a.step();
  b.step();
  EXPECT_NE(a.stateHash(), b.stateHash());
  EXPECT_EQ(a.stateHash(5), b.stateHash(5));  // format 5 knew no terrain changes
  EXPECT_EQ(b.grid().map().at({50, 40}), Terrain::Trees);
  EXPECT_EQ(a.grid().map().at({50, 40}), Terrain::Ground);
}

TEST(WorldTerrainChange, NeedsAWorldThatMayChangeItsTerrain) {
  const Scenario s = loadDemolition(withoutDemolition());
  WorldSettings settings = s.settings;
  World world(s.grid, s.catalogue, settings);
  EXPECT_THROW(world.setTerrain({1, 1, 1, 1}, Terrain::Water), std::logic_error);
}

class TerrainReplay : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "warpath_terrain_replay";
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(TerrainReplay, RecordsTheChangeAndVerifies) {
  ReplaySource source;
  Result<Scenario> s = loadRecordedScenario(kDemolitionFile, source);
  ASSERT_TRUE(s.ok()) << s.error().describe();
  source.seed = s.value().settings.seed;
  source.hashEvery = 10;
  const fs::path file = dir_ / "bridge.rpl";
  Result<ReplayWriter> writer = ReplayWriter::open(file, source);
  ASSERT_TRUE(writer.ok());
  ScenarioRun run(s.value());
  ASSERT_TRUE(writer.value().record(run));
  while (!run.done()) {
    run.step();
    ASSERT_TRUE(writer.value().record(run));
  }
  ASSERT_TRUE(writer.value().finish(run, ReplayEnd::Complete));

  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok()) << replay.error().describe();
  EXPECT_EQ(replay.value().version, kReplayVersion);
  const auto change =
      std::find_if(replay.value().orders.begin(), replay.value().orders.end(),
                   [](const IssuedOrder& o) { return o.kind == IssuedKind::SetTerrain; });
  ASSERT_NE(change, replay.value().orders.end());
  EXPECT_EQ(change->command.area, kBridge);
  EXPECT_EQ(change->group, static_cast<int>(Terrain::Water));

  Result<ReplayPlayback> playback = ReplayPlayback::open(replay.value(), file.string());
  ASSERT_TRUE(playback.ok()) << playback.error().describe();
  const VerifyOutcome outcome = verifyReplay(playback.value());
  EXPECT_FALSE(outcome.mismatch);
  EXPECT_EQ(outcome.ticks, run.world().tick());

  // Played without the change, the hashes part at the tick it was applied.
  Replay without = replay.value();
  std::erase_if(without.orders,
                [](const IssuedOrder& o) { return o.kind == IssuedKind::SetTerrain; });
  Result<ReplayPlayback> other = ReplayPlayback::open(without, file.string());
  ASSERT_TRUE(other.ok()) << other.error().describe();
  const VerifyOutcome differs = verifyReplay(other.value());
  ASSERT_TRUE(differs.mismatch);
  EXPECT_LE(differs.mismatch->tick, change->tick + source.hashEvery + 1);

  // A format-5 file cannot hold a change.
  Replay old = replay.value();
  old.version = 5;
  const Result<ReplayPlayback> refused = ReplayPlayback::open(old, file.string());
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("sets terrain, which format 5 cannot record"),
            std::string::npos)
      << refused.error().message;
}

// Replays of formats <= 5 play back without wrecks blocking planning (ReplayPlayback::open turns
// it off): river_ambush, whose tank wrecks change the battle, then runs exactly as it did before
// the rule — its golden hash as format 3 laid the state out, pinned before terrain changes. (Its
// southern red riflemen as they stood then, a row further into the woods, and its seed then.)
TEST(WreckRule, OffItRunsRiverAmbushAsBefore) {
  const std::filesystem::path file =
      std::filesystem::path(WARPATH_SOURCE_DIR) / "scenarios/river_ambush.yaml";
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  std::string then = text.str();
  const std::size_t south = then.find("x: 55, y: 29,");
  ASSERT_NE(south, std::string::npos);
  then.replace(south, 13, "x: 55, y: 30,");
  const std::size_t seed = then.find("\nseed: 612\n");  // its seed then (606 until format 25)
  ASSERT_NE(seed, std::string::npos);
  then.replace(seed, 11, "\nseed: 606\n");
  Result<Scenario> s = parseScenario(then, file);
  ASSERT_TRUE(s.ok()) << s.error().describe();
  s.value().settings.combat.wrecksBlock = false;
  s.value().settings.pathing.cooperative = false;  // off by default before format 7
  ScenarioRun run(s.value());
  while (!run.done())
    run.step();
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(run.stateHash(3)));
  EXPECT_EQ(std::string(hex), "db97e493b5eaebef");
}

// ---- units on terrain that became impassable, and wrecks ------------------------------------

std::shared_ptr<const pathing::AnnotatedGrid> openGrid(int width, int height) {
  return std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(width, height));
}

units::UnitType kind(const std::string& name, int size) {
  units::UnitType t;
  t.name = name;
  t.size = size;
  t.capability = pathing::parseCapability("ground").value();
  t.setSpeed(2.0);
  t.acceleration = 20.0;
  t.turnRate = 30.0;
  t.radius = 0.4 * size;
  t.hp = 100;
  return t;
}

// The rule: a unit whose footprint can no longer stand where it is moves to the nearest anchor
// it can stand on, at once, at the start of the step the change applies in.
TEST(WorldTerrainChange, AUnitOnTerrainThatBecameImpassableIsPushedToTheNearestStandableCell) {
  WorldSettings settings;
  settings.terrainChanges = true;
  settings.combat.enabled = false;
  World world(openGrid(20, 10), {kind("truck", 2)}, settings);
  const UnitId truck = world.spawn(0, 0, 0, {5, 4});
  world.setTerrain({4, 2, 4, 6}, Terrain::Blocked);  // x 4-7, rows 2-7: under the truck
  world.step();
  EXPECT_EQ(testing::countEvents(world, EventKind::Pushed), 1);
  const Unit& u = *world.find(truck);
  const Cell anchor = units::centreToAnchor(u.position, 2);
  EXPECT_TRUE(world.grid().canStand({2, pathing::parseCapability("ground").value()}, anchor));
  // The nearest anchor where 2x2 fits: left of the wall, x 2, row 4.
  EXPECT_EQ(anchor, (Cell{2, 4}));
  EXPECT_TRUE(u.alive());
}

// ... and when no cell of the map can hold it any more, it is killed.
TEST(WorldTerrainChange, AUnitWithNowhereToStandIsKilled) {
  WorldSettings settings;
  settings.terrainChanges = true;
  settings.combat.enabled = false;
  World world(openGrid(8, 8), {kind("truck", 2)}, settings);
  const UnitId truck = world.spawn(0, 0, 0, {3, 3});
  world.setTerrain({0, 0, 8, 8}, Terrain::Water);
  world.step();
  EXPECT_FALSE(world.find(truck)->alive());
  EXPECT_EQ(testing::countEvents(world, EventKind::Killed), 1);
  EXPECT_EQ(testing::countEvents(world, EventKind::Pushed), 0);
}

TEST(WorldTerrainChange, AMovingUnitWhosePathCrossesTheChangeRepaths) {
  WorldSettings settings;
  settings.terrainChanges = true;
  settings.combat.enabled = false;
  World world(openGrid(30, 12), {kind("truck", 1)}, settings);
  const UnitId truck = world.spawn(0, 0, 0, {2, 5});
  world.orderMove({truck}, {26, 5, 2, 2});
  for (int i = 0; i < 5; ++i)
    world.step();
  ASSERT_EQ(world.find(truck)->state, UnitState::Moving);
  world.setTerrain({14, 0, 2, 10}, Terrain::Water);  // a wall across, open at rows 10-11
  world.step();
  const auto repath = std::count_if(world.events().begin(), world.events().end(), [](auto& e) {
    return e.kind == EventKind::Repath && e.detail == 3;
  });
  EXPECT_EQ(repath, 1);
  while (world.find(truck)->arrivalTick < 0 && world.tick() < 900)
    world.step();
  EXPECT_GE(world.find(truck)->arrivalTick, 0);
}

// A unit pushed back along its path has cells behind its waypoint to walk again: a change there
// makes it repath too (replay format 29). The push is put in by hand: the truck, 4.5 cells along
// its way east, is set back to its start, and a wall rises across the cells in between.
TEST(WorldTerrainChange, AUnitPushedBackRepathsForAChangeBehindItsWaypoint) {
  for (const bool rule : {true, false}) {
    WorldSettings settings;
    settings.terrainChanges = true;
    settings.combat.enabled = false;
    settings.pathing.routeFromPlaceOnPath = rule;
    World world(openGrid(30, 12), {kind("truck", 1)}, settings);
    const UnitId truck = world.spawn(0, 0, 0, {2, 5});
    world.orderMove({truck}, {26, 5, 2, 2});
    while (world.find(truck)->position.x < 7.0 && world.tick() < 300)
      world.step();
    // (The world gives out its units read-only; the test writes the push into the unit's state
    // as the physics step would, and the next step's terrain phase reads it before physics.)
    Unit& u = const_cast<Unit&>(*world.find(truck));
    ASSERT_EQ(u.state, UnitState::Moving);
    ASSERT_TRUE(u.path);
    ASSERT_GT(u.next, 1u);
    ASSERT_GT(units::anchorToCentre(u.path->cells[u.next - 1], 1).x, 5.0);
    u.position = {2.5, 5.5};
    world.setTerrain({4, 0, 1, 10}, Terrain::Water);  // behind the waypoint it had passed
    world.step();
    EXPECT_EQ(std::count_if(world.events().begin(), world.events().end(),
                            [](auto& e) { return e.kind == EventKind::Repath && e.detail == 3; }),
              rule ? 1 : 0)
        << (rule ? "with" : "without") << " the rule";
  }
}

// A unit that found no way to its goal tries again when terrain opens one: a river cuts the map
// in two, the unit's order fails, then a ford appears (water set to ground) and it crosses.
TEST(WorldTerrainChange, AUnitWithNoPathTriesAgainWhenTerrainOpensAWay) {
  WorldSettings settings;
  settings.terrainChanges = true;
  settings.combat.enabled = false;
  World world(openGrid(30, 12), {kind("truck", 1)}, settings);
  world.setTerrain({14, 0, 2, 12}, Terrain::Water);  // the river, bank to bank
  world.step();
  const UnitId truck = world.spawn(0, 0, 0, {2, 5});
  world.orderMove({truck}, {26, 5, 2, 2});
  for (int i = 0; i < 5; ++i)
    world.step();
  ASSERT_EQ(world.find(truck)->state, UnitState::NoPath);
  // Closing terrain elsewhere cannot open a way: the unit does not try again.
  world.setTerrain({2, 0, 1, 1}, Terrain::Blocked);
  world.step();
  EXPECT_EQ(world.find(truck)->state, UnitState::NoPath);
  world.setTerrain({14, 5, 2, 2}, Terrain::Ground);  // the ford
  world.step();
  const auto retries = std::count_if(world.events().begin(), world.events().end(), [](auto& e) {
    return e.kind == EventKind::Repath && e.detail == 4;
  });
  EXPECT_EQ(retries, 1);
  while (world.find(truck)->arrivalTick < 0 && world.tick() < 900)
    world.step();
  EXPECT_GE(world.find(truck)->arrivalTick, 0);
}

// A size-2 wreck blocks planning over its footprint while it stands; a size-1 one does not.
TEST(WorldTerrainChange, WrecksOfLargeUnitsBlockPlanningWhileTheyStand) {
  for (const bool block : {true, false}) {
    WorldSettings settings;
    settings.combat.wreckSeconds = 1.0;  // 30 ticks
    settings.combat.wrecksBlock = block;
    std::vector<units::UnitType> types{kind("truck", 2)};
    types[0].weapon = units::defaultWeaponFor("tank");
    types[0].armour = *units::defaultArmourFor("jeep");
    World world(openGrid(24, 8), types, settings);
    const UnitId a = world.spawn(0, 0, 0, {4, 3});
    const UnitId b = world.spawn(0, 1, 1, {9, 3});
    world.order({OrderKind::Hold, {a}, {}, {}});
    world.order({OrderKind::Hold, {b}, {}, {}});
    std::int64_t guard = 0;
    while (world.find(a)->alive() && world.find(b)->alive() && ++guard < 5000)
      world.step();
    const Unit& dead = world.find(a)->alive() ? *world.find(b) : *world.find(a);
    ASSERT_FALSE(dead.alive());
    const Cell at = units::centreToAnchor(dead.position, 2);
    const pathing::Agent one{1, pathing::parseCapability("ground").value()};
    world.step();  // the obstacle goes down at the start of the step after the death
    EXPECT_EQ(!world.grid().canStand(one, at), block) << block;
    EXPECT_EQ(dead.wreckArea.width, block ? 2 : 0);
    while (dead.wreckUntilTick >= 0)
      world.step();
    world.step();  // and is cleared at the start of the step after the wreck went
    EXPECT_TRUE(world.grid().canStand(one, at));
  }
}

}  // namespace
}  // namespace warpath::engine
