// The world on small maps: every unit type reaches reachable goals, amphibious units swim where
// tanks go around, tanks never squeeze through gaps narrower than themselves, no unit ever
// overlaps terrain it may not enter, and the path service keeps its promises.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "engine/physics.h"
#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "pathing/map_io.h"
#include "support/event_history.h"
#include "support/expect_rejected.h"
#include "support/scenario_files.h"

namespace warpath::engine {
namespace {

using pathing::Cell;
using pathing::Terrain;

Scenario load(const std::string& text) {
  return testing::parsedScenario(text, testing::kScenariosDir + "test_input.yaml");
}

// Largest depth by which a unit's body overlaps a cell it may not enter (or the outside).
double overlapDepth(const World& world, const Unit& unit) {
  const units::UnitType& type = world.catalogue()[static_cast<std::size_t>(unit.type)];
  const pathing::GridMap& map = world.grid().map();
  double depth = 0.0;
  const int x0 = static_cast<int>(std::floor(unit.position.x - type.radius));
  const int y0 = static_cast<int>(std::floor(unit.position.y - type.radius));
  for (int y = y0; y <= static_cast<int>(unit.position.y + type.radius); ++y) {
    for (int x = x0; x <= static_cast<int>(unit.position.x + type.radius); ++x) {
      const Terrain t = map.at({x, y});
      if (pathing::isTraversable(t) && type.capability.allows(t)) continue;
      const double dx = std::max({x - unit.position.x, 0.0, unit.position.x - (x + 1)});
      const double dy = std::max({y - unit.position.y, 0.0, unit.position.y - (y + 1)});
      depth = std::max(depth, type.radius - std::sqrt(dx * dx + dy * dy));
    }
  }
  return depth;
}

// Runs to the end, checking every tick that no body overlaps forbidden terrain by more than
// Box2D's tolerance (linear slop).
void runChecked(ScenarioRun& run) {
  constexpr double kTolerance = 0.02;
  while (!run.done()) {
    run.step();
    for (const Unit& unit : run.world().units()) {
      ASSERT_LE(overlapDepth(run.world(), unit), kTolerance)
          << "unit " << unit.id.index << " at " << unit.position.x << "," << unit.position.y
          << " tick " << run.world().tick();
    }
  }
}

const std::string kHeader = "catalogue: ../assets/units.yaml\nteams: [blue]\n";

// A size-1 walker of ground only, at 1.5 cells/s.
units::UnitType groundInfantry() {
  units::UnitType infantry;
  infantry.name = "infantry";
  infantry.capability = pathing::Capability::of({Terrain::Ground});
  infantry.setSpeed(1.5);
  return infantry;
}

TEST(World, EveryTypeReachesAReachableGoal) {
  const Scenario s =
      load(kHeader +
           "map:\n  rows:\n"
           "    - '........................'\n"
           "    - '........................'\n"
           "    - '......@@@...............'\n"
           "    - '......@@@...............'\n"
           "    - '........................'\n"
           "    - '........................'\n"
           "    - '........................'\n"
           "    - '........................'\n"
           "duration: 25\n"
           "groups:\n"
           "  - {type: infantry, team: blue, count: 2, spawn: {x: 0, y: 0, w: 2, h: 2},"
           " goal: {x: 20, y: 0, w: 4, h: 3}}\n"
           "  - {type: jeep, team: blue, count: 1, spawn: {x: 0, y: 4, w: 2, h: 2},"
           " goal: {x: 20, y: 3, w: 4, h: 3}}\n"
           "  - {type: tank, team: blue, count: 1, spawn: {x: 2, y: 4, w: 3, h: 3},"
           " goal: {x: 19, y: 5, w: 5, h: 3}}\n"
           "  - {type: amphibious, team: blue, count: 1, spawn: {x: 0, y: 6, w: 2, h: 2},"
           " goal: {x: 14, y: 6, w: 3, h: 2}}\n");
  ScenarioRun run(s);
  runChecked(run);
  for (const Unit& unit : run.world().units()) {
    EXPECT_GE(unit.arrivalTick, 0) << "unit " << unit.id.index;
    EXPECT_EQ(unit.state, UnitState::Parked) << "unit " << unit.id.index;
    EXPECT_TRUE(unit.goalArea.contains(units::centreToAnchor(
        unit.position, run.world().catalogue()[static_cast<std::size_t>(unit.type)].size)));
  }
}

// A lake between spawn and goal with a ground strip around its south end.
const std::string kLake =
    kHeader +
    "map:\n  rows:\n"
    "    - '...........WWWWWW...........'\n"
    "    - '...........WWWWWW...........'\n"
    "    - '...........WWWWWW...........'\n"
    "    - '...........WWWWWW...........'\n"
    "    - '...........WWWWWW...........'\n"
    "    - '...........WWWWWW...........'\n"
    "    - '...........WWWWWW...........'\n"
    "    - '...........WWWWWW...........'\n"
    "    - '............................'\n"
    "    - '............................'\n"
    "    - '............................'\n"
    "duration: 40\n"
    "groups:\n"
    "  - {type: amphibious, team: blue, count: 1, spawn: {x: 2, y: 1, w: 2, h: 2},"
    " goal: {x: 23, y: 1, w: 2, h: 2}}\n"
    "  - {type: tank, team: blue, count: 1, spawn: {x: 2, y: 3, w: 3, h: 3},"
    " goal: {x: 23, y: 3, w: 3, h: 3}}\n";

TEST(World, AmphibiousUnitsSwimWhereTanksGoAround) {
  const Scenario s = load(kLake);
  ScenarioRun run(s);
  bool amphibiousSwam = false;
  double tankLowest = 0.0;  // largest row reached by the tank's centre
  while (!run.done()) {
    run.step();
    const Unit& amphibious = run.world().units()[0];
    const Unit& tank = run.world().units()[1];
    const auto under = [&](const Unit& u) {
      return run.world().grid().map().at(
          {static_cast<int>(std::floor(u.position.x)), static_cast<int>(std::floor(u.position.y))});
    };
    amphibiousSwam = amphibiousSwam || under(amphibious) == Terrain::Water;
    ASSERT_NE(under(tank), Terrain::Water);
    ASSERT_LE(overlapDepth(run.world(), tank), 0.02);
    tankLowest = std::max(tankLowest, tank.position.y);
  }
  const Unit& amphibious = run.world().units()[0];
  const Unit& tank = run.world().units()[1];
  EXPECT_TRUE(amphibiousSwam);
  EXPECT_GE(amphibious.arrivalTick, 0);
  EXPECT_GE(tank.arrivalTick, 0);
  EXPECT_GT(tankLowest, 8.0);  // went round the south end of the lake
  EXPECT_LT(amphibious.arrivalTick, tank.arrivalTick);
}

TEST(World, TanksNeverPassGapsNarrowerThanThreeCells) {
  // A wall with a 2-cell gap near the direct line and a 3-cell gap far south.
  const Scenario s =
      load(kHeader +
           "map:\n  rows:\n"
           "    - '..........@..........'\n"
           "    - '..........@..........'\n"
           "    - '..........@..........'\n"
           "    - '.....................'\n"
           "    - '.....................'\n"
           "    - '..........@..........'\n"
           "    - '..........@..........'\n"
           "    - '..........@..........'\n"
           "    - '..........@..........'\n"
           "    - '..........@..........'\n"
           "    - '..........@..........'\n"
           "    - '.....................'\n"
           "    - '.....................'\n"
           "    - '.....................'\n"
           "duration: 40\n"
           "groups:\n"
           "  - {type: tank, team: blue, count: 1, spawn: {x: 2, y: 2, w: 3, h: 3},"
           " goal: {x: 15, y: 2, w: 3, h: 3}}\n"
           "  - {type: infantry, team: blue, count: 1, spawn: {x: 0, y: 0, w: 1, h: 1},"
           " goal: {x: 15, y: 0, w: 3, h: 3}}\n");
  ScenarioRun run(s);
  bool tankUsedSouthGap = false;
  bool infantryUsedNorthGap = false;
  while (!run.done()) {
    run.step();
    const Unit& tank = run.world().units()[0];
    const Unit& infantry = run.world().units()[1];
    if (std::abs(tank.position.x - 10.5) < 1.0) {
      ASSERT_GT(tank.position.y, 11.0) << "the tank is in the wall's 2-cell gap";
      tankUsedSouthGap = true;
    }
    if (std::abs(infantry.position.x - 10.5) < 0.5 && infantry.position.y < 5.0)
      infantryUsedNorthGap = true;
  }
  EXPECT_TRUE(tankUsedSouthGap);
  EXPECT_TRUE(infantryUsedNorthGap);
  EXPECT_GE(run.world().units()[0].arrivalTick, 0);
}

TEST(Physics, ABodyCannotBePushedThroughAGapNarrowerThanIt) {
  // Directly in Box2D: a tank-sized body driven at a 2-cell gap stays on its side.
  pathing::GridMap map(12, 9);
  for (int y = 0; y < 9; ++y) {
    if (y != 4 && y != 5) map.set({6, y}, Terrain::Blocked);
  }
  const pathing::Capability ground = pathing::Capability::of({Terrain::Ground});
  Physics physics(map, std::span<const pathing::Capability>(&ground, 1));
  const BodyId body = physics.addBody({3.0, 5.0}, 1.4, ground);
  double furthest = 0.0;
  for (int i = 0; i < 300; ++i) {
    physics.setVelocity(body, {3.0, 0.0});
    physics.step(1.0 / 30.0);
    furthest = std::max(furthest, physics.position(body).x);
  }
  EXPECT_LT(furthest, 6.0);  // wedged in the gap's mouth, never through the wall's column
  Physics other(map, std::span<const pathing::Capability>(&ground, 1));
  const BodyId small = other.addBody({3.0, 5.0}, 0.9, ground);
  for (int i = 0; i < 300; ++i) {
    other.setVelocity(small, {3.0, 0.0});
    other.step(1.0 / 30.0);
  }
  EXPECT_GT(other.position(small).x, 8.0);  // a 2-cell unit fits
}

TEST(Physics, TouchingReportsTheOwnersOfBodiesInContact) {
  const pathing::GridMap map(20, 10);
  const pathing::Capability ground = pathing::Capability::of({Terrain::Ground});
  Physics physics(map, std::span<const pathing::Capability>(&ground, 1));
  const BodyId a = physics.addBody({5.0, 5.0}, 0.5, ground, 11);
  const BodyId b = physics.addBody({5.9, 5.0}, 0.5, ground, 22);  // overlapping a
  const BodyId far = physics.addBody({15.0, 5.0}, 0.5, ground, 33);
  physics.step(1.0 / 30.0);
  std::vector<std::uint32_t> owners{99};
  physics.touching(a, owners);
  EXPECT_EQ(owners, std::vector<std::uint32_t>{22});
  physics.touching(b, owners);
  EXPECT_EQ(owners, std::vector<std::uint32_t>{11});
  physics.touching(far, owners);
  EXPECT_TRUE(owners.empty());
  physics.removeBody(b);
  physics.touching(a, owners);
  EXPECT_TRUE(owners.empty());
}

TEST(Physics, CollisionMasksFollowCapabilities) {
  const auto tank = collisionMaskFor(pathing::Capability::of({Terrain::Ground}));
  const auto amphibious =
      collisionMaskFor(pathing::Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water}));
  EXPECT_NE(tank & terrainCategory(Terrain::Water), 0);
  EXPECT_EQ(amphibious & terrainCategory(Terrain::Water), 0);
  EXPECT_NE(amphibious & terrainCategory(Terrain::Trees), 0);
  for (auto mask : {tank, amphibious}) {
    EXPECT_NE(mask & kBlockedCategory, 0);
    EXPECT_NE(mask & kUnitCategory, 0);
    EXPECT_EQ(mask & terrainCategory(Terrain::Ground), 0);
  }
}

