#include "engine/world.h"

#include <set>
#include <stdexcept>

#include "engine/fnv1a.h"
#include "engine/src/world/phase_timer.h"
#include "engine/src/world/phases.h"
#include "engine/state_description.h"

namespace warpath::engine {

using namespace pathing;

std::string_view toString(EventKind kind) {
  return kEventKindNames.name(kind);
}

std::string_view toString(OrderKind kind) {
  return kOrderKindNames.name(kind);
}

std::optional<OrderKind> orderKindFromName(std::string_view name) {
  return kOrderKindNames.parse(name);
}

namespace {

std::string outOfLimit(const char* field, const char* limit, double value) {
  std::string out = field;
  out.append(" must be ").append(limit).append(" (got ");
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return out.append(buffer).append(")");
}

std::vector<Capability> capabilitiesOf(const std::vector<units::UnitType>& catalogue) {
  std::set<Capability> distinct;
  for (const units::UnitType& type : catalogue)
    distinct.insert(type.capability);
  return {distinct.begin(), distinct.end()};
}

}  // namespace

std::string problemWith(const CombatSettings& settings) {
  if (!(settings.wreckSeconds >= 0.0))
    return outOfLimit("combat.wreckSeconds", ">= 0", settings.wreckSeconds);
  if (settings.scanEveryTicks < 1)
    return outOfLimit("combat.scanEveryTicks", ">= 1", settings.scanEveryTicks);
  return {};
}

std::string problemWith(const WorldSettings& settings) {
  // Written so that NaN fails every check.
  if (!(settings.tickRate > 0.0) || !std::isfinite(settings.tickRate))
    return outOfLimit("tickRate", "> 0 and finite", settings.tickRate);
  if (!(settings.stuck.windowSeconds > 0.0))
    return outOfLimit("stuck.windowSeconds", "> 0", settings.stuck.windowSeconds);
  if (!(settings.stuck.minProgress >= 0.0))
    return outOfLimit("stuck.minProgress", ">= 0", settings.stuck.minProgress);
  if (settings.stuck.flagAfter < 1)
    return outOfLimit("stuck.flagAfter", ">= 1", settings.stuck.flagAfter);
  if (std::string p = problemWith(settings.pathing); !p.empty()) return "pathing: " + p;
  return problemWith(settings.combat);
}

// The tick's phases and their scratch memory.
struct World::Phases {
  explicit Phases(int maxUnitSize) : combat(maxUnitSize) {}
  world::Combat combat;
  world::Traffic traffic;
  world::SteeringScratch steering;
  world::FullGoalAreas fullGoalAreas;
  std::vector<bool> contestedTracked;  // per catalogue type: its chokepoints are tracked
  std::vector<PathDelivery> deliveries;
  world::PhaseTimer timer;
};

World::World(std::shared_ptr<const AnnotatedGrid> grid, std::vector<units::UnitType> catalogue,
             const WorldSettings& settings)
    : grid_(std::move(grid)),
      catalogue_(std::move(catalogue)),
      settings_(settings),
      phases_(std::make_unique<Phases>(world::maxUnitSize(catalogue_))) {
  if (std::string problem = problemWith(settings_); !problem.empty())
    throw std::invalid_argument("world settings: " + problem);
  // A world that may change its terrain plans on a grid of its own (the path service keeps a
  // reference to it, so it is chosen here, once): the scenario's grid is shared by every run of
  // it and never changes. The copy starts from the map alone, as the shared grid does.
  const bool wreckObstacles = settings_.combat.wrecksBlock && world::maxUnitSize(catalogue_) >= 2;
  if (settings_.terrainChanges || wreckObstacles) {
    ownGrid_ = std::make_shared<AnnotatedGrid>(grid_->map());
    ownGrid_->setUpdateThreads(settings_.pathing.buildThreads);
    grid_ = ownGrid_;
  }
  const std::vector<Capability> capabilities = capabilitiesOf(catalogue_);
  state_.rng = SplitMix64(settings_.seed);
  state_.goals = GoalBoard(grid_->map());
  state_.physics = std::make_unique<Physics>(grid_->map(), capabilities);
  // With terrain costs, one cost profile per catalogue type (index = type).
  std::vector<CostProfile> costProfiles;
  if (settings_.pathing.terrainCosts) {
    for (const units::UnitType& type : catalogue_)
      costProfiles.push_back({type.agent(), type.terrainCosts()});
  }
  state_.paths =
      std::make_unique<PathService>(*grid_, settings_.pathing, capabilities,
                                    world::maxUnitSize(catalogue_), std::move(costProfiles));
  // Reservations are kept at the chokepoints of the kinds of unit on the map only (spawn adds
  // them): in the open, Box2D lets units slide past each other, and reserving there made group
  // moves 10-30 % slower (docs/cooperative.md).
  state_.reservations = std::make_unique<ReservationTable>(
      ReservationTable::trackingNothing(grid_->map().width(), grid_->map().height()));
  phases_->contestedTracked.assign(catalogue_.size(), false);
}

World::~World() = default;

UnitId World::spawn(int type, int team, int group, Cell anchor) {
  settleStateHash();
  const units::UnitType& kind = catalogue_[static_cast<std::size_t>(type)];
  if (settings_.pathing.cooperative && !phases_->contestedTracked[static_cast<std::size_t>(type)]) {
    // The first of its kind: the chokepoints it cannot pass others in are tracked from now on.
    const Agent agent = kind.agent();
    state_.reservations->track(
        contestedCells(*grid_, std::span<const Agent>(&agent, 1), settings_.pathing.dents()));
    phases_->contestedTracked[static_cast<std::size_t>(type)] = true;
  }
  Unit unit;
  unit.id = {static_cast<std::uint32_t>(state_.units.size()), 0};
  unit.type = type;
  unit.team = team;
  unit.group = group;
  unit.hp = kind.hp;
  unit.position = units::anchorToCentre(anchor, kind.size);
  unit.body = state_.physics->addBody(unit.position, kind.radius, kind.capability, unit.id.index);
  // A weapon is ready one cooldown after spawning, so that units spawned in range of each
  // other do not all fire in their first tick.
  if (kind.weapon)
    unit.readyTick = state_.tick + units::cooldownTicks(*kind.weapon, settings_.tickRate);
  state_.units.push_back(std::move(unit));
  events_.push_back({state_.tick, EventKind::Spawned, state_.units.back().id, 0});
  return state_.units.back().id;
}

const Unit* World::find(UnitId id) const {
  return state_.find(id);
}

int World::aliveCount(int team) const {
  int n = 0;
  for (const Unit& unit : state_.units)
    n += unit.alive() && unit.team == team ? 1 : 0;
  return n;
}

void World::order(Command command) {
  settleStateHash();
  state_.pending.push_back(std::move(command));
}

void World::setTerrain(CellRect area, Terrain terrain) {
  settleStateHash();
  if (!settings_.terrainChanges)
    throw std::logic_error("World::setTerrain needs WorldSettings::terrainChanges");
  state_.terrain.pending.push_back({TerrainEditKind::SetTerrain, area, terrain});
}

void World::applyTerrain() {
  TerrainLog& log = state_.terrain;
  if (log.pending.empty()) return;
  world::Refs w{*grid_, catalogue_, settings_, state_, events_};
  // Moved out first: pushing a unit off new terrain may kill it, which may queue a wreck.
  const std::vector<TerrainEdit> edits = std::move(log.pending);
  log.pending.clear();
  for (const TerrainEdit& edit : edits) {
    TerrainChange change;
    switch (edit.kind) {
      case TerrainEditKind::SetTerrain:
        change = ownGrid_->setTerrain(edit.area, edit.terrain);
        state_.physics->setTerrain(change.area, edit.terrain);
        break;
      case TerrainEditKind::PlaceObstacle:  // the wreck is a body already
        change = ownGrid_->placeObstacle(edit.area);
        break;
      case TerrainEditKind::ClearObstacle:
        change = ownGrid_->clearObstacle(edit.area);
        break;
    }
    ++log.applied;
    log.digest = world::digestAfter(log.digest, edit);
    if (!change.changed) continue;
    state_.paths->changeTerrain(change);
    // New chokepoints may have appeared: track them for the kinds of unit on the map (cells
    // tracked before stay tracked, which costs reservations there and nothing else).
    std::vector<Agent> tracked;
    for (std::size_t t = 0; t < catalogue_.size(); ++t) {
      if (phases_->contestedTracked[t]) tracked.push_back(catalogue_[t].agent());
    }
    if (!tracked.empty())
      state_.reservations->track(contestedCells(*grid_, tracked, settings_.pathing.dents()));
    phases_->traffic.terrainChanged();
    const bool set = edit.kind == TerrainEditKind::SetTerrain;
    world::afterTerrainChange(
        w, change.area, set,
        edit.kind == TerrainEditKind::ClearObstacle || (set && edit.terrain != Terrain::Blocked));
  }
}

void World::step() {
  using world::Phase;
  world::PhaseTimer& timer = phases_->timer;
  world::Refs w{*grid_, catalogue_, settings_, state_, events_};
  timer.beginTick();
  // The log keeps what was logged since the last step ended (spawns, say) and this step's.
  events_.erase(events_.begin(), events_.begin() + static_cast<std::ptrdiff_t>(eventsKept_));

  // 0. Terrain changes due this tick (wrecks of the last tick, then set_terrain), in order.
  applyTerrain();
  timer.mark(Phase::Pathing);
  // 1. Commands due this tick.
  for (const Command& command : state_.pending)
    world::applyCommand(w, command);
  state_.pending.clear();
  timer.mark(Phase::Bookkeeping);
  // 2. Path service within its expansion budget; answers to their units; cooperative windows
  // with what is left of the budget.
  const std::uint64_t spent = world::deliverPaths(w, phases_->deliveries);
  const std::uint64_t budget = settings_.pathing.expansionBudget;
  const world::Traffic::TickWork windows =
      phases_->traffic.plan(w, budget > spent ? budget - spent : 0);
  state_.paths->countWindows(spent, windows.expanded, windows.paused);
  timer.mark(Phase::Pathing);
  // 3. Targets, steering along paths, fire and shots landing.
  const bool combat = settings_.combat.enabled;
  if (combat) phases_->combat.chooseTargets(w);
  timer.mark(Phase::Combat);
  world::steerAll(w, phases_->steering);
  timer.mark(Phase::Steering);
  if (combat) phases_->combat.fire(w);
  timer.mark(Phase::Combat);
  // 4. Box2D.
  world::stepPhysics(w);
  timer.mark(Phase::Physics);
  // 5. Rules on the new tick: wrecks, arrivals, pursuit, repaths, stuck units.
  ++state_.tick;
  world::applyRules(w, phases_->fullGoalAreas);
  // 6. The state hash, when asked for.
  stateHash_.reset();
  eventsKept_ = events_.size();
  timer.mark(Phase::Bookkeeping);
  timer.endTick();
}

void World::settleStateHash() const {
  if (!stateHash_) stateHash_ = hashState(state_);
}

std::uint64_t World::stateHash() const {
  settleStateHash();
  return *stateHash_;
}

std::uint64_t World::stateHash(std::uint32_t format) const {
  return format >= kStateFormat ? stateHash() : hashState(state_, format);
}

std::uint64_t World::legacyStateHash() const {
  // The field list replays of format 2 recorded, byte-wise FNV-1a: kept so that those replays
  // still verify.
  const WorldState& state = state_;
  Fnv1a hash;
  const auto word = [&](std::uint64_t v) { hash.add(v); };
  const auto add = [&](auto value) {
    if constexpr (std::is_same_v<decltype(value), double>)
      word(static_cast<std::uint64_t>(std::llround(value * 1024.0)));
    else
      word(static_cast<std::uint64_t>(value));
  };
  add(state.tick);
  for (const Unit& unit : state.units) {
    add(static_cast<std::uint64_t>(unit.id.index) << 32 | unit.id.generation);
    add(unit.position.x);
    add(unit.position.y);
    add(unit.velocity.x);
    add(unit.velocity.y);
    add(static_cast<std::int64_t>(unit.hp));
    add(static_cast<std::uint64_t>(unit.state));
    add(static_cast<std::uint64_t>(unit.order));
    add(static_cast<std::int64_t>(unit.goalCell.x));
    add(static_cast<std::int64_t>(unit.goalCell.y));
    add(unit.arrivalTick);
    add(unit.pathSerial);
    add(static_cast<std::uint64_t>(unit.next));
    add(static_cast<std::uint64_t>(unit.target.index) << 32 | unit.target.generation);
    add(unit.readyTick);
    add(unit.wreckUntilTick);
  }
  for (const Shot& shot : state.inFlight) {
    add(static_cast<std::uint64_t>(shot.shooter.index) << 32 | shot.shooter.generation);
    add(static_cast<std::uint64_t>(shot.target.index) << 32 | shot.target.generation);
    add(static_cast<std::int64_t>(shot.damage));
    add(shot.landTick);
  }
  return hash.value();
}

TickTiming World::meanTiming() const {
  return phases_->timer.mean();
}

}  // namespace warpath::engine
