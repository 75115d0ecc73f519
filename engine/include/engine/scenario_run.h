#pragma once
// Runs a loaded scenario: spawns its groups, fires its triggers (orders, reinforcements, the
// end of the battle), steps the world, judges the victory conditions and, in the report, the
// expectations.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/scenario.h"
#include "engine/world.h"
#include "pathing/enum_names.h"

namespace warpath::engine {

// Per (team, type): how many arrived and how long it took (time-to-arrive counts from the
// order). Times in seconds; -1 when no unit of the pair has arrived.
struct ArrivalStats {
  std::string team;
  std::string type;
  int units = 0;
  int arrived = 0;
  int dead = 0;
  double rate = 0.0;
  double p50 = -1.0;
  double p90 = -1.0;
  double max = -1.0;
  // [Unit: s] the simulated time of each arrival, ascending: the arrival curve (arrivals by
  // time) of the HTML report and `rts report plot`.
  std::vector<double> arrivedAt;
  bool operator==(const ArrivalStats&) const = default;
};

// Battle statistics per (team, type): sums of the units' CombatStats; losses are deaths.
struct BattleStats {
  std::string team;
  std::string type;
  int units = 0;  // spawned so far
  int alive = 0;
  int losses = 0;
  int kills = 0;
  int shotsFired = 0;
  int hits = 0;
  int damageDealt = 0;
  int damageTaken = 0;
  bool operator==(const BattleStats&) const = default;
};

// Per (team, type): delay = time to arrive / planned time, the planned time being what the
// unit alone needed along its order's first path at its top speeds. -1 when none arrived.
struct DelayStats {
  std::string team;
  std::string type;
  int arrived = 0;  // units the delays are taken over
  double p50 = -1.0;
  double p90 = -1.0;
  double max = -1.0;
  std::vector<double> delays;  // each arrived unit's delay, ascending (the histogram's data)
  bool operator==(const DelayStats&) const = default;
};

// The report's `movement` section (docs/cooperative.md).
struct MovementReport {
  bool cooperative = false;
  int window = 0;  // [Unit: moves]
  MovementStats counters;
  double maxWaitSeconds = 0.0;
  std::vector<DelayStats> delay;  // per (team, type) with units, team-major
  bool operator==(const MovementReport&) const = default;
};

struct ExpectationResult {
  std::string text;
  double actual = 0.0;  // rate, count or seconds; +inf when a percentile has not arrived
  bool pass = false;
  // The units it counts against, by index, ascending: for arrival_rate those not arrived by its
  // time, for arrival_time and delay those beyond its bound (or not arrived), for max_stuck
  // those flagged; empty for the expectations about no unit in particular. What to trace.
  std::vector<std::uint32_t> units;
  bool operator==(const ExpectationResult&) const = default;
};

// Everything a run produces except wall-clock measurements (see World::meanTiming).
struct Report {
  std::string scenario;
  std::uint64_t seed = 0;
  std::int64_t ticks = 0;
  double simSeconds = 0.0;
  std::uint64_t stateHash = 0;
  bool complete = false;  // ran to its end: the whole duration, or until the battle ended
  std::vector<ArrivalStats> arrivals;
  std::vector<std::uint32_t> stuckUnits;  // ids of units ever flagged stuck
  int noPath = 0;                         // units whose goal could not be reached
  int repaths = 0;
  PathServiceMetrics pathing;
  MovementReport movement;
  std::vector<BattleStats> battle;  // per (team, type) with units, team-major
  std::string winner;               // team name; empty when no team has won (yet)
  std::string victory;              // the condition (or trigger) that decided it
  // The tick a victory condition or an end_battle ended the battle; -1 when none has (the
  // battle goes on, or the duration ran out undecided).
  std::int64_t endTick = -1;
  std::vector<std::string> triggersFired;  // trigger names, in firing order
  std::vector<ExpectationResult> expectations;