TEST(PathService, BudgetSpreadsRequestsAndCacheAnswersRepeats) {
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(64, 64));
  PathServiceSettings settings;
  settings.algorithm = pathing::Algorithm::AStar;
  settings.expansionBudget = 1;  // one search a tick
  const pathing::Agent agent{1, pathing::Capability::of({Terrain::Ground})};
  PathService service(*grid, settings, {agent.capability}, 1);
  service.request({{0, 0}, 1, agent, {0, 0}, {60, 60}});
  service.request({{1, 0}, 1, agent, {0, 0}, {60, 60}});  // identical: coalesced
  service.request({{2, 0}, 1, agent, {0, 1}, {60, 60}});
  std::vector<PathDelivery> out;
  service.serve(out);
  ASSERT_EQ(out.size(), 2u);  // the search spends the budget; its duplicate rides along free
  EXPECT_EQ(out[0].unit.index, 0u);
  EXPECT_EQ(out[1].unit.index, 1u);
  EXPECT_EQ(out[0].path, out[1].path);
  EXPECT_EQ(service.metrics().cacheHits, 1u);
  EXPECT_EQ(service.queued(), 1u);
  out.clear();
  service.serve(out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].unit.index, 2u);
  EXPECT_EQ(out[0].status, pathing::PathStatus::Found);
  EXPECT_EQ(service.metrics().requests, 3u);
  EXPECT_EQ(service.metrics().searches, 2u);
}

