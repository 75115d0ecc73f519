#pragma once
// Scenario and unit-catalogue files (YAML; the schema is in docs/scenarios.md). Loading checks
// everything a run needs up front: errors name the file, line and column and the problem.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/world.h"
#include "pathing/annotated_grid.h"
#include "pathing/enum_names.h"
#include "pathing/error.h"
#include "pathing/file_read.h"
#include "units/unit_type.h"

namespace warpath::engine {

enum class ExpectationKind : std::uint8_t {
  ArrivalRate,  // fraction of units (team, type) inside their goal area by `by` >= threshold
  MaxStuck,     // units ever flagged stuck <= threshold
  ArrivalTime,  // the `percentile` of time-to-arrive (team, type) <= threshold seconds
  Winner,       // the report's winner is `team` (-1: no winner)
  Stat,         // a battle statistic of (team, type) compared with threshold
  // The movement section's figures (docs/cooperative.md):
  Delay,         // the `percentile` of delay = time to arrive / planned time (team, type)
                 // <= threshold
  MaxWait,       // the longest single wait of any unit <= threshold seconds
  MaxDeadlocks,  // cycles of units waiting on each other, broken, <= threshold
};
// The keys of the expectations that are not statistics (a Stat expectation's key is the name of
// its statistic, kStatKindNames).
inline constexpr EnumNames<ExpectationKind, 7> kExpectationKindNames{{{
    {ExpectationKind::ArrivalRate, "arrival_rate"},
    {ExpectationKind::ArrivalTime, "arrival_time"},
    {ExpectationKind::MaxStuck, "max_stuck"},
    {ExpectationKind::Winner, "winner"},
    {ExpectationKind::Delay, "delay"},
    {ExpectationKind::MaxWait, "max_wait"},
    {ExpectationKind::MaxDeadlocks, "max_deadlocks"},
}}};

// Battle statistics summed per (team, type) in the report.
enum class StatKind : std::uint8_t { Kills, Losses, DamageDealt, DamageTaken, ShotsFired, Alive };
inline constexpr EnumNames<StatKind, 6> kStatKindNames{{{
    {StatKind::Kills, "kills"},
    {StatKind::Losses, "losses"},
    {StatKind::DamageDealt, "damage_dealt"},
    {StatKind::DamageTaken, "damage_taken"},
    {StatKind::ShotsFired, "shots_fired"},
    {StatKind::Alive, "alive"},
}}};
std::string_view toString(StatKind kind);  // "kills", "losses", "damage_dealt", …

struct Expectation {
  ExpectationKind kind = ExpectationKind::ArrivalRate;
  int team = -1;  // index into Scenario::teams; -1: every team (Winner: no winner)
  int type = -1;  // index into Scenario::catalogue; -1: every type
  double threshold = 0.0;
  double by = 0.0;          // [Unit: s] ArrivalRate
  double percentile = 0.0;  // [Limit: 0..100] ArrivalTime, Delay
  StatKind stat = StatKind::Kills;
  bool atMost = true;  // Stat: actual <= threshold; else actual >= threshold
  std::string text;    // as printed, e.g. "arrival_rate(blue, tank) >= 0.9 by 120s"
};

struct GroupSpec {
  std::string name;
  int team = 0;
  int type = 0;
  int count = 0;
  pathing::CellRect spawn;
  std::optional<pathing::CellRect> goal;  // a Move order given when the group spawns
  std::vector<pathing::Cell> anchors;     // spawn cells, one per unit, chosen at load
  // Reinforcements do not spawn at the start: a trigger's `reinforce` action brings them in.
  bool reinforcement = false;
};

// What a trigger waits for. A trigger fires once, at the start of the first step whose
// preceding state meets its condition.
enum class TriggerKind : std::uint8_t {
  At,         // the battle clock reached `at` seconds
  Arrived,    // `fraction` of group `group` has arrived at its goal area
  TeamBelow,  // team `team` has fewer than `count` living units
  Enters,     // at least `count` living units of group `group` are inside `area`
  Dies,       // at least `count` units of group `group` have died
};
// The condition keys of a trigger's `when:`.
inline constexpr EnumNames<TriggerKind, 5> kTriggerKindNames{{{
    {TriggerKind::At, "at"},
    {TriggerKind::Arrived, "arrived"},
    {TriggerKind::TeamBelow, "team_below"},
    {TriggerKind::Enters, "enters"},
    {TriggerKind::Dies, "dies"},
}}};

enum class ActionKind : std::uint8_t {
  Order,       // order `groups` (their living units): `order` with `area` or `targetGroups`
  Reinforce,   // spawn the reinforcement group `group`
  EndBattle,   // stop the run; `team` (-1: none) is the winner unless a victory came first
  SetTerrain,  // every cell of `area` becomes `terrain` (docs/terrain_changes.md)
};
// The key that says which action an entry of a trigger's `do:` is.
inline constexpr EnumNames<ActionKind, 4> kActionKindNames{{{
    {ActionKind::Order, "order"},
    {ActionKind::Reinforce, "reinforce"},
    {ActionKind::EndBattle, "end_battle"},
    {ActionKind::SetTerrain, "set_terrain"},
}}};

struct ActionSpec {
  ActionKind kind = ActionKind::Order;
  OrderKind order = OrderKind::Move;
  std::vector<int> groups;                              // Order
  pathing::CellRect area;                               // Order: Move, AttackMove; SetTerrain
  pathing::Terrain terrain = pathing::Terrain::Ground;  // SetTerrain
  std::vector<int> targetGroups;                        // Order: Attack, the enemies' groups
  int group = -1;                                       // Reinforce
  int team = -1;                                        // EndBattle
};

struct TriggerSpec {
  std::string name;  // for reports and errors; "trigger N" when not given
  TriggerKind kind = TriggerKind::At;
  double at = 0.0;                  // [Unit: s] At
  int group = -1;                   // Arrived, Enters, Dies
  int team = -1;                    // TeamBelow
  int count = 1;                    // TeamBelow, Enters, Dies
  double fraction = 1.0;            // Arrived
  pathing::CellRect area;           // Enters
  std::vector<ActionSpec> actions;  // run in the order written
};

// How a team wins. The first condition met (in the order written) decides the winner and ends
// the battle.
enum class VictoryKind : std::uint8_t {
  Eliminate,  // every other team has no living unit (and `team` has one)
  HoldArea,   // `team` alone has living units inside `area` for `seconds` without a break
  Exit,       // `count` living units of `team` have stood inside `area` (each counts once)
};
inline constexpr EnumNames<VictoryKind, 3> kVictoryKindNames{{{
    {VictoryKind::Eliminate, "eliminate"},
    {VictoryKind::HoldArea, "hold"},
    {VictoryKind::Exit, "exit"},
}}};

struct VictorySpec {
  VictoryKind kind = VictoryKind::Eliminate;
  int team = 0;
  pathing::CellRect area;  // HoldArea, Exit
  double seconds = 0.0;    // [Unit: s] HoldArea
  int count = 1;           // Exit
  std::string text;        // as printed, e.g. "blue holds 40,20 8x8 for 30s"
};
// The text of a victory condition, e.g. "blue holds 40,20 8x8 for 30s". [Limit: v.team indexes
// teams]
std::string describe(const VictorySpec& v, const std::vector<std::string>& teams);

struct Scenario {
  std::filesystem::path file;
  std::string name;
  std::shared_ptr<const pathing::AnnotatedGrid> grid;
  std::vector<units::UnitType> catalogue;
  std::vector<std::string> teams;
  WorldSettings settings;
  double duration = 60.0;  // [Unit: s]
  std::vector<GroupSpec> groups;
  // Scripted orders (`orders:`) and `triggers:`, in the order written: an order is a trigger
  // with one Order action.
  std::vector<TriggerSpec> triggers;
  std::vector<VictorySpec> victory;
  std::vector<Expectation> expectations;

