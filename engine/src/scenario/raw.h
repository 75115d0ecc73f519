#pragma once
// A scenario or catalogue file as written: what decoding (engine/src/scenario/decode.cpp) reads
// out of the YAML — keys, shapes, scalars and the schema's own names (terrains, armour classes,
// orders, …) — before anything is checked against anything else. Every value keeps where it is
// written, so that the checks (engine/src/scenario/scenario.cpp: ranges, team, type and group
// names, the map, the settings' limits) report a problem at the key that holds it. No yaml-cpp
// here: decoding is its only user.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/scenario.h"
#include "engine/world.h"
#include "pathing/planner.h"
#include "pathing/terrain.h"
#include "units/combat.h"

namespace warpath::engine::raw {

// Where a node is written: 1-based line and column.
struct Mark {
  int line = 0;
  int column = 0;
};

// A value and where it is written.
template <class T>
struct Field {
  T value{};
  Mark mark;
};
// A key the file may leave out.
template <class T>
using Maybe = std::optional<Field<T>>;

// `{x, y, w, h}`
struct Area {
  Mark mark;
  Field<int> x, y, w, h;
};

// `NAME` or `[NAME, ...]` (groups): at least one.
struct Names {
  std::vector<Field<std::string>> items;
};

// `map:`: a file, or inline `rows`.
struct Map {
  Maybe<std::string> file;
  Mark rowsMark;
  std::vector<Field<std::string>> rows;
};

struct Weapon {
  Mark mark;
  bool none = false;  // `weapon: none`
  Maybe<std::string> name;
  Maybe<units::DamageKind> kind;
  Maybe<int> damage;
  Maybe<double> range;
  Maybe<double> cooldown;
  Maybe<double> projectileSpeed;
  Maybe<units::TargetMask> targets;
  std::vector<std::pair<Field<units::ArmourClass>, Field<int>>> priority;  // class, rank
};

// `speed:` one number for every terrain, or per terrain.
struct Speed {
  Mark mark;
  Maybe<double> all;
  std::vector<std::pair<Field<pathing::Terrain>, Field<double>>> perTerrain;
};

// One entry of `unit_types:`: the fields given.
struct UnitType {
  Field<std::string> name;
  Mark mark;  // the mapping of fields
  Maybe<int> size;
  Maybe<pathing::Capability> capability;
  std::optional<Speed> speed;
  Maybe<double> acceleration;
  Maybe<double> turnRate;  // [Unit: degrees/s] as written
  Maybe<double> radius;
  Maybe<int> hp;
  Maybe<units::ArmourClass> armour;
  std::optional<Weapon> weapon;
};

// `tick_rate` and `duration`: what a scenario's length in ticks is computed from.
struct Timing {
  Maybe<double> tickRate;
  Field<double> duration;
};

struct Pathing {
  Maybe<pathing::Algorithm> algorithm;
  Maybe<int> clusterSize;
  Maybe<int> levels;
  Maybe<int> levelTwoSize;
  Maybe<int> budget;
  Maybe<int> cache;
  Maybe<bool> cooperative;
  Maybe<int> window;
  Maybe<bool> corridorSearch;  // cooperative_search: cpra (true) or whca
  Maybe<int> corridor;
  Maybe<bool> congestion;
  Maybe<bool> terrainCosts;
  Maybe<bool> sliced;
  Maybe<pathing::InsertionMode> insertion;
};

struct Stuck {
  Maybe<double> seconds;
  Maybe<double> minProgress;
  Maybe<int> flagAfter;
};

struct ArmourPercent {
  Field<units::DamageKind> kind;
  Field<units::ArmourClass> armour;
  Field<int> percent;
};

struct Combat {
  Maybe<bool> enabled;
  Maybe<double> wreckSeconds;
  Maybe<bool> wrecksBlock;
  Maybe<int> sightThroughTrees;
  Maybe<int> scanEvery;
  std::vector<ArmourPercent> armour;
};

// What a scenario gives of the world settings: `seed`, `tick_rate`, `duration`, `pathing`,
// `stuck` and `combat`.
struct Settings {
  Mark root;  // the scenario's mapping
  Maybe<std::uint64_t> seed;
  Timing timing;
  std::optional<Pathing> pathing;
  std::optional<Stuck> stuck;
  std::optional<Combat> combat;
};

struct Group {
  Mark mark;
  Maybe<std::string> name;
  Field<std::string> team;
  Field<std::string> type;
  Field<int> count;
  Area spawn;
  std::optional<Area> goal;
  Maybe<bool> reinforcement;
};

// An order (an `orders:` entry's, or an `order:` action's): `order` (Move when not given, marked
// at the entry), `group`, and `move_to` or `target` as the kind takes.
struct OrderAction {
  Field<OrderKind> order;
  Names groups;
  std::optional<Area> moveTo;
  std::optional<Names> target;
};

// An `orders:` entry: `at` a time, or `when: {arrived, fraction}`.
struct Order {
  Maybe<double> at;
  Field<std::string> arrived;
  Maybe<double> fraction;
  OrderAction action;
};

// A trigger's `when:`: one condition; the fields its kind takes are set.
struct Condition {
  Field<TriggerKind> kind;   // marked at the condition's key
  Field<double> at;          // At
  Field<std::string> group;  // Arrived, Enters, Dies
  Field<std::string> team;   // TeamBelow
  Maybe<int> count;          // TeamBelow (always given), Enters, Dies
  Maybe<double> fraction;    // Arrived
  Area area;                 // Enters
};

// An entry of a trigger's `do:`.
struct Action {
  ActionKind kind = ActionKind::Order;
  OrderAction order;                // Order
  Field<std::string> name;          // Reinforce: the group; EndBattle: the team or `none`
  Area area;                        // SetTerrain
  Field<pathing::Terrain> terrain;  // SetTerrain
};

struct Trigger {
  Mark mark;
  Maybe<std::string> name;
  Condition when;
  std::vector<Action> actions;
};

struct Victory {
  Field<VictoryKind> kind;  // marked at the condition's key
  Field<std::string> team;
  Area area;              // HoldArea, Exit
  Field<double> seconds;  // HoldArea
  Field<int> count;       // Exit
};

struct Expectation {
  Field<std::string> key;  // as written: the kind, or the statistic's name
  ExpectationKind kind = ExpectationKind::ArrivalRate;
  StatKind stat = StatKind::Kills;
  Maybe<std::string> team;  // ArrivalRate, ArrivalTime, Delay, Stat; Winner: the team or `none`
  Maybe<std::string> type;
  // at_least (ArrivalRate, Stat), at_most (ArrivalTime, Delay, Stat), the value (MaxWait)
  Field<double> threshold;
  bool atMost = false;       // Stat
  Field<double> by;          // ArrivalRate
  Field<double> percentile;  // ArrivalTime, Delay
  Field<int> count;          // MaxStuck, MaxDeadlocks
};

}  // namespace warpath::engine::raw