// A jammed unit's detour (PathRequest::detour): planned by AA* inside its region around the
// footprints to avoid, back onto the rest of its path, and on along it; the cache is neither
// read nor written. Where the region holds no way around, the request is planned as any other.
TEST(PathService, ADetourGoesAroundWhatStandsOnThePathAndOnAlongIt) {
  // A wall across x = 20 with a 2-cell gap at rows 10-11 (the only way) and open ground
  // elsewhere.
  pathing::GridMap map(40, 24);
  for (int y = 0; y < 24; ++y) {
    if (y != 10 && y != 11) map.set({20, y}, Terrain::Blocked);
  }
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(std::move(map));
  PathServiceSettings settings;
  settings.algorithm = pathing::Algorithm::HaaHigh;
  const pathing::Agent agent{1, pathing::Capability::of({Terrain::Ground})};
  PathService service(*grid, settings, {agent.capability}, 1);
  service.request({{0, 0}, 1, agent, {2, 4}, {37, 4}});
  std::vector<PathDelivery> out;
  service.serve(out);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].status, pathing::PathStatus::Found);
  const SharedPath path = out[0].path;
  // Something stands on the path at (10, 7)-(11, 8); a way around it inside the region.
  const auto onPath = [&](const SharedPath& p, pathing::CellRect r) {
    return std::any_of(p->cells.begin(), p->cells.end(), [&](pathing::Cell c) {
      return c.x >= r.x && c.x < r.x + r.width && c.y >= r.y && c.y < r.y + r.height;
    });
  };
  std::size_t blocked = 0;
  while (blocked < path->cells.size() &&
         !(path->cells[blocked].x >= 10 && path->cells[blocked].y >= 7))
    ++blocked;
  ASSERT_LT(blocked, path->cells.size());
  const pathing::CellRect standing{path->cells[blocked].x, path->cells[blocked].y, 2, 2};
  auto detour = std::make_shared<Detour>();
  detour->avoid = {standing};
  detour->rest = path;
  detour->rejoin = static_cast<std::uint32_t>(blocked + 4);
  detour->region = {0, 0, 20, 24};
  const std::uint64_t searches = service.metrics().searches;
  service.request({{0, 0}, 2, agent, {2, 4}, {37, 4}, -1, 0.0, detour});
  out.clear();
  service.serve(out);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].status, pathing::PathStatus::Found);
  EXPECT_FALSE(onPath(out[0].path, standing));
  EXPECT_TRUE(onPath(path, standing));
  EXPECT_EQ(pathing::findIllegalStep(*grid, agent, out[0].path->cells), "");
  EXPECT_EQ(out[0].path->cells.back(), (pathing::Cell{37, 4}));
  // On along the rest: its last cells are the old path's.
  EXPECT_TRUE(std::equal(path->cells.end() - 10, path->cells.end(), out[0].path->cells.end() - 10));
  // No cell twice: a way around that meets the rest beyond its rejoin cell joins it there.
  std::set<std::pair<int, int>> seen;
  for (const pathing::Cell& c : out[0].path->cells)
    EXPECT_TRUE(seen.insert({c.x, c.y}).second) << c.x << "," << c.y;
  EXPECT_EQ(service.metrics().detours, 1u);
  EXPECT_EQ(service.metrics().searches, searches + 1);
  EXPECT_EQ(service.metrics().cacheHits, 0u);
  // Sent beyond the wall through a region that leaves out the gap: no way inside it, so the
  // request is planned as any (here from the cache, through the gap).
  detour = std::make_shared<Detour>(*detour);
  detour->rejoin = static_cast<std::uint32_t>(path->cells.size() - 1);
  detour->region = {0, 0, 40, 8};
  service.request({{0, 0}, 3, agent, {2, 4}, {37, 4}, -1, 0.0, detour});
  out.clear();
  service.serve(out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].path, path);  // the cached answer
  EXPECT_EQ(service.metrics().detours, 1u);
}

