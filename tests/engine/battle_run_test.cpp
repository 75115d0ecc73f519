// Battles run by ScenarioRun: each trigger kind fires on the tick its condition first holds,
// reinforcements come in, end_battle stops the run, each victory condition decides the winner,
// battle statistics add up (a duel worked out by hand), outcome expectations pass and fail
// when they should, script playback reproduces a live run, and battles are deterministic.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "support/battle_field.h"
#include "support/run_out.h"
#include "support/scenario_files.h"

namespace warpath::engine {
namespace {

const std::string kBattleRunFile =
    std::string(WARPATH_SOURCE_DIR) + "/scenarios/battle_run_test.yaml";

// The open field with the riflemen and an unarmed `truck`; `rest` holds the groups onwards.
std::string field(const std::string& rest, double duration = 20) {
  return warpath::testing::openFieldMap() + "unit_types:\n" + warpath::testing::kRiflemenTypes +
         "  truck: {size: 1, capability: [ground], speed: 3}\n"
         "duration: " +
         std::to_string(duration) + "\nteams: [blue, red]\n" + rest;
}

Scenario loadBattleRun(const std::string& text) {
  return testing::parsedScenario(text, kBattleRunFile);
}

using testing::runOut;

const BattleStats* statsOf(const Report& r, const std::string& team, const std::string& type) {
  for (const BattleStats& s : r.battle) {
    if (s.team == team && s.type == type) return &s;
  }
  return nullptr;
}

std::string idsText(const std::vector<UnitId>& ids) {
  std::string t;
  for (UnitId id : ids)
    t += (t.empty() ? "" : ",") + std::to_string(id.index) + "." + std::to_string(id.generation);
  return t;
}

// An issued entry as text, to compare whole entries with a readable failure (Command has no
// usable operator== while CellRect has none).
std::string describe(const IssuedOrder& o) {
  const pathing::CellRect& a = o.command.area;
  return "tick " + std::to_string(o.tick) + " kind " + std::to_string(static_cast<int>(o.kind)) +
         " group " + std::to_string(o.group) + " " + std::string(toString(o.command.kind)) +
         " units [" + idsText(o.command.units) + "] area " + std::to_string(a.x) + "," +
         std::to_string(a.y) + " " + std::to_string(a.width) + "x" + std::to_string(a.height) +
         " targets [" + idsText(o.command.targets) + "]";
}

std::vector<std::string> describe(const std::vector<IssuedOrder>& orders) {
  std::vector<std::string> out;
  for (const IssuedOrder& o : orders)
    out.push_back(describe(o));
  return out;
}

std::vector<UnitId> idsOf(const World& world, int group) {
  std::vector<UnitId> ids;
  for (const Unit& u : world.units()) {
    if (u.group == group) ids.push_back(u.id);
  }
  return ids;
}

// One blue vet against one red recruit, three cells apart, both idle (a Stop order fires at
// what is in range). Unit ids: the vet 0, the recruit 1; a red truck column (group 2) is a
// reinforcement that never comes.
const std::string kDuelGroups =
    "groups:\n"
    "  - {name: b, team: blue, type: vet, count: 1, spawn: {x: 5, y: 5, w: 1, h: 1}}\n"
    "  - {name: r, team: red, type: recruit, count: 1, spawn: {x: 8, y: 5, w: 1, h: 1}}\n"
    "  - {name: convoy, team: red, type: truck, count: 2, spawn: {x: 20, y: 0, w: 2, h: 2},\n"
    "     reinforcement: true}\n";

// Worked out by hand (docs/combat.md): a weapon is ready one cooldown (30 ticks) after spawning
// and both have found each other by then, so both fire at ticks 30, 60 and 90. All shots of a
// tick land after every unit fired: at tick 90 the vet's third hit kills the recruit (30 hp)
// and the recruit's third still hits the vet (40 - 30 = 10 hp left).
TEST(BattleRun, DuelStatisticsAndEliminationVictory) {
  const Scenario s =
      loadBattleRun(field(kDuelGroups + "victory:\n  - eliminate: blue\n  - eliminate: red\n"));
  ScenarioRun run(s);
  runOut(run);
  const Report r = run.report();
  const Unit& recruit = run.world().units()[1];
  ASSERT_FALSE(recruit.alive());
  EXPECT_EQ(recruit.deathTick, 90);
  EXPECT_EQ(recruit.killedBy, run.world().units()[0].id);
  // Eliminated: the red convoy never came, so red has no living unit.
  EXPECT_TRUE(run.done());
  EXPECT_TRUE(run.ended());
  EXPECT_EQ(r.winner, "blue");
  EXPECT_EQ(r.victory, s.victory[0].text);
  EXPECT_EQ(r.endTick, 91);  // judged on the state the killing step left
  EXPECT_EQ(r.ticks, 91);
  EXPECT_TRUE(r.complete);

  ASSERT_EQ(r.battle.size(), 2u);  // pairs with units only: the convoy never spawned
  const BattleStats* vet = statsOf(r, "blue", "vet");
  const BattleStats* rec = statsOf(r, "red", "recruit");
  ASSERT_TRUE(vet && rec);
  EXPECT_EQ(*vet, (BattleStats{"blue", "vet", 1, 1, 0, 1, 3, 3, 30, 30}));
  EXPECT_EQ(*rec, (BattleStats{"red", "recruit", 1, 0, 1, 0, 3, 3, 30, 30}));
  EXPECT_EQ(run.world().units()[0].hp, 10);

  // Nothing moves once the battle has ended.
  const std::uint64_t hash = run.world().stateHash();
  run.step();
  EXPECT_EQ(run.world().tick(), 91);
  EXPECT_EQ(run.world().stateHash(), hash);
}

TEST(BattleRun, WinnerAndStatExpectationsPassAndFail) {
  const Scenario s = loadBattleRun(
      field(kDuelGroups + "victory:\n  - eliminate: blue\n"
                          "expectations:\n"
                          "  - winner: blue\n"
                          "  - winner: red\n"
                          "  - winner: none\n"
                          "  - kills: {team: blue, at_least: 1}\n"
                          "  - losses: {team: red, at_most: 0}\n"
                          "  - shots_fired: {at_most: 6}\n"
                          "  - shots_fired: {team: blue, at_most: 2}\n"
                          "  - damage_dealt: {team: red, type: recruit, at_least: 30}\n"
                          "  - damage_taken: {type: vet, at_most: 29}\n"
                          "  - alive: {team: red, at_most: 0}\n"
                          "  - alive: {team: blue, at_least: 2}\n"));
  ScenarioRun run(s);
  runOut(run);
  const Report r = run.report();
  ASSERT_EQ(r.expectations.size(), 11u);
  const std::vector<std::pair<double, bool>> want = {
      {0, true},  {0, false}, {0, false},  {1, true}, {1, false}, {6, true},
      {3, false}, {30, true}, {30, false}, {0, true}, {1, false}};
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(r.expectations[i].actual, want[i].first) << r.expectations[i].text;
    EXPECT_EQ(r.expectations[i].pass, want[i].second) << r.expectations[i].text;
  }
  EXPECT_FALSE(r.passed());
}

TEST(BattleRun, NoWinnerWhenTimeRunsOut) {
  // Out of range of each other (gap 15 > 5): nobody fires, nobody wins.
  const Scenario s = loadBattleRun(
      field("groups:\n"
            "  - {name: b, team: blue, type: vet, count: 1, spawn: {x: 1, y: 5, w: 1, h: 1}}\n"
            "  - {name: r, team: red, type: recruit, count: 1, spawn: {x: 17, y: 5, w: 1, h: 1}}\n"
            "victory:\n  - eliminate: blue\n"
            "expectations:\n  - winner: none\n  - winner: blue\n",
            2));
  ScenarioRun run(s);
  runOut(run);
  const Report r = run.report();
  EXPECT_FALSE(run.ended());
  EXPECT_EQ(r.ticks, 60);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.winner, "");
  EXPECT_EQ(r.victory, "");
  EXPECT_EQ(r.endTick, -1);
  EXPECT_EQ(r.expectations[0].actual, -1);
  EXPECT_TRUE(r.expectations[0].pass);
  EXPECT_FALSE(r.expectations[1].pass);
  EXPECT_EQ(statsOf(r, "blue", "vet")->shotsFired, 0);
}