  bool passed() const;
  bool operator==(const Report&) const = default;
};

// What the run did to the world between steps: given before step `tick` + 1 ran (orders are
// applied at the start of that step). What a replay records as the command stream.
enum class IssuedKind : std::uint8_t {
  Order,      // `command` given to the world
  Reinforce,  // the reinforcement group `group` spawned
  EndBattle,  // the battle ended; `group` holds the winner's team index, -1 for none
  // The terrain of `command.area` set (World::setTerrain); `group` holds the pathing::Terrain.
  // Replay format 6 on.
  SetTerrain,
};
inline constexpr EnumNames<IssuedKind, 4> kIssuedKindNames{{{
    {IssuedKind::Order, "order"},
    {IssuedKind::Reinforce, "reinforce"},
    {IssuedKind::EndBattle, "end_battle"},
    {IssuedKind::SetTerrain, "set_terrain"},
}}};

struct IssuedOrder {
  std::int64_t tick = 0;
  IssuedKind kind = IssuedKind::Order;
  Command command;
  int group = -1;
  bool operator==(const IssuedOrder&) const = default;
};

// Nearest-rank percentile of ascending `sorted`; [Limit: !sorted.empty(), p in 0..100]
double percentile(const std::vector<double>& sorted, double p);

// What a run holds besides the world and that a live run and its replay's playback share: the
// groups, the outcome and the state of the victory conditions. Hashed with the world
// (ScenarioRun::stateHash) through engine/state_description.h, together with the number of
// entries issued so far (what the triggers did, or the script played). How each mode decides
// what to issue (which triggers fired; how far the script has been played) is the mode's own
// bookkeeping and stays out of it, so that a replay's hashes can match the live run's.
struct RunState {
  std::vector<std::vector<UnitId>> members;  // per group, in spawn order
  std::vector<bool> spawned;                 // per group
  // The battle's outcome.
  bool ended = false;
  int winner = -1;  // team index
  std::int64_t endTick = -1;
  // Per victory condition. Exit: per unit index, whether it has stood inside the area alive,
  // and how many have. HoldArea: the first tick of the current unbroken hold, -1 when none.
  std::vector<std::vector<bool>> exited;
  std::vector<int> exitedCount;
  std::vector<std::int64_t> holdSince;
};

class ScenarioRun {
 public:
  // Spawns every group that is not a reinforcement, gives each group with a goal its Move
  // order and fires the triggers whose condition already holds. `seed` replaces the scenario's
  // seed when given. The scenario must outlive the run.
  explicit ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed = {});
  // Plays `script` (ascending tick) instead of the scenario's group goals and triggers: each
  // entry is played at its tick (orders given, reinforcements spawned, the battle ended), so
  // playback never re-derives a trigger. The victory conditions are judged as in a live run:
  // they follow from the state. The caller checks that the script names units and groups the
  // scenario has (ReplayPlayback::open does); entries that do not are ignored.
  ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed,
              std::vector<IssuedOrder> script);

  // One tick: the world steps, then the victory conditions are judged on the new state and, if
  // none ended the battle, the triggers are evaluated on it (their orders reach the world at
  // the start of the next step). Nothing happens once the battle has ended.
  void step();
  // The whole duration has run, or the battle ended (a victory condition or an end_battle).
  bool done() const { return state_.ended || world_.tick() >= scenario_.durationTicks(); }
  // A victory condition or an end_battle action ended the battle.
  bool ended() const { return state_.ended; }
  const World& world() const { return world_; }
  const RunState& state() const { return state_; }
  // The world's state hash combined with the run's (triggers, victory, groups): what replays
  // record and verify, and the report's state_hash.
  std::uint64_t stateHash() const;
  // As replays of `format` (3 or later) recorded it.
  std::uint64_t stateHash(std::uint32_t format) const;
  const Scenario& scenario() const { return scenario_; }
  Report report() const;
  // Everything done to the world so far (orders, reinforcements, the end), in the order done.
  const std::vector<IssuedOrder>& issued() const { return issued_; }

 private:
  static WorldSettings settingsFor(const Scenario& scenario, std::optional<std::uint64_t> seed);
  void spawnGroup(int group, bool orderGoal);
  // The living members of `groups`, ascending index.
  std::vector<UnitId> living(const std::vector<int>& groups) const;
  void give(Command command);
  void setTerrain(pathing::CellRect area, pathing::Terrain terrain);
  void playScript();
  void fireTriggers();
  bool triggerDue(const TriggerSpec& trigger) const;
  void runAction(const TriggerSpec& trigger, const ActionSpec& action);
  void judgeVictory();
  void endBattle(int team, std::string how);

  const Scenario& scenario_;
  std::uint64_t seed_ = 0;
  World world_;
  std::optional<std::vector<IssuedOrder>> script_;
  std::vector<IssuedOrder> issued_;  // what was done, in order; hashed by its length
  RunState state_;
  // Live runs: per trigger, whether it fired, and the names in firing order.
  std::vector<bool> fired_;
  std::vector<std::string> triggersFired_;
  std::size_t scriptNext_ = 0;  // playback: the first script entry not yet played
  std::string victory_;         // how the battle was decided, for people
};

}  // namespace warpath::engine
