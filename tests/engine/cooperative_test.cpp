// Cooperative movement in the world (docs/cooperative.md): units reserve windows of space-time
// and keep to them, give way in passages too narrow to pass, and the movement rules of this
// release (turning circle, pushing, holding, stuck along the path) hold.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "engine/state_description.h"

namespace warpath::engine {
namespace {

Scenario parse(const std::string& text) {
  Result<Scenario> r =
      parseScenario(text, std::string(WARPATH_SOURCE_DIR) + "/scenarios/inline.yaml");
  EXPECT_TRUE(r.ok()) << r.error().describe();
  return std::move(r).value();
}

Report runToEnd(const Scenario& s, std::uint64_t seed) {
  ScenarioRun run(s, seed);
  while (!run.done())
    run.step();
  return run.report();
}

// A 1-cell door in a wall, two infantry on each side swapping sides.
const std::string kDoor =
    "map: {rows: ['..........', '..........', '..........', '..........', '@@@@.@@@@@',\n"
    "             '..........', '..........', '..........', '..........']}\n"
    "catalogue: ../assets/units.yaml\n"
    "duration: 40\n"
    "combat: {enabled: false}\n"
    "teams: [blue, red]\n"
    "groups:\n"
    "  - {name: north, team: blue, type: infantry, count: 3, spawn: {x: 2, y: 0, w: 6, h: 2},\n"
    "     goal: {x: 2, y: 7, w: 6, h: 2}}\n"
    "  - {name: south, team: red, type: infantry, count: 3, spawn: {x: 2, y: 7, w: 6, h: 2},\n"
    "     goal: {x: 2, y: 0, w: 6, h: 2}}\n"
    "expectations:\n"
    "  - arrival_rate: {team: blue, type: infantry, at_least: 1.0, by: 40}\n"
    "  - arrival_rate: {team: red, type: infantry, at_least: 1.0, by: 40}\n"
    "  - max_stuck: 0\n";

std::string withPathing(const std::string& text, const std::string& pathing) {
  return text + "pathing: " + pathing + "\n";
}

TEST(Cooperative, SettingsComeFromTheScenario) {
  const Scenario on = parse(kDoor);
  EXPECT_TRUE(on.settings.pathing.cooperative);  // on by default
  EXPECT_EQ(on.settings.pathing.window, 16);
  const Scenario off = parse(withPathing(kDoor, "{cooperative: false, window: 8}"));
  EXPECT_FALSE(off.settings.pathing.cooperative);
  EXPECT_EQ(off.settings.pathing.window, 8);
  const Result<Scenario> bad =
      parseScenario(withPathing(kDoor, "{window: 0}"),
                    std::string(WARPATH_SOURCE_DIR) + "/scenarios/inline.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().describe().find("window"), std::string::npos) << bad.error().describe();
}

TEST(Cooperative, SwapsThroughADoorAtEverySeed) {
  const Scenario s = parse(kDoor);
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Report r = runToEnd(s, seed);
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_TRUE(r.stuckUnits.empty()) << "seed " << seed;
    EXPECT_TRUE(r.movement.cooperative);
    EXPECT_GT(r.movement.counters.windows, 0);
    // Someone had to let the other side through.
    EXPECT_GT(r.movement.counters.waits + r.movement.counters.giveWays, 0) << "seed " << seed;
  }
}

TEST(Cooperative, ReservationsNeverOverlapAtTheCurrentTick) {
  // The windows units follow are conflict-free: no cell is held by two units' plans over the
  // same tick (a unit that found no safe window holds only its own cell).
  const Scenario s = parse(kDoor);
  ScenarioRun run(s, 2);
  int checked = 0;
  while (!run.done()) {
    run.step();
    const WorldState& state = run.world().state();
    const std::vector<Unit>& units = state.units;
    const pathing::Tick now = state.tick;
    for (const Unit& a : units) {
      if (!a.plan || a.plan->status == pathing::CooperativeStatus::Blocked) continue;
      for (const pathing::TimedCell& step : a.plan->steps) {
        if (step.tick < now) continue;
        const int size = run.world().catalogue()[static_cast<std::size_t>(a.type)].size;
        const std::optional<std::uint32_t> other =
            state.reservations->blocker(step.cell, size, step.tick, step.tick + 1, a.id.index);
        if (other) {
          const Unit& b = units[*other];
          // Only a unit with no safe window may overlap another's reservation.
          EXPECT_TRUE(b.plan == nullptr || b.plan->status == pathing::CooperativeStatus::Blocked)
              << "tick " << now << ": units " << a.id.index << " and " << b.id.index
              << " both reserved " << step.cell.x << "," << step.cell.y << " at " << step.tick;
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(Cooperative, IsDeterministicAndHashesItsState) {
  const Scenario s = parse(kDoor);
  const Report a = runToEnd(s, 3);
  const Report b = runToEnd(s, 3);
  EXPECT_EQ(a.stateHash, b.stateHash);
  EXPECT_EQ(a, b);
  const Report off = runToEnd(parse(withPathing(kDoor, "{cooperative: false}")), 3);
  EXPECT_NE(a.stateHash, off.stateHash);
  EXPECT_FALSE(off.movement.cooperative);
  EXPECT_EQ(off.movement.counters.windows, 0);
}

TEST(Cooperative, ReportsDelayAgainstThePlannedTime) {
  const Report r = runToEnd(parse(kDoor), 1);
  ASSERT_FALSE(r.movement.delay.empty());
  for (const DelayStats& d : r.movement.delay) {
    if (d.arrived == 0) continue;
    EXPECT_GT(d.p50, 0.3) << d.team;  // arriving inside the area can beat the goal cell's time
    EXPECT_LE(d.p50, d.p90);
    EXPECT_LE(d.p90, d.max);
  }
}

// Two tanks head-on in a corridor 4 cells wide: they cannot pass each other inside it.
const std::string kCorridor =
    "map: {rows: ['....................................',\n"
    "             '....................................',\n"
    "             '....................................',\n"
    "             '....................................',\n"
    "             '......@@@@@@@@@@@@@@@@@@@@@@@@......',\n"
    "             '....................................',\n"
    "             '....................................',\n"
    "             '....................................',\n"
    "             '....................................',\n"
    "             '......@@@@@@@@@@@@@@@@@@@@@@@@......',\n"
    "             '....................................',\n"
    "             '....................................',\n"
    "             '....................................',\n"
    "             '....................................']}\n"
    "catalogue: ../assets/units.yaml\n"
    "duration: 90\n"
    "combat: {enabled: false}\n"
    "teams: [blue, red]\n"
    "groups:\n"
    "  - {name: west, team: blue, type: tank, count: 1, spawn: {x: 0, y: 5, w: 3, h: 3},\n"
    "     goal: {x: 33, y: 5, w: 3, h: 4}}\n"
    "  - {name: east, team: red, type: tank, count: 1, spawn: {x: 33, y: 5, w: 3, h: 3},\n"
    "     goal: {x: 0, y: 5, w: 3, h: 4}}\n"
    "expectations:\n"
    "  - arrival_rate: {team: blue, type: tank, at_least: 1.0, by: 90}\n"
    "  - arrival_rate: {team: red, type: tank, at_least: 1.0, by: 90}\n"
    "  - max_stuck: 0\n";

TEST(Cooperative, TanksHeadOnInACorridorBothGetThrough) {
  const Scenario s = parse(kCorridor);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Report r = runToEnd(s, seed);
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.movement.counters.deadlocksBroken, 0) << "seed " << seed;
  }
}

// A unit that holds its position is not driven through: a tank ordered through it goes around.
TEST(MovementRules, HoldingUnitsAreNotDrivenThrough) {
  const Scenario s = parse(
      "map: {rows: ['....................', '....................', '....................',\n"
      "             '....................', '....................', '....................',\n"
      "             '....................', '....................']}\n"
      "catalogue: ../assets/units.yaml\n"
      "duration: 20\n"
      "combat: {enabled: false}\n"
      "pathing: {cooperative: false}\n"
      "teams: [blue, red]\n"
      "groups:\n"
      "  - {name: guard, team: red, type: infantry, count: 1, spawn: {x: 10, y: 4, w: 1, h: 1}}\n"
      "  - {name: tank, team: blue, type: tank, count: 1, spawn: {x: 0, y: 3, w: 3, h: 3},\n"
      "     goal: {x: 17, y: 3, w: 3, h: 3}}\n"
      "orders:\n"
      "  - {at: 0, group: guard, order: hold}\n");
  ScenarioRun run(s, 1);
  const Unit* guard = nullptr;
  for (const Unit& u : run.world().units())
    if (u.group == 0) guard = &u;
  ASSERT_NE(guard, nullptr);
  const units::Vec2 start = guard->position;
  double furthest = 0.0;
  while (!run.done()) {
    run.step();
    furthest = std::max(furthest, (run.world().units()[guard->id.index].position - start).length());
  }
  EXPECT_LT(furthest, 0.5);
}

}  // namespace
}  // namespace warpath::engine