// team_below and dies fire on the state the recruit's death left; their actions run in order;
// an order names only the living; end_battle ends the run with its winner, whatever happened.
TEST(BattleRun, DeathTriggersOrdersAndEndBattle) {
  const Scenario s =
      loadBattleRun(field(kDuelGroups + "triggers:\n"
                                        "  - name: red broken\n"
                                        "    when: {team_below: {team: red, count: 1}}\n"
                                        "    do: [{order: hold, group: [b, r]}]\n"
                                        "  - name: recruit down\n"
                                        "    when: {dies: {group: r}}\n"
                                        "    do: [{end_battle: red}, {order: stop, group: b}]\n"
                                        "  - name: never\n"
                                        "    when: {at: 1000}\n"
                                        "    do: [{end_battle: none}]\n"));
  ScenarioRun run(s);
  runOut(run);
  const Report r = run.report();
  EXPECT_EQ(r.triggersFired, (std::vector<std::string>{"red broken", "recruit down"}));
  EXPECT_EQ(r.winner, "red");
  EXPECT_EQ(r.victory, "end_battle by trigger recruit down");
  EXPECT_EQ(r.endTick, 91);
  EXPECT_EQ(run.world().tick(), 91);
  const std::vector<IssuedOrder>& issued = run.issued();
  ASSERT_EQ(issued.size(), 2u);  // nothing after the end: the stop order is not given
  EXPECT_EQ(issued[0].tick, 91);
  EXPECT_EQ(issued[0].kind, IssuedKind::Order);
  EXPECT_EQ(issued[0].command.kind, OrderKind::Hold);
  EXPECT_EQ(issued[0].command.units, std::vector<UnitId>{run.world().units()[0].id});
  EXPECT_EQ(describe(issued[1]), describe(IssuedOrder{91, IssuedKind::EndBattle, {}, 1}));
}