// A way around the far end of a wall that the path runs along meets the rest of the path
// beyond the cell it was sent to: it joins the rest there instead of doubling back.
TEST(PathService, ADetourJoinsTheRestWhereItFirstMeetsIt) {
  pathing::GridMap map(40, 12);
  for (int x = 10; x < 26; ++x) {
    map.set({x, 5}, Terrain::Blocked);
    map.set({x, 6}, Terrain::Blocked);
  }
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(std::move(map));
  PathServiceSettings settings;
  settings.algorithm = pathing::Algorithm::AStar;
  const pathing::Agent agent{1, pathing::Capability::of({Terrain::Ground})};
  PathService service(*grid, settings, {agent.capability}, 1);
  std::vector<pathing::Cell> straight;
  for (int x = 2; x <= 37; ++x)
    straight.push_back({x, 8});
  auto detour = std::make_shared<Detour>();
  detour->rest = std::make_shared<const PlannedPath>(planned(straight));
  detour->avoid = {{14, 7, 3, 5}};  // across the road below the wall
  detour->rejoin = 16;              // (18, 8), just past them
  detour->region = {0, 0, 40, 12};
  service.request({{0, 0}, 1, agent, {2, 8}, {37, 8}, -1, 0.0, detour});
  std::vector<PathDelivery> out;
  service.serve(out);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].status, pathing::PathStatus::Found);
  const std::vector<pathing::Cell>& cells = out[0].path->cells;
  EXPECT_EQ(pathing::findIllegalStep(*grid, agent, cells), "");
  EXPECT_EQ(cells.back(), (pathing::Cell{37, 8}));
  // Over the wall and down past its east end, then east along the road: never back west to
  // (18, 8).
  EXPECT_TRUE(std::none_of(cells.begin(), cells.end(),
                           [](pathing::Cell c) { return c.y == 8 && c.x >= 13 && c.x <= 24; }));
  std::set<std::pair<int, int>> seen;
  for (const pathing::Cell& c : cells)
    EXPECT_TRUE(seen.insert({c.x, c.y}).second) << c.x << "," << c.y;
}

