#pragma once
// The world: units on a grid map, advanced by a fixed timestep. One tick (DESIGN.md §4):
// commands due → path service (within its expansion budget) → steering → Box2D step → rules
// (arrivals, blocked waypoints, stuck units) → state hash. Everything that changes the state
// is a function of the map, the catalogue, the seed and the commands: the world owns its RNG,
// iterates units in id order and never reads a clock except to measure itself.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/handle.h"
#include "engine/path_service.h"
#include "engine/physics.h"
#include "pathing/annotated_grid.h"
#include "pathing/random.h"
#include "units/steering.h"
#include "units/stuck.h"
#include "units/unit_type.h"

namespace warpath::engine {

struct WorldSettings {
  double tickRate = 30.0;  // [Unit: ticks/s] [Limit: > 0]
  std::uint64_t seed = 1;
  PathServiceSettings pathing;
  units::StuckRule stuck;
  units::SteeringParams steering;
};

enum class UnitState : std::uint8_t {
  Idle,         // no order
  WaitingPath,  // ordered, path requested
  Moving,       // following a path
  Parked,       // reached its goal cell
  NoPath,       // the goal cannot be reached; reported once, not retried
};

struct Unit {
  UnitId id;
  int type = 0;   // index into the world's catalogue
  int team = 0;   // index into the scenario's teams
  int group = 0;  // index into the scenario's groups
  int hp = 0;
  std::uint32_t body = 0;
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
};

enum class EventKind : std::uint8_t {
  Spawned,
  Ordered,
  PathFound,
  PathFailed,    // detail: pathing::PathStatus
  Arrived,       // anchor entered the goal area
  Parked,        // reached its goal cell
  Repath,        // detail: 0 stuck, 1 left its path, 2 goal cell taken
  StuckFlagged,  // stuck for StuckRule::flagAfter windows in a row
};
std::string_view toString(EventKind kind);

struct Event {
  std::int64_t tick = 0;
  EventKind kind = EventKind::Spawned;
  UnitId unit;
  int detail = 0;
};

// Mean wall time per phase over the ticks stepped so far: measurement only.
struct TickTiming {
  double pathingMicros = 0.0;
  double steeringMicros = 0.0;
  double physicsMicros = 0.0;
  double bookkeepingMicros = 0.0;  // commands, rules, state hash
  double slowestTickMicros = 0.0;  // the whole of the slowest tick (not a mean)
  std::int64_t ticks = 0;
};

class World {
 public:
  // `catalogue` holds every unit type the world may spawn; the path service is built for their
  // capabilities and the largest size. The grid is shared (read-only).
  World(std::shared_ptr<const pathing::AnnotatedGrid> grid, std::vector<units::UnitType> catalogue,
        const WorldSettings& settings);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Spawns a unit at an anchor cell where its type can stand (the caller checks).
  UnitId spawn(int type, int team, int group, pathing::Cell anchor);
  // Orders units to move into `area`; applied at the start of the next step. Each unit gets a
  // goal cell of its own inside the area, drawn with the world's RNG.
  void orderMove(std::vector<UnitId> units, pathing::CellRect area);

  void step();

  std::int64_t tick() const { return tick_; }
  double tickRate() const { return settings_.tickRate; }
  double seconds() const { return static_cast<double>(tick_) / settings_.tickRate; }
  const std::vector<Unit>& units() const { return units_; }
  const Unit* find(UnitId id) const;
  const std::vector<units::UnitType>& catalogue() const { return catalogue_; }
  const std::vector<Event>& events() const { return events_; }
  const pathing::AnnotatedGrid& grid() const { return *grid_; }
  const PathService& pathService() const { return *paths_; }
  const Physics& physics() const { return *physics_; }
  // FNV-1a over the tick and every unit's quantised position, velocity, hp and order, in id
  // order; updated at the end of every step.
  std::uint64_t stateHash() const { return stateHash_; }
  TickTiming meanTiming() const;

 private:
  struct MoveCommand {
    std::vector<UnitId> units;
    pathing::CellRect area;
  };

  void applyCommand(const MoveCommand& command);
  void requestPath(Unit& unit);
  void deliver(const PathDelivery& delivery);
  void steerAll();
  void applyRules();
  bool reassignGoal(Unit& unit);
  void claimGoal(const Unit& unit, bool claim);
  pathing::Cell nearestStandable(const Unit& unit) const;
  void log(EventKind kind, const Unit& unit, int detail = 0);
  std::uint64_t computeHash() const;

  std::shared_ptr<const pathing::AnnotatedGrid> grid_;
  std::vector<units::UnitType> catalogue_;
  WorldSettings settings_;
  pathing::SplitMix64 rng_;
  std::unique_ptr<Physics> physics_;
  std::unique_ptr<PathService> paths_;
  std::vector<Unit> units_;
  std::vector<MoveCommand> pending_;
  std::vector<PathDelivery> deliveries_;  // scratch, reused every tick
  // Unit index + 1 of the parked unit covering each cell, 0 where none.
  std::vector<std::uint32_t> parkedAt_;
  // Unit index + 1 of the unit whose goal footprint covers each cell, 0 where none: goal
  // cells handed out by different orders do not overlap while the area has room.
  std::vector<std::uint32_t> claimedBy_;
  std::vector<Event> events_;
  std::int64_t tick_ = 0;
  std::uint64_t stateHash_ = 0;
  TickTiming timing_;  // sums
};

}  // namespace warpath::engine