// A victory judged on the same state comes before the triggers.
TEST(BattleRun, AVictoryComesBeforeAnEndBattleOnTheSameTick) {
  const Scenario s = loadBattleRun(
      field(kDuelGroups + "triggers:\n"
                          "  - {name: down, when: {dies: {group: r}}, do: [{end_battle: "
                          "red}]}\n"
                          "victory:\n  - eliminate: blue\n"));
  ScenarioRun run(s);
  runOut(run);
  const Report r = run.report();
  EXPECT_EQ(r.winner, "blue");
  EXPECT_EQ(r.endTick, 91);
  EXPECT_TRUE(r.triggersFired.empty());
}

TEST(BattleRun, AttackOrdersNameTheLivingTargets) {
  const Scenario s = loadBattleRun(
      field(kDuelGroups + "orders:\n"
                          "  - {at: 0, group: b, order: attack, target: r}\n"
                          "  - {at: 0, group: r, order: attack_move, move_to: {x: 0, y: 0, "
                          "w: 3, h: 3}}\n"));
  ScenarioRun run(s);  // tick-0 triggers fire at construction
  const std::vector<IssuedOrder>& issued = run.issued();
  ASSERT_EQ(issued.size(), 2u);
  EXPECT_EQ(issued[0].tick, 0);
  EXPECT_EQ(issued[0].command.kind, OrderKind::Attack);
  EXPECT_EQ(issued[0].command.units, std::vector<UnitId>{run.world().units()[0].id});
  EXPECT_EQ(issued[0].command.targets, std::vector<UnitId>{run.world().units()[1].id});
  EXPECT_EQ(issued[1].command.kind, OrderKind::AttackMove);
  EXPECT_EQ(issued[1].command.area.width, 3);
  EXPECT_TRUE(issued[1].command.targets.empty());
  EXPECT_EQ(run.report().triggersFired, (std::vector<std::string>{"order 1", "order 2"}));
}

// Unarmed trucks: a timed trigger, a reinforcement with a goal, arrival and area triggers.
const std::string kConvoy =
    "groups:\n"
    "  - {name: b, team: blue, type: truck, count: 3, spawn: {x: 0, y: 4, w: 2, h: 3},\n"
    "     goal: {x: 20, y: 4, w: 4, h: 4}}\n"
    "  - {name: r, team: red, type: truck, count: 2, spawn: {x: 22, y: 0, w: 2, h: 1},\n"
    "     goal: {x: 0, y: 10, w: 4, h: 2}, reinforcement: true}\n";

