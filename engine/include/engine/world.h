#pragma once
// The world: units on a grid map, advanced by a fixed timestep. One tick (DESIGN.md §4):
// commands due → path service (within its expansion budget) → targets → steering → firing and
// shots landing (deaths) → Box2D step → rules (arrivals, blocked waypoints, stuck units, wrecks)
// → state hash. docs/combat.md states the combat rules and the order of fire within a tick.
// Everything that changes the state is a function of the map, the catalogue, the seed and the
// commands: the world owns its RNG, iterates units in id order and never reads a clock except to
// measure itself. The state is one value, WorldState; engine/state_description.h describes every
// field of it, and the state hash is computed through that description. Each phase of a tick
// lives in engine/src/world/ and has one job.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/goal_board.h"
#include "engine/handle.h"
#include "engine/path_service.h"
#include "engine/physics.h"
#include "pathing/annotated_grid.h"
#include "pathing/cooperative_search.h"
#include "pathing/enum_names.h"
#include "pathing/random.h"
#include "pathing/reservation_table.h"
#include "units/combat.h"
#include "units/steering.h"
#include "units/stuck.h"
#include "units/unit_type.h"

namespace warpath::engine {

struct CombatSettings {
  bool enabled = true;  // false: weapons never fire (travel-only scenarios)
  units::SightRules sight;
  units::ArmourTable armour = units::defaultArmourTable();
  // [Unit: s] [Limit: >= 0] how long a destroyed unit's wreck stays as an obstacle; 0 removes
  // the body at once.
  double wreckSeconds = 20.0;
  // Wrecks of units of size >= 2 block planning while they stand: an obstacle over the cells
  // of the footprint they died on (docs/terrain_changes.md). Replays of formats <= 5 play back
  // without it.
  bool wrecksBlock = true;
  // [Unit: ticks] [Limit: >= 1] how often a unit without a target scans for one (staggered by
  // id); a unit with a target checks every tick that it may still engage it.
  int scanEveryTicks = 5;
};
// Empty when the settings can be used, else the first field out of its limits and why.
std::string problemWith(const CombatSettings& settings);

struct WorldSettings {
  double tickRate = 30.0;  // [Unit: ticks/s] [Limit: > 0]
  std::uint64_t seed = 1;
  PathServiceSettings pathing;
  units::StuckRule stuck;
  units::SteeringParams steering;
  CombatSettings combat;
  // The run may change its terrain (World::setTerrain): the world plans on a grid of its own,
  // copied from the one it is given, instead of sharing it. Wreck obstacles get one too
  // (combat.wrecksBlock with a unit of size >= 2 in the catalogue).
  bool terrainChanges = false;
};
// Empty when every [Limit] of the settings (path service, stuck rule, combat included) holds,
// else the first that does not, beginning with the field, e.g. "tickRate must be > 0 (got 0)",
// "stuck.flagAfter …", "pathing: clusterSize …" (the scenario loader reports it at the key that
// set that field). World's constructor throws std::invalid_argument with this message; callers
// that take user input check first.
std::string problemWith(const WorldSettings& settings);

// What a unit was told to do (RTS semantics; docs/combat.md).
enum class OrderKind : std::uint8_t {
  Stop,        // stand still; fire at enemies in range
  Move,        // go to an area; fire on the move, never stop to fight
  AttackMove,  // go to an area; halt to fight enemies in range, then go on
  Attack,      // close in on a set of enemy units and fire at them until all are dead
  Hold,        // keep the current spot; fire at enemies in range, never move
};
inline constexpr EnumNames<OrderKind, 5> kOrderKindNames{{{
    {OrderKind::Stop, "stop"},
    {OrderKind::Move, "move"},
    {OrderKind::AttackMove, "attack_move"},
    {OrderKind::Attack, "attack"},
    {OrderKind::Hold, "hold"},
}}};
std::string_view toString(OrderKind kind);
std::optional<OrderKind> orderKindFromName(std::string_view name);  // "move", "attack_move", …

// An order as the world receives it (and as replays record it).
struct Command {
  OrderKind kind = OrderKind::Move;
  std::vector<UnitId> units;    // ascending index; dead or unknown units are skipped
  pathing::CellRect area;       // Move, AttackMove
  std::vector<UnitId> targets;  // Attack: ascending index; each unit closes on the nearest
  bool operator==(const Command&) const = default;
};

enum class UnitState : std::uint8_t {
  Idle,         // no order
  WaitingPath,  // ordered, path requested
  Moving,       // following a path
  Parked,       // reached its goal cell
  NoPath,       // the goal cannot be reached; reported once, not retried
  Dead,         // destroyed: no body (or a wreck's), no orders, never steps again
};

// Per unit, since spawn; the report sums them per (team, type).
struct CombatStats {
  int shotsFired = 0;
  int hits = 0;         // shots that landed on a living target
  int damageDealt = 0;  // hit points removed, capped at what the target had left
  int damageTaken = 0;
  int kills = 0;
  bool operator==(const CombatStats&) const = default;
};

// A unit's cooperative plan: the window it reserved, as timed anchor cells (waits are two
// entries on one cell), with a digest computed once so the state hash covers it cheaply.
struct TimedPlan {
  std::vector<pathing::TimedCell> steps;
  pathing::CooperativeStatus status = pathing::CooperativeStatus::Blocked;
  // The unit keeps to the plan's times: it waits, or crosses a chokepoint (a tracked cell of
  // the reservation table). Otherwise it follows its path as a unit without a plan would, and
  // the plan only looks ahead for the next chokepoint.
  bool timed = false;
  // No chokepoint lies within a window's reach along the path: nothing was searched or
  // reserved, and the unit follows its path until one comes into reach.
  bool cruising = false;
  std::uint64_t digest = 0;  // FNV-1a over the steps and the flags
  // The passage ahead whose gate the window was planned under (docs/cooperative.md: a passage
  // lets one way through at a time), -1 for none; whether the unit was let through (else it
  // keeps out of the passage and its mouth), and since when it has been let through or kept
  // out. Kept from window to window, so a unit that falls behind its window keeps its turn.
  std::int32_t gate = -1;
  bool admitted = false;
  std::int64_t gateSince = -1;
};
TimedPlan timedPlan(std::vector<pathing::TimedCell> steps, pathing::CooperativeStatus status,
                    bool timed, bool cruising = false);
using SharedPlan = std::shared_ptr<const TimedPlan>;

struct Unit {
  UnitId id;
  int type = 0;   // index into the world's catalogue
  int team = 0;   // index into the scenario's teams
  int group = 0;  // index into the scenario's groups
  int hp = 0;
  BodyId body;
  units::Vec2 position;  // [Unit: cells] body centre
  units::Vec2 velocity;  // [Unit: cells/s]
  // The current order.
  UnitState state = UnitState::Idle;
  pathing::CellRect goalArea;
  pathing::Cell goalCell;         // anchor cell the unit heads for inside goalArea
  std::int64_t orderTick = -1;    // tick the order was given
  std::int64_t arrivalTick = -1;  // first tick the anchor was inside goalArea, this order
  std::uint64_t pathSerial = 0;   // number of the latest path request
  SharedPath path;
  std::size_t next = 0;  // waypoint steered to
  units::ProgressMonitor progress;
  bool everStuck = false;  // flagged by the stuck rule at least once
  int repaths = 0;
  // Cooperative movement (docs/cooperative.md).
  SharedPlan plan;  // the reserved window being followed; null when none
  // Anchor whose footprint the unit holds in the reservation table from `heldSince` on, for
  // good, while it follows no plan (parked, waiting for a path, fighting, a wreck); -1: none.
  pathing::Cell held{-1, -1};
  std::int64_t heldSince = -1;
  std::int64_t waitSince = -1;     // the tick the current wait began; -1 when not waiting
  std::int64_t waitedTicks = 0;    // ticks spent waiting since the order (priority ages with it)
  std::int64_t plannedTicks = -1;  // free-flow time of the order's first path; -1 unknown
  // Combat.
  OrderKind order = OrderKind::Stop;
  std::vector<UnitId> attackTargets;  // Attack order: the enemies to close on
  UnitId target;                      // what the weapon aims at; invalid when none
  std::int64_t readyTick = 0;         // the weapon may fire at this tick or later
  bool engaged = false;               // halted this tick to fight (AttackMove, Attack)
  std::int64_t deathTick = -1;
  std::int64_t wreckUntilTick = -1;  // the wreck's body is removed at this tick
  // The obstacle the wreck stands as on the planning grid until wreckUntilTick; width 0: none.
  pathing::CellRect wreckArea;
  UnitId killedBy;
  CombatStats combat;