// Under terrain costs each distinct profile gets one planner (a weighted graph for HAA*),
// built when first asked: profiles that differ only on terrains the map lacks share it.
TEST(PathService, CostProfilesEqualOnTheMapShareAPlanner) {
  pathing::GridMap map(48, 32);
  for (int y = 0; y < 24; ++y) {
    for (int x = 16; x < 32; ++x)
      map.set({x, y}, Terrain::Swamp);
  }
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(std::move(map));
  const pathing::Capability land = pathing::Capability::of({Terrain::Ground, Terrain::Swamp});
  const pathing::Capability amphibious =
      pathing::Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water});
  pathing::TerrainCosts wader;  // swamp barely slower than ground
  wader.perCell[static_cast<std::size_t>(Terrain::Ground)] = 0.5;
  wader.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 0.6;
  pathing::TerrainCosts swimmer = wader;  // the same, and swims: no water on this map
  swimmer.perCell[static_cast<std::size_t>(Terrain::Water)] = 1.0;
  pathing::TerrainCosts shy = wader;  // swamp four times slower
  shy.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 2.0;
  PathServiceSettings settings;
  settings.algorithm = pathing::Algorithm::HaaHigh;
  settings.terrainCosts = true;
  PathService service(*grid, settings, {land, amphibious}, 1,
                      {{{1, land}, wader}, {{1, amphibious}, swimmer}, {{1, land}, shy}});
  EXPECT_EQ(service.distinctCostProfiles(), 2u);
  EXPECT_EQ(service.builtCostPlanners(), 0u);
  EXPECT_EQ(service.abstraction(), nullptr);  // no uniform graph under costs
  service.request({{0, 0}, 1, {1, land}, {2, 2}, {45, 2}, 0});
  service.request({{1, 0}, 1, {1, amphibious}, {2, 2}, {45, 2}, 1});
  std::vector<PathDelivery> out;
  service.serve(out);
  EXPECT_EQ(service.builtCostPlanners(), 1u);
  ASSERT_NE(service.abstraction(), nullptr);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].path->cells, out[1].path->cells);
  EXPECT_GT(out[0].seconds, 0.0);
  service.request({{2, 0}, 1, {1, land}, {2, 2}, {45, 2}, 2});
  service.serve(out);
  EXPECT_EQ(service.builtCostPlanners(), 2u);
  ASSERT_EQ(out.size(), 3u);
  // The wader crosses the swamp; the swamp-shy unit goes round it, longer and faster for it.
  EXPECT_GT(out[2].path->cells.size(), out[0].path->cells.size());
  for (const pathing::Cell& c : out[2].path->cells)
    EXPECT_EQ(grid->map().at(c), Terrain::Ground);
}