TEST(BattleRun, TimedReinforcementSpawnsAndMoves) {
  const Scenario s = loadBattleRun(
      field(kConvoy + "triggers:\n"
                      "  - {name: help, when: {at: 1}, do: [{reinforce: r}]}\n"
                      "  - {name: halt, when: {at: 2}, do: [{order: stop, group: r}]}\n"));
  ScenarioRun run(s);
  EXPECT_EQ(run.world().units().size(), 3u);
  while (run.world().tick() < 29) {
    run.step();
    EXPECT_EQ(run.world().units().size(), 3u);
  }
  run.step();  // tick 30 = 1 s
  ASSERT_EQ(run.world().units().size(), 5u);
  EXPECT_EQ(run.report().triggersFired, std::vector<std::string>{"help"});
  const std::vector<UnitId> red = idsOf(run.world(), 1);
  ASSERT_EQ(red.size(), 2u);
  EXPECT_EQ(red[0].index, 3u);
  for (UnitId id : red) {
    const Unit* u = run.world().find(id);
    EXPECT_EQ(u->team, 1);
    EXPECT_TRUE(s.groups[1].spawn.contains(units::centreToAnchor(u->position, 1)));
  }
  std::vector<IssuedOrder> issued = run.issued();
  ASSERT_EQ(issued.size(), 3u);
  EXPECT_EQ(issued[0].tick, 0);  // b's goal
  EXPECT_EQ(describe(issued[1]), describe(IssuedOrder{30, IssuedKind::Reinforce, {}, 1}));
  EXPECT_EQ(describe(issued[2]),
            describe(IssuedOrder{30, IssuedKind::Order,
                                 Command{OrderKind::Move, red, *s.groups[1].goal, {}}, -1}));
  while (run.world().tick() < 60)
    run.step();
  ASSERT_EQ(run.issued().size(), 4u);
  EXPECT_EQ(run.issued()[3].tick, 60);
  EXPECT_EQ(run.issued()[3].command.kind, OrderKind::Stop);
  EXPECT_EQ(run.issued()[3].command.units, red);
  // The reinforcements were moving towards their goal before the stop.
  EXPECT_GE(run.world().find(red[0])->orderTick, 30);
}

TEST(BattleRun, ArrivalAndAreaTriggersFireOnTheTickTheirConditionFirstHolds) {
  const pathing::CellRect strip{10, 0, 3, 12};
  const Scenario s = loadBattleRun(
      field(kConvoy + "triggers:\n"
                      "  - name: crossed\n"
                      "    when: {enters: {group: b, area: {x: 10, y: 0, w: 3, h: 12},"
                      " count: 2}}\n"
                      "    do: [{reinforce: r}]\n"
                      "  - name: there\n"
                      "    when: {arrived: {group: b, fraction: 1}}\n"
                      "    do: [{end_battle: blue}]\n"));
  ScenarioRun run(s);
  std::int64_t crossed = -1;
  while (!run.done()) {
    run.step();
    int inside = 0;
    for (UnitId id : idsOf(run.world(), 0)) {
      const Unit* u = run.world().find(id);
      inside += strip.contains(units::centreToAnchor(u->position, 1)) ? 1 : 0;
    }
    const bool fired = !run.report().triggersFired.empty();
    if (crossed < 0 && inside >= 2) crossed = run.world().tick();
    EXPECT_EQ(fired, crossed >= 0) << "tick " << run.world().tick();
  }
  ASSERT_GT(crossed, 0);
  const std::vector<IssuedOrder>& issued = run.issued();
  ASSERT_EQ(issued.size(), 4u);
  EXPECT_EQ(issued[1].kind, IssuedKind::Reinforce);
  EXPECT_EQ(issued[1].tick, crossed);
  // The end: the tick the last of b arrived.
  std::int64_t last = 0;
  for (UnitId id : idsOf(run.world(), 0))
    last = std::max(last, run.world().find(id)->arrivalTick);
  const Report r = run.report();
  EXPECT_EQ(r.triggersFired, (std::vector<std::string>{"crossed", "there"}));
  EXPECT_EQ(describe(issued[3]), describe(IssuedOrder{last, IssuedKind::EndBattle, {}, 0}));
  EXPECT_EQ(r.endTick, last);
  EXPECT_EQ(r.winner, "blue");
  EXPECT_LT(r.ticks, s.durationTicks());
}

TEST(BattleRun, ExitVictoryCountsEachUnitOnce) {
  const Scenario s = loadBattleRun(
      field(kConvoy + "victory:\n  - exit: {team: blue, area: {x: 20, y: 4, w: 4, h: 4},"
                      " count: 2}\n"));
  ScenarioRun run(s);
  runOut(run);
  std::vector<std::int64_t> arrivals;
  for (UnitId id : idsOf(run.world(), 0)) {
    if (run.world().find(id)->arrivalTick >= 0)
      arrivals.push_back(run.world().find(id)->arrivalTick);
  }
  std::sort(arrivals.begin(), arrivals.end());
  ASSERT_GE(arrivals.size(), 2u);
  const Report r = run.report();
  EXPECT_EQ(r.winner, "blue");
  EXPECT_EQ(r.victory, s.victory[0].text);
  ASSERT_GT(arrivals[1], 0);
  EXPECT_EQ(r.endTick, arrivals[1]);  // the goal is the exit: arrival is exit
}