  bool alive() const { return hp > 0; }
};

// A shot in flight (or landing this tick). Homing: it lands on its target when that is still
// alive at landTick, wherever the target went.
struct Shot {
  UnitId shooter;
  UnitId target;
  int damage = 0;  // after the armour multiplier
  std::int64_t firedTick = 0;
  std::int64_t landTick = 0;
  units::Vec2 from;  // [Unit: cells] the shooter's centre when fired
  units::Vec2 to;    // [Unit: cells] the target's centre when fired
};

enum class EventKind : std::uint8_t {
  Spawned,
  Ordered,
  PathFound,
  PathFailed,    // detail: pathing::PathStatus
  Arrived,       // anchor entered the goal area
  Parked,        // reached its goal cell
  Repath,        // detail: 0 stuck, 1 left its path, 2 goal cell taken, 3 terrain changed,
                 // 4 a unit that had no path tries again after terrain opened,
                 // 5 a parked unit handed its goal cell to a teammate it blocked
  StuckFlagged,  // stuck for StuckRule::flagAfter windows in a row
  Killed,        // hp reached 0; detail: the killer's index
  WreckCleared,  // the wreck's body was removed
  Pushed,        // moved to the nearest anchor it can stand on: its terrain became impassable
};
inline constexpr EnumNames<EventKind, 11> kEventKindNames{{{
    {EventKind::Spawned, "spawned"},
    {EventKind::Ordered, "ordered"},
    {EventKind::PathFound, "path-found"},
    {EventKind::PathFailed, "path-failed"},
    {EventKind::Arrived, "arrived"},
    {EventKind::Parked, "parked"},
    {EventKind::Repath, "repath"},
    {EventKind::StuckFlagged, "stuck"},
    {EventKind::Killed, "killed"},
    {EventKind::WreckCleared, "wreck-cleared"},
    {EventKind::Pushed, "pushed"},
}}};
std::string_view toString(EventKind kind);

struct Event {
  std::int64_t tick = 0;
  EventKind kind = EventKind::Spawned;
  UnitId unit;
  int detail = 0;
};

// Counters of cooperative movement since the start, for the report's `movement` section.
struct MovementStats {
  std::int64_t windows = 0;          // windows planned
  std::int64_t blockedWindows = 0;   // searches that found no safe window (the unit held on)
  std::int64_t waits = 0;            // times a unit began to wait
  std::int64_t giveWays = 0;         // windows that begin by moving away from the goal
  std::int64_t deadlocksBroken = 0;  // cycles of units waiting on each other, broken
  std::int64_t maxWaitTicks = 0;     // the longest single wait
  std::uint64_t expanded = 0;        // space-time nodes expanded
  bool operator==(const MovementStats&) const = default;
};

// A change of the terrain (docs/terrain_changes.md): a scenario's set_terrain, or a wreck's
// obstacle placed or cleared.
enum class TerrainEditKind : std::uint8_t { SetTerrain, PlaceObstacle, ClearObstacle };
struct TerrainEdit {
  TerrainEditKind kind = TerrainEditKind::SetTerrain;
  pathing::CellRect area;                               // inside the map
  pathing::Terrain terrain = pathing::Terrain::Ground;  // SetTerrain
  bool operator==(const TerrainEdit&) const = default;
};
// The terrain's part of the state: the changes waiting for the next step, and a digest of those
// applied (with the map, what the grid is now).
struct TerrainLog {
  std::vector<TerrainEdit> pending;  // applied at the start of the next step, in order
  std::uint64_t applied = 0;         // changes applied so far
  std::uint64_t digest = 0;          // FNV-1a over the changes applied, in order
};

// The whole simulation state: everything a step reads besides the map, the catalogue and the
// settings, and everything it changes. The state hash covers every field through
// engine/state_description.h (a test fails when a field is not described). Events are the
// step's output, not state; scratch memory of the phases is not state either.
struct WorldState {
  std::int64_t tick = 0;
  pathing::SplitMix64 rng{1};
  std::vector<Unit> units;       // by UnitId::index, in creation order
  std::vector<Command> pending;  // given, applied at the start of the next step
  std::vector<Shot> inFlight;    // in firing order
  std::vector<Shot> lastTickShots;
  GoalBoard goals;
  std::unique_ptr<Physics> physics;
  std::unique_ptr<PathService> paths;
  // Who holds which cells when (cooperative movement): the union of every unit's plan and
  // held footprint, so its content follows from the units' fields.
  std::unique_ptr<pathing::ReservationTable> reservations;
  MovementStats movement;
  TerrainLog terrain;

