// Every enum of the engine that is read from or shown to people names its values through one
// EnumNames table; the names parse back and the message lists come from the tables.

#include <gtest/gtest.h>

#include "engine/replay.h"
#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "engine/world.h"
#include "support/enum_round_trip.h"

namespace warpath::engine {
namespace {

TEST(EngineEnumNames, TablesRoundTrip) {
  testing::expectRoundTrip(
      kOrderKindNames, {OrderKind::Stop, OrderKind::Move, OrderKind::AttackMove, OrderKind::Attack,
                        OrderKind::Hold});
  testing::expectRoundTrip(
      kEventKindNames,
      {EventKind::Spawned, EventKind::Ordered, EventKind::PathFound, EventKind::PathFailed,
       EventKind::Arrived, EventKind::Parked, EventKind::Repath, EventKind::StuckFlagged,
       EventKind::Killed, EventKind::WreckCleared, EventKind::Pushed});
  // Stat expectations are keyed by their statistic, not by a name of their own.
  testing::expectRoundTrip(
      kExpectationKindNames,
      {ExpectationKind::ArrivalRate, ExpectationKind::ArrivalTime, ExpectationKind::MaxStuck,
       ExpectationKind::Winner, ExpectationKind::Delay, ExpectationKind::MaxWait,
       ExpectationKind::MaxDeadlocks});
  EXPECT_EQ(kExpectationKindNames.name(ExpectationKind::Stat), "?");
  testing::expectRoundTrip(kStatKindNames,
                           {StatKind::Kills, StatKind::Losses, StatKind::DamageDealt,
                            StatKind::DamageTaken, StatKind::ShotsFired, StatKind::Alive});
  testing::expectRoundTrip(kTriggerKindNames,
                           {TriggerKind::At, TriggerKind::Arrived, TriggerKind::TeamBelow,
                            TriggerKind::Enters, TriggerKind::Dies});
  testing::expectRoundTrip(kActionKindNames, {ActionKind::Order, ActionKind::Reinforce,
                                              ActionKind::EndBattle, ActionKind::SetTerrain});
  testing::expectRoundTrip(kVictoryKindNames,
                           {VictoryKind::Eliminate, VictoryKind::HoldArea, VictoryKind::Exit});
  testing::expectRoundTrip(kIssuedKindNames, {IssuedKind::Order, IssuedKind::Reinforce,
                                              IssuedKind::EndBattle, IssuedKind::SetTerrain});
  testing::expectRoundTrip(kReplayEndNames,
                           {ReplayEnd::Complete, ReplayEnd::Stopped, ReplayEnd::Interrupted});
}

// The named functions are the tables.
TEST(EngineEnumNames, FunctionsReadTheTables) {
  for (const auto& row : kOrderKindNames.rows()) {
    EXPECT_EQ(toString(row.value), row.name);
    EXPECT_EQ(orderKindFromName(row.name), row.value);
  }
  for (const auto& row : kEventKindNames.rows())
    EXPECT_EQ(toString(row.value), row.name);
  for (const auto& row : kStatKindNames.rows())
    EXPECT_EQ(toString(row.value), row.name);
  for (const auto& row : kReplayEndNames.rows())
    EXPECT_EQ(toString(row.value), row.name);
}

// A scenario's unknown names are answered with the table's list.
TEST(EngineEnumNames, ScenarioMessagesListTheTables) {
  const std::string head =
      "map: {rows: ['....', '....']}\n"
      "unit_types: {a: {size: 1, capability: [ground], speed: 1}}\n"
      "duration: 1\n"
      "teams: [blue]\n"
      "groups: [{name: g, team: blue, type: a, count: 1, spawn: {x: 0, y: 0, w: 1, h: 1}}]\n";
  const auto message = [&](const std::string& extra) {
    const Result<Scenario> r = parseScenario(head + extra, "enums.yaml");
    EXPECT_FALSE(r.ok()) << extra;
    return r.ok() ? std::string() : r.error().message;
  };
  EXPECT_EQ(message("pathing: {algo: dijkstra}\n"),
            "unknown algo 'dijkstra' (" + pathing::kAlgorithmNames.list() + ")");
  EXPECT_EQ(message("orders: [{at: 0, group: g, order: charge}]\n"),
            "unknown order 'charge' (expected " + kOrderKindNames.list(", ", " or ") + ")");
  EXPECT_EQ(
      message("triggers: [{when: {sunset: 1}, do: [{end_battle: none}]}]\n"),
      "unknown trigger condition 'sunset' (expected " + kTriggerKindNames.list(", ", " or ") + ")");
  EXPECT_EQ(message("victory: [{conquer: blue}]\n"),
            "unknown victory condition 'conquer' (expected " +
                kVictoryKindNames.list(", ", " or ") + ")");
  EXPECT_EQ(message("expectations: [{casualties: 1}]\n"),
            "unknown expectation 'casualties' (expected " + kExpectationKindNames.list() + ", " +
                kStatKindNames.list(", ", " or ") + ")");
}

}  // namespace
}  // namespace warpath::engine