TEST(PathService, SettingsAreValidatedByTheConstructor) {
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(32, 32));
  const pathing::Capability ground = pathing::Capability::of({Terrain::Ground});
  EXPECT_EQ(problemWith(PathServiceSettings{}), "");
  const auto check = [&](PathServiceSettings settings, const std::string& message) {
    EXPECT_EQ(problemWith(settings), message);
    warpath::testing::expectRejected([&] { PathService service(*grid, settings, {ground}, 1); },
                                     message);
  };
  check({.clusterSize = 1}, "clusterSize must be 2..4096 (got 1)");
  check({.clusterSize = 4097}, "clusterSize must be 2..4096 (got 4097)");
  check({.expansionBudget = 0}, "expansionBudget must be >= 1 (got 0)");
  // Even for AA*, which builds no abstraction: the settings are wrong either way.
  check({.algorithm = pathing::Algorithm::AStar, .clusterSize = 0},
        "clusterSize must be 2..4096 (got 0)");
  // The abstraction's own limits surface from the same constructor.
  warpath::testing::expectRejected([&] { PathService service(*grid, {}, {ground}, 0); },
                                   "maxAgentSize must be 1..255 (got 0)");
  PathService usable(*grid, {.clusterSize = 2, .expansionBudget = 1}, {ground}, 1);
  EXPECT_EQ(usable.settings().clusterSize, 2);
}

TEST(World, AnUnreachableGoalIsReportedOnceAndNotRetried) {
  // Ordered straight into an enclosed pocket (the loader would refuse this as a goal).
  pathing::GridMap map(16, 8);
  for (int y = 0; y < 8; ++y)
    map.set({10, y}, Terrain::Blocked);
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(std::move(map));
  const units::UnitType infantry = groundInfantry();
  World world(grid, {infantry}, {});
  const UnitId id = world.spawn(0, 0, 0, {1, 1});
  world.orderMove({id}, {12, 2, 2, 2});
  const std::vector<Event> events = testing::stepKeepingEvents(world, 200);
  EXPECT_EQ(world.find(id)->state, UnitState::NoPath);
  const auto failures = std::count_if(
      events.begin(), events.end(), [](const Event& e) { return e.kind == EventKind::PathFailed; });
  EXPECT_EQ(failures, 1);
  EXPECT_LE(world.pathService().metrics().requests, 1u);
  EXPECT_EQ(world.find({id.index, id.generation + 1}), nullptr);  // a stale handle
}

TEST(World, UnitsMeetingHeadOnInACorridorPushPast) {
  // Two teams for the two directions, not a fight: weapons stay silent.
  const Scenario s = load(
      "catalogue: ../assets/units.yaml\nteams: [blue, red]\nduration: 40\n"
      "combat: {enabled: false}\n"
      "map:\n  rows:\n"
      "    - '@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@'\n"
      "    - '..............................'\n"
      "    - '..............................'\n"
      "    - '..............................'\n"
      "    - '@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@'\n"
      "groups:\n"
      "  - {type: infantry, team: blue, count: 6, spawn: {x: 0, y: 1, w: 2, h: 3},"
      " goal: {x: 27, y: 1, w: 3, h: 3}}\n"
      "  - {type: infantry, team: red, count: 6, spawn: {x: 28, y: 1, w: 2, h: 3},"
      " goal: {x: 0, y: 1, w: 3, h: 3}}\n");
  ScenarioRun run(s);
  runChecked(run);
  for (const Unit& unit : run.world().units())
    EXPECT_GE(unit.arrivalTick, 0) << "unit " << unit.id.index;
}

TEST(World, NoUnitOfABundledScenarioEverOverlapsForbiddenTerrain) {
  for (const char* name : {"demo", "river_crossing", "forest", "narrow_pass", "swamp"}) {
    SCOPED_TRACE(name);
    Result<Scenario> s = loadScenario(testing::kScenariosDir + name + ".yaml");
    ASSERT_TRUE(s.ok()) << s.error().describe();
    ScenarioRun run(s.value());
    runChecked(run);
  }
}