  // The unit a handle names; null when the world did not give it out (an index past the units,
  // or a stale generation). The one handle check: World::find and the phases use it.
  const Unit* find(UnitId id) const {
    return id.index < units.size() && units[id.index].id.generation == id.generation
               ? &units[id.index]
               : nullptr;
  }
  Unit* find(UnitId id) { return const_cast<Unit*>(std::as_const(*this).find(id)); }
};

// Mean wall time per phase over the ticks stepped so far: measurement only.
struct TickTiming {
  double pathingMicros = 0.0;
  double combatMicros = 0.0;  // targets, firing, shots landing
  double steeringMicros = 0.0;
  double physicsMicros = 0.0;
  double bookkeepingMicros = 0.0;  // commands, rules (not the state hash: computed when asked)
  double slowestTickMicros = 0.0;  // the whole of the slowest tick (not a mean)
  std::int64_t ticks = 0;
};

class World {
 public:
  // `catalogue` holds every unit type the world may spawn; the path service is built for their
  // capabilities and the largest size. The grid is shared (read-only) unless the terrain may
  // change (WorldSettings::terrainChanges, wreck obstacles): then the world copies its map into
  // a grid of its own, so that other runs of the same scenario never see its changes.
  World(std::shared_ptr<const pathing::AnnotatedGrid> grid, std::vector<units::UnitType> catalogue,
        const WorldSettings& settings);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Spawns a unit at an anchor cell where its type can stand (the caller checks).
  UnitId spawn(int type, int team, int group, pathing::Cell anchor);
  // Gives an order; applied at the start of the next step, in the order given. Move and
  // AttackMove give each unit a goal cell of its own inside the area, drawn with the world's RNG.
  void order(Command command);
  void orderMove(std::vector<UnitId> units, pathing::CellRect area) {
    order({OrderKind::Move, std::move(units), area, {}});
  }
  // Sets every cell of `area` (clipped to the map) to `terrain` at the start of the next step,
  // before the orders given (docs/terrain_changes.md). [Limit: settings().terrainChanges, else
  // std::logic_error]
  void setTerrain(pathing::CellRect area, pathing::Terrain terrain);