TEST(BattleRun, HoldVictoryNeedsTheAreaAloneForItsWholeTime) {
  const std::string hold =
      "victory:\n  - hold: {team: blue, area: {x: 20, y: 4, w: 4, h: 4}, seconds: 2}\n";
  {
    const Scenario s = loadBattleRun(field(kConvoy + hold));
    ScenarioRun run(s);
    runOut(run);
    std::int64_t first = s.durationTicks();
    for (UnitId id : idsOf(run.world(), 0)) {
      if (run.world().find(id)->arrivalTick >= 0)
        first = std::min(first, run.world().find(id)->arrivalTick);
    }
    const Report r = run.report();
    EXPECT_EQ(r.winner, "blue");
    EXPECT_EQ(r.endTick, first + 60);
  }
  {
    // A red truck parked in the corner of the area contests it to the end.
    const Scenario s = loadBattleRun(field(
        "groups:\n"
        "  - {name: b, team: blue, type: truck, count: 3, spawn: {x: 0, y: 4, w: 2, h: 3},\n"
        "     goal: {x: 20, y: 4, w: 4, h: 4}}\n"
        "  - {name: r, team: red, type: truck, count: 1, spawn: {x: 23, y: 7, w: 1, h: 1}}\n" +
        hold + "expectations:\n  - winner: none\n"));
    ScenarioRun run(s);
    runOut(run);
    const Report r = run.report();
    EXPECT_EQ(r.winner, "");
    EXPECT_EQ(r.ticks, s.durationTicks());
    EXPECT_TRUE(r.passed());
  }
}

// A skirmish of four recruits a side, each attack-moving through the other's start; two red
// vets come in when red is down to two (tick 224), and red wins at tick 272. `triggers` are
// added to the scenario's.
std::string skirmish(const std::string& triggers = "") {
  return warpath::testing::skirmishForces(triggers);
}

TEST(BattleRun, SkirmishIsDeterministicAndItsStatisticsAddUp) {
  const Scenario s = loadBattleRun(field(skirmish(), 60));
  ScenarioRun a(s);
  runOut(a);
  ScenarioRun b(s);
  runOut(b);
  const Report ra = a.report();
  EXPECT_EQ(ra, b.report());
  EXPECT_EQ(a.world().stateHash(), b.world().stateHash());
  EXPECT_EQ(describe(a.issued()), describe(b.issued()));

  int kills = 0, losses = 0, dealt = 0, taken = 0, shots = 0, hits = 0, units = 0;
  for (const BattleStats& st : ra.battle) {
    kills += st.kills;
    losses += st.losses;
    dealt += st.damageDealt;
    taken += st.damageTaken;
    shots += st.shotsFired;
    hits += st.hits;
    units += st.units;
    EXPECT_EQ(st.units, st.alive + st.losses) << st.team << " " << st.type;
  }
  EXPECT_GT(losses, 0);
  EXPECT_EQ(kills, losses);  // every death is somebody's kill
  EXPECT_EQ(dealt, taken);
  EXPECT_LE(hits, shots);
  EXPECT_GT(shots, 0);
  EXPECT_EQ(static_cast<std::size_t>(units), a.world().units().size());
}

// Playing a live run's issued entries back (ScenarioRun's script mode) gives the same world:
// orders of every kind, a reinforcement, and the end.
TEST(BattleRun, ScriptPlaybackReproducesTheLiveRun) {
  const Scenario s = loadBattleRun(
      field(skirmish("  - {name: stop, when: {at: 8}, do: [{end_battle: none}]}\n"), 60));
  ScenarioRun live(s);
  std::vector<std::uint64_t> hashes;
  while (!live.done()) {
    live.step();
    hashes.push_back(live.world().stateHash());
  }
  const bool reinforced =
      std::any_of(live.issued().begin(), live.issued().end(),
                  [](const IssuedOrder& o) { return o.kind == IssuedKind::Reinforce; });
  EXPECT_TRUE(reinforced);
  ScenarioRun played(s, std::nullopt, live.issued());
  std::size_t i = 0;
  while (!played.done()) {
    played.step();
    ASSERT_LT(i, hashes.size());
    ASSERT_EQ(played.world().stateHash(), hashes[i]) << "tick " << played.world().tick();
    ++i;
  }
  EXPECT_EQ(i, hashes.size());
  EXPECT_EQ(describe(played.issued()), describe(live.issued()));
  const Report rl = live.report();
  const Report rp = played.report();
  EXPECT_EQ(rp.winner, rl.winner);
  EXPECT_EQ(rp.endTick, rl.endTick);
  EXPECT_EQ(rp.battle, rl.battle);
  EXPECT_TRUE(rp.triggersFired.empty());  // playback never evaluates a trigger
}

}  // namespace
}  // namespace warpath::engine