  std::int64_t durationTicks() const;
};

// Supplies the contents of a file a scenario names (its map, its catalogue), given the path
// resolved against the scenario's folder and the limit for that kind of file; an Error naming
// the file otherwise (message kNoSuchFile when there is no such file). Replays pass one that
// answers from the files they embed, so a replay never reads the disk.
using FileReader = std::function<Result<std::string>(const std::filesystem::path&, FileLimit)>;
// The whole of a regular file on disk, through readFileCapped.
Result<std::string> readDiskFile(const std::filesystem::path& file, FileLimit limit);

// `text` is read as if it were the file `file` (relative paths resolve against its folder).
// Referenced files come from `files` (default: the disk). A setting the file leaves out keeps
// its value in `defaults` (replays of older formats pass the defaults of their time).
Result<Scenario> parseScenario(std::string_view text, const std::filesystem::path& file);
Result<Scenario> parseScenario(std::string_view text, const std::filesystem::path& file,
                               const FileReader& files, const WorldSettings& defaults = {});
Result<Scenario> loadScenario(const std::filesystem::path& file);
// The scenario's length in ticks (duration x tick rate, as Scenario::durationTicks()) from its
// `duration` and `tick_rate` alone, without loading its map or anything else: what a replay's
// ticks are checked against before anything is simulated. [Limit: <= kMaxScenarioTicks]
Result<std::int64_t> scenarioDurationTicks(std::string_view text,
                                           const std::filesystem::path& file);
// The longest scenario the schema allows: duration 1e6 s at tick_rate 1000. [Unit: ticks]
inline constexpr std::int64_t kMaxScenarioTicks = 1'000'000'000;
// A catalogue file: `unit_types:` mapping type names to their fields.
Result<std::vector<units::UnitType>> loadCatalogue(const std::filesystem::path& file);

// Up to `count` anchor cells in `area` where `agent` can stand, row-major, with footprints
// that overlap neither each other nor cells already marked in `occupied` (one byte per map
// cell; the chosen footprints are marked).
std::vector<pathing::Cell> placeUnits(const pathing::AnnotatedGrid& grid, pathing::Agent agent,
                                      pathing::CellRect area, int count,
                                      std::vector<std::uint8_t>& occupied);

}  // namespace warpath::engine