  void step();

  std::int64_t tick() const { return state_.tick; }
  double tickRate() const { return settings_.tickRate; }
  double seconds() const { return static_cast<double>(state_.tick) / settings_.tickRate; }
  const std::vector<Unit>& units() const { return state_.units; }
  const Unit* find(UnitId id) const;
  const std::vector<units::UnitType>& catalogue() const { return catalogue_; }
  const WorldSettings& settings() const { return settings_; }
  // What happened during the last step (spawns since then included), in order. Cleared at the
  // start of every step, so the log stays as long as one tick's events: callers that want a
  // history (reports, recorders, tests) keep what they need after each step.
  const std::vector<Event>& events() const { return events_; }
  // Shots in flight after the last step, and those that were fired or landed during it.
  const std::vector<Shot>& shotsInFlight() const { return state_.inFlight; }
  const std::vector<Shot>& shotsLastTick() const { return state_.lastTickShots; }
  int aliveCount(int team) const;
  const pathing::AnnotatedGrid& grid() const { return *grid_; }
  const PathService& pathService() const { return *state_.paths; }
  const Physics& physics() const { return *state_.physics; }
  const WorldState& state() const { return state_; }
  // Hash of the whole WorldState (engine/state_description.h) as the last step left it (0
  // before the first step): positions and velocities quantised to 1/1024 cell, everything else
  // exact.
  std::uint64_t stateHash() const;
  // The same hash as an older replay format laid the state out (engine/state_description.h),
  // computed on demand.
  std::uint64_t stateHash(std::uint32_t format) const;
  // The hash replays of format 2 recorded (a hand-picked subset of the fields), so that those
  // replays still verify.
  std::uint64_t legacyStateHash() const;
  TickTiming meanTiming() const;

 private:
  struct Phases;  // the tick's phases and their scratch memory (engine/src/world/)
  // Applies the pending terrain changes (phase 0 of a step).
  void applyTerrain();

  std::shared_ptr<const pathing::AnnotatedGrid> grid_;
  std::shared_ptr<pathing::AnnotatedGrid> ownGrid_;  // grid_'s target when the terrain may change
  std::vector<units::UnitType> catalogue_;
  WorldSettings settings_;
  WorldState state_;
  std::vector<Event> events_;
  std::unique_ptr<Phases> phases_;
  std::size_t eventsKept_ = 0;  // events_ entries from before the last step ended
  // stateHash(), computed when first asked after a step (a run that records no hashes does not
  // pay for them), or before spawn, order or setTerrain change the state the step left.
  void settleStateHash() const;
  mutable std::optional<std::uint64_t> stateHash_ = 0;
};

}  // namespace warpath::engine