TEST(World, AUnitThatCannotReachItsCellIsRepathedThenFlaggedStuck) {
  // Two units sent to a one-cell area: the first parks there and holds it, the second pushes
  // without progress.
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(12, 6));
  const units::UnitType infantry = groundInfantry();
  WorldSettings settings;
  settings.stuck.windowSeconds = 1.0;
  settings.stuck.flagAfter = 2;
  // Independent movement's rule (progress as displacement). With cooperation the second unit
  // does not park on the held cell either, but it is not flagged: docs/cooperative.md.
  settings.pathing.cooperative = false;
  World world(grid, {infantry}, settings);
  const UnitId first = world.spawn(0, 0, 0, {6, 2});
  const UnitId second = world.spawn(0, 0, 0, {1, 2});
  world.orderMove({first, second}, {9, 2, 1, 1});
  const std::vector<Event> events = testing::stepKeepingEvents(world, 30 * 12);
  EXPECT_EQ(world.find(first)->state, UnitState::Parked);
  EXPECT_FALSE(world.find(first)->everStuck);
  EXPECT_TRUE(world.find(second)->everStuck);
  EXPECT_GE(world.find(second)->repaths, 2);
  const auto flagged = std::count_if(events.begin(), events.end(), [&](const Event& e) {
    return e.kind == EventKind::StuckFlagged && e.unit == second;
  });
  EXPECT_GE(flagged, 1);
  // The parked unit was shoved but holds its cell.
  EXPECT_LT((world.find(first)->position - units::anchorToCentre({9, 2}, 1)).length(), 0.6);
}

TEST(World, AUnitWhoseGoalAreaIsFullTakesACellOnceOneIsFreed) {
  // Three units sent to a two-cell area: the last finds no free cell (the rules then remember
  // the area as full for it and do not scan it again while nothing changes). Once a parked unit
  // is sent elsewhere its cell is free again, and the last one (whose goal cell was the other
  // one's) takes it.
  auto grid = std::make_shared<const pathing::AnnotatedGrid>(pathing::GridMap(14, 8));
  const units::UnitType infantry = groundInfantry();
  World world(grid, {infantry}, {});
  const UnitId a = world.spawn(0, 0, 0, {6, 2});
  const UnitId b = world.spawn(0, 0, 0, {6, 3});
  const UnitId c = world.spawn(0, 0, 0, {1, 5});
  world.orderMove({a, b, c}, {10, 3, 2, 1});
  testing::stepKeepingEvents(world, 20 * 12);
  ASSERT_EQ(world.find(a)->state, UnitState::Parked);
  ASSERT_EQ(world.find(b)->state, UnitState::Parked);
  ASSERT_NE(world.find(c)->state, UnitState::Parked);
  world.orderMove({b}, {13, 7, 1, 1});
  testing::stepKeepingEvents(world, 20 * 12);
  EXPECT_EQ(world.find(b)->state, UnitState::Parked);
  ASSERT_EQ(world.find(c)->state, UnitState::Parked);
  EXPECT_EQ(world.find(c)->goalCell, (Cell{11, 3}));  // b's, not a's
}

// Those whose goal cell another parked on first, inside the area and with no other cell free
// for them, park where they stand (replay format 15); before, with cooperation, they pushed into
// the parked crowd to the end.
TEST(World, UnitsInAFullGoalAreaParkWhereTheyStand) {
  for (const bool park : {true, false}) {
    SCOPED_TRACE(park ? "parking where they stand" : "format 14's rule");
    Result<Scenario> loaded =
        loadScenario(std::string(WARPATH_SOURCE_DIR) + "/tests/fixtures/full_goal_area.yaml");
    ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
    Scenario s = std::move(loaded).value();
    ASSERT_TRUE(s.settings.pathing.cooperative && s.settings.pathing.parkWhenAreaFull);
    s.settings.pathing.parkWhenAreaFull = park;
    ScenarioRun run(s);
    while (!run.done())
      run.step();
    const auto parked = std::count_if(run.world().units().begin(), run.world().units().end(),
                                      [](const Unit& u) { return u.state == UnitState::Parked; });
    if (park) {
      EXPECT_EQ(parked, 12);
      for (const Unit& u : run.world().units())
        EXPECT_TRUE(pathing::CellRect({14, 3, 3, 3}).contains(u.goalCell)) << u.id.index;
    } else {
      EXPECT_LT(parked, 12);  // the rest push on
    }
  }
}
}  // namespace
}  // namespace warpath::engine
