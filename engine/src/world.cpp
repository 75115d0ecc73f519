#include "engine/world.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <set>

namespace warpath::engine {

using namespace pathing;
using units::Vec2;

std::string_view toString(EventKind kind) {
  switch (kind) {
    case EventKind::Spawned:
      return "spawned";
    case EventKind::Ordered:
      return "ordered";
    case EventKind::PathFound:
      return "path-found";
    case EventKind::PathFailed:
      return "path-failed";
    case EventKind::Arrived:
      return "arrived";
    case EventKind::Parked:
      return "parked";
    case EventKind::Repath:
      return "repath";
    case EventKind::StuckFlagged:
      return "stuck";
    case EventKind::Killed:
      return "killed";
    case EventKind::WreckCleared:
      return "wreck-cleared";
  }
  return "?";
}

std::string_view toString(OrderKind kind) {
  return kOrderKindNames.name(kind);
}

std::optional<OrderKind> orderKindFromName(std::string_view name) {
  return kOrderKindNames.parse(name);
}

namespace {

std::vector<Capability> capabilitiesOf(const std::vector<units::UnitType>& catalogue) {
  std::set<Capability> distinct;
  for (const units::UnitType& type : catalogue)
    distinct.insert(type.capability);
  return {distinct.begin(), distinct.end()};
}

int maxSizeOf(const std::vector<units::UnitType>& catalogue) {
  int size = 1;
  for (const units::UnitType& type : catalogue)
    size = std::max(size, type.size);
  return size;
}

// Calls f(cell) for every cell of the size×size footprint anchored at `anchor`.
template <class F>
void forFootprint(Cell anchor, int size, F f) {
  for (int dy = 0; dy < size; ++dy) {
    for (int dx = 0; dx < size; ++dx)
      f(Cell{anchor.x + dx, anchor.y + dy});
  }
}

int chebyshev(Cell a, Cell b) {
  return std::max(std::abs(a.x - b.x), std::abs(a.y - b.y));
}

class Stopwatch {
 public:
  // Microseconds since the last call (or construction).
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double us = std::chrono::duration<double, std::micro>(now - last_).count();
    last_ = now;
    return us;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

World::World(std::shared_ptr<const AnnotatedGrid> grid, std::vector<units::UnitType> catalogue,
             const WorldSettings& settings)
    : grid_(std::move(grid)),
      catalogue_(std::move(catalogue)),
      settings_(settings),
      rng_(settings.seed),
      parkedAt_(grid_->map().cellCount(), 0),
      claimedBy_(grid_->map().cellCount(), 0) {
  const std::vector<Capability> capabilities = capabilitiesOf(catalogue_);
  physics_ = std::make_unique<Physics>(grid_->map(), capabilities);
  paths_ =
      std::make_unique<PathService>(*grid_, settings_.pathing, capabilities, maxSizeOf(catalogue_));
  const GridMap& map = grid_->map();
  bucketsWide_ = (map.width() + kBucketCells - 1) / kBucketCells;
  bucketsHigh_ = (map.height() + kBucketCells - 1) / kBucketCells;
  maxUnitSize_ = maxSizeOf(catalogue_);
}

World::~World() = default;

UnitId World::spawn(int type, int team, int group, Cell anchor) {
  const units::UnitType& kind = catalogue_[static_cast<std::size_t>(type)];
  Unit unit;
  unit.id = {static_cast<std::uint32_t>(units_.size()), 0};
  unit.type = type;
  unit.team = team;
  unit.group = group;
  unit.hp = kind.hp;
  unit.position = units::anchorToCentre(anchor, kind.size);
  unit.body = physics_->addBody(unit.position, kind.radius, kind.capability);
  // A weapon is ready one cooldown after spawning, so that units spawned in range of each
  // other do not all fire in their first tick.
  if (kind.weapon) unit.readyTick = tick_ + units::cooldownTicks(*kind.weapon, settings_.tickRate);
  units_.push_back(std::move(unit));
  log(EventKind::Spawned, units_.back());
  return units_.back().id;
}

const Unit* World::find(UnitId id) const {
  if (id.index >= units_.size() || units_[id.index].id.generation != id.generation) return nullptr;
  return &units_[id.index];
}

int World::aliveCount(int team) const {
  int n = 0;
  for (const Unit& unit : units_)
    n += unit.alive() && unit.team == team ? 1 : 0;
  return n;
}

void World::order(Command command) {
  pending_.push_back(std::move(command));
}

void World::log(EventKind kind, const Unit& unit, int detail) {
  events_.push_back({tick_, kind, unit.id, detail});
}

const units::UnitType& World::typeOf(const Unit& unit) const {
  return catalogue_[static_cast<std::size_t>(unit.type)];
}

Cell World::nearestStandable(const Unit& unit) const {
  const units::UnitType& type = typeOf(unit);
  const Cell anchor = units::centreToAnchor(unit.position, type.size);
  if (grid_->canStand(type.agent(), anchor)) return anchor;
  // Pushed against an edge, the rounded anchor may straddle it: take the nearest cell where
  // the footprint fits (row-major order breaks ties).
  constexpr int kReach = 2;
  Cell best = anchor;
  double bestDistance = INFINITY;
  for (int y = anchor.y - kReach; y <= anchor.y + kReach; ++y) {
    for (int x = anchor.x - kReach; x <= anchor.x + kReach; ++x) {
      if (!grid_->canStand(type.agent(), {x, y})) continue;
      const double d = (units::anchorToCentre({x, y}, type.size) - unit.position).length();
      if (d < bestDistance) {
        bestDistance = d;
        best = {x, y};
      }
    }
  }
  return best;
}

void World::leaveOrder(Unit& unit) {
  const GridMap& map = grid_->map();
  if (unit.state == UnitState::Parked) {
    forFootprint(unit.goalCell, typeOf(unit).size, [&](Cell c) {
      std::uint32_t& owner = parkedAt_[map.indexOf(c)];
      if (owner == unit.id.index + 1) owner = 0;
    });
  }
  claimGoal(unit, false);
  unit.path.reset();
  unit.next = 0;
  unit.attackTargets.clear();
  unit.engaged = false;
  ++unit.pathSerial;  // answers to requests of the old order are stale
}

void World::applyCommand(const Command& command) {
  std::vector<Cell> candidates;
  int candidatesType = -1;
  std::size_t cursor = 0;
  for (UnitId id : command.units) {
    if (find(id) == nullptr || !units_[id.index].alive()) continue;
    Unit& unit = units_[id.index];
    leaveOrder(unit);
    unit.order = command.kind;
    log(EventKind::Ordered, unit, static_cast<int>(command.kind));
    switch (command.kind) {
      case OrderKind::Move:
      case OrderKind::AttackMove:
        if (unit.type != candidatesType) {
          candidates = shuffledStandable(typeOf(unit).agent(), command.area);
          candidatesType = unit.type;
          cursor = 0;
        }
        beginMove(unit, command.area, candidates, cursor);
        break;
      case OrderKind::Attack:
        for (UnitId t : command.targets) {
          const Unit* target = find(t);
          if (target != nullptr && target->alive() && target->team != unit.team)
            unit.attackTargets.push_back(t);
        }
        unit.target = {};
        unit.state = UnitState::Idle;
        pursue(unit, true);
        break;
      case OrderKind::Hold:
        // Holding a spot is parking where the unit stands: steering brings it back when shoved.
        unit.goalCell = nearestStandable(unit);
        unit.state = UnitState::Parked;
        forFootprint(unit.goalCell, typeOf(unit).size, [&](Cell c) {
          std::uint32_t& owner = parkedAt_[grid_->map().indexOf(c)];
          if (owner == 0) owner = unit.id.index + 1;
        });
        break;
      case OrderKind::Stop:
        unit.state = UnitState::Idle;
        break;
    }
  }
}

std::vector<Cell> World::shuffledStandable(Agent agent, const CellRect& area) {
  // Every cell of the area the agent can stand on, in an order drawn from the world RNG.
  std::vector<Cell> cells;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      if (grid_->canStand(agent, {x, y})) cells.push_back({x, y});
    }
  }
  for (std::size_t i = cells.size(); i > 1; --i)
    std::swap(cells[i - 1], cells[rng_.below(static_cast<std::uint32_t>(i))]);
  return cells;
}

void World::beginMove(Unit& unit, const CellRect& area, const std::vector<Cell>& candidates,
                      std::size_t& cursor) {
  const GridMap& map = grid_->map();
  const units::UnitType& type = typeOf(unit);
  const auto& components = grid_->layer(type.agent()).components();
  const std::uint32_t component = components[map.indexOf(nearestStandable(unit))];
  const auto fits = [&](Cell c, bool strict) {
    if (components[map.indexOf(c)] != component) return false;
    if (!strict) return true;
    bool free = true;
    forFootprint(c, type.size, [&](Cell f) {
      free = free && claimedBy_[map.indexOf(f)] == 0 && parkedAt_[map.indexOf(f)] == 0;
    });
    return free;
  };
  // Prefer a footprint nobody else was given; when the area is full, share one.
  std::optional<Cell> goal;
  for (bool strict : {true, false}) {
    for (std::size_t k = 0; k < candidates.size() && !goal; ++k) {
      const Cell c = candidates[(cursor + k) % candidates.size()];
      if (fits(c, strict)) {
        goal = c;
        cursor = (cursor + k + 1) % candidates.size();
      }
    }
    if (goal) break;
  }
  unit.goalArea = area;
  unit.orderTick = tick_;
  unit.arrivalTick = -1;
  unit.progress.reset(unit.position, tick_);
  if (!goal) {
    unit.state = UnitState::NoPath;
    log(EventKind::PathFailed, unit, static_cast<int>(PathStatus::Unreachable));
    return;
  }
  unit.goalCell = *goal;
  claimGoal(unit, true);
  unit.state = UnitState::WaitingPath;
  requestPath(unit);
}

std::optional<Cell> World::approachCell(const Unit& unit, const Unit& target) const {
  // The standable cell in the unit's own component nearest the target's centre, searched in
  // square rings around it out to the weapon's reach: the target may stand where the unit
  // cannot (infantry in a forest, an amphibious unit afloat).
  const units::UnitType& type = typeOf(unit);
  const GridMap& map = grid_->map();
  const auto& components = grid_->layer(type.agent()).components();
  const std::uint32_t component = components[map.indexOf(nearestStandable(unit))];
  const Cell centre = units::centreToAnchor(target.position, type.size);
  const int reach =
      static_cast<int>(std::ceil(type.weapon ? type.weapon->range : 0.0)) + typeOf(target).size;
  for (int r = 0; r <= reach; ++r) {
    std::optional<Cell> best;
    double bestDistance = INFINITY;
    for (int y = centre.y - r; y <= centre.y + r; ++y) {
      for (int x = centre.x - r; x <= centre.x + r; ++x) {
        if (std::max(std::abs(x - centre.x), std::abs(y - centre.y)) != r) continue;
        if (!grid_->canStand(type.agent(), {x, y})) continue;
        if (components[map.indexOf({x, y})] != component) continue;
        const double d = (units::anchorToCentre({x, y}, type.size) - target.position).length();
        if (d < bestDistance) {
          bestDistance = d;
          best = Cell{x, y};
        }
      }
    }
    if (best) return best;
  }
  return std::nullopt;
}

void World::pursue(Unit& unit, bool force) {
  // The living attack target nearest the unit (gap, then id).
  const units::Combatant self = combatantOf(unit);
  const Unit* chase = nullptr;
  double chaseGap = INFINITY;
  std::erase_if(unit.attackTargets, [&](UnitId t) { return !units_[t.index].alive(); });
  for (UnitId t : unit.attackTargets) {
    const double gap = units::gapSquared(self, combatantOf(units_[t.index]));
    if (gap < chaseGap) {
      chaseGap = gap;
      chase = &units_[t.index];
    }
  }
  if (chase == nullptr) {
    // Every target is dead: the order is done.
    leaveOrder(unit);
    unit.order = OrderKind::Stop;
    unit.state = UnitState::Idle;
    return;
  }
  const std::optional<Cell> cell = approachCell(unit, *chase);
  if (!cell) {
    unit.state = UnitState::NoPath;
    return;
  }
  if (!force && unit.state != UnitState::NoPath && chebyshev(*cell, unit.goalCell) <= 2) return;
  unit.goalCell = *cell;
  unit.progress.reset(unit.position, tick_);
  unit.state = UnitState::WaitingPath;
  requestPath(unit);
}

void World::claimGoal(const Unit& unit, bool claim) {
  const GridMap& map = grid_->map();
  const int size = typeOf(unit).size;
  forFootprint(unit.goalCell, size, [&](Cell c) {
    std::uint32_t& owner = claimedBy_[map.indexOf(c)];
    if (claim && owner == 0) owner = unit.id.index + 1;
    if (!claim && owner == unit.id.index + 1) owner = 0;
  });
}

void World::requestPath(Unit& unit) {
  ++unit.pathSerial;
  paths_->request(
      {unit.id, unit.pathSerial, typeOf(unit).agent(), nearestStandable(unit), unit.goalCell});
}

void World::deliver(const PathDelivery& delivery) {
  if (find(delivery.unit) == nullptr) return;
  Unit& unit = units_[delivery.unit.index];
  if (delivery.serial != unit.pathSerial || !unit.alive()) return;  // superseded, or dead
  if (delivery.status == PathStatus::Found) {
    unit.path = delivery.path;
    unit.next = 0;
    unit.state = UnitState::Moving;
    unit.progress.restartWindow(unit.position, tick_);
    log(EventKind::PathFound, unit);
  } else {
    unit.path.reset();
    unit.state = UnitState::NoPath;
    log(EventKind::PathFailed, unit, static_cast<int>(delivery.status));
  }
}

units::Combatant World::combatantOf(const Unit& unit) const {
  const units::UnitType& type = typeOf(unit);
  return {unit.id.index, unit.team, type.armour, type.size, unit.position, unit.hp};
}

void World::indexUnits() {
  // Counting sort of the living units into buckets of kBucketCells² cells (CSR layout), so a
  // scan for targets looks at the units near the shooter only.
  const std::size_t buckets = static_cast<std::size_t>(bucketsWide_ * bucketsHigh_);
  bucketStart_.assign(buckets + 1, 0);
  combatants_.clear();
  for (const Unit& unit : units_)
    combatants_.push_back(combatantOf(unit));
  const auto bucketOf = [&](const Unit& unit) {
    const int bx =
        std::clamp(static_cast<int>(unit.position.x) / kBucketCells, 0, bucketsWide_ - 1);
    const int by =
        std::clamp(static_cast<int>(unit.position.y) / kBucketCells, 0, bucketsHigh_ - 1);
    return static_cast<std::size_t>(by * bucketsWide_ + bx);
  };
  for (const Unit& unit : units_)
    if (unit.alive()) ++bucketStart_[bucketOf(unit) + 1];
  for (std::size_t b = 0; b < buckets; ++b)
    bucketStart_[b + 1] += bucketStart_[b];
  bucketUnits_.assign(bucketStart_[buckets], 0);
  bucketFill_.assign(bucketStart_.begin(), bucketStart_.end() - 1);
  for (const Unit& unit : units_)
    if (unit.alive()) bucketUnits_[bucketFill_[bucketOf(unit)]++] = unit.id.index;
}

std::optional<std::uint32_t> World::scanForTarget(const Unit& unit, const units::Weapon& weapon) {
  const units::Combatant& self = combatants_[unit.id.index];
  // Anything whose footprint comes within range has its centre within this reach.
  const double reach = weapon.range + 0.5 * (typeOf(unit).size + maxUnitSize_);
  const int bx0 = std::max(0, static_cast<int>(std::floor(unit.position.x - reach)) / kBucketCells);
  const int by0 = std::max(0, static_cast<int>(std::floor(unit.position.y - reach)) / kBucketCells);
  const int bx1 = std::min(bucketsWide_ - 1,
                           static_cast<int>(std::floor(unit.position.x + reach)) / kBucketCells);
  const int by1 = std::min(bucketsHigh_ - 1,
                           static_cast<int>(std::floor(unit.position.y + reach)) / kBucketCells);
  candidates_.clear();
  for (int by = by0; by <= by1; ++by) {
    for (int bx = bx0; bx <= bx1; ++bx) {
      const auto b = static_cast<std::size_t>(by * bucketsWide_ + bx);
      for (std::uint32_t i = bucketStart_[b]; i < bucketStart_[b + 1]; ++i)
        candidates_.push_back(combatants_[bucketUnits_[i]]);
    }
  }
  return units::acquireTarget(weapon, self, candidates_, grid_->map(), settings_.combat.sight);
}

void World::chooseTargets() {
  indexUnits();
  const GridMap& map = grid_->map();
  const units::SightRules& sight = settings_.combat.sight;
  const auto every = static_cast<std::int64_t>(settings_.combat.scanEveryTicks);
  for (Unit& unit : units_) {
    unit.engaged = false;
    const units::UnitType& type = typeOf(unit);
    if (!unit.alive() || !type.weapon) continue;
    const units::Weapon& weapon = *type.weapon;
    const units::Combatant& self = combatants_[unit.id.index];
    if (unit.order == OrderKind::Attack) {
      // Ordered targets only: the nearest of them, once it can be engaged.
      std::erase_if(unit.attackTargets, [&](UnitId t) { return !units_[t.index].alive(); });
      unit.target = {};
      double best = INFINITY;
      for (UnitId t : unit.attackTargets) {
        const units::Combatant& other = combatants_[t.index];
        const double gap = units::gapSquared(self, other);
        if (gap < best && units::canEngage(weapon, self, other, map, sight)) {
          best = gap;
          unit.target = t;
        }
      }
      unit.engaged = unit.target.valid();
      continue;
    }
    // Sticky: keep a target while it may be engaged; otherwise scan, staggered by id.
    const bool keep = unit.target.valid() &&
                      units::canEngage(weapon, self, combatants_[unit.target.index], map, sight);
    if (!keep && (unit.target.valid() || (tick_ + unit.id.index) % every == 0)) {
      const std::optional<std::uint32_t> found = scanForTarget(unit, weapon);
      unit.target = found ? units_[*found].id : UnitId{};
    }
    unit.engaged = unit.target.valid() && unit.order == OrderKind::AttackMove;
  }
}

void World::fire() {
  lastTickShots_.clear();
  for (Unit& unit : units_) {
    const units::UnitType& type = typeOf(unit);
    if (!unit.alive() || !type.weapon || !unit.target.valid() || tick_ < unit.readyTick) continue;
    const units::Weapon& weapon = *type.weapon;
    const Unit& target = units_[unit.target.index];
    const double gap = std::sqrt(units::gapSquared(combatantOf(unit), combatantOf(target)));
    Shot shot;
    shot.shooter = unit.id;
    shot.target = target.id;
    shot.damage = units::damageDealt(weapon, typeOf(target).armour, settings_.combat.armour);
    shot.firedTick = tick_;
    shot.landTick = tick_ + units::travelTicks(weapon, gap, settings_.tickRate);
    shot.from = unit.position;
    shot.to = target.position;
    unit.readyTick = tick_ + units::cooldownTicks(weapon, settings_.tickRate);
    ++unit.combat.shotsFired;
    inFlight_.push_back(shot);
    lastTickShots_.push_back(shot);
  }
  // Shots land in the order fired, including those of shooters that died meanwhile.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < inFlight_.size(); ++i) {
    const Shot& shot = inFlight_[i];
    if (shot.landTick > tick_) {
      inFlight_[kept++] = shot;
      continue;
    }
    Unit& target = units_[shot.target.index];
    if (!target.alive()) continue;  // already dead: the shot is wasted
    Unit& shooter = units_[shot.shooter.index];
    const int dealt = std::min(shot.damage, target.hp);
    target.hp = units::applyDamage(target.hp, shot.damage);
    target.combat.damageTaken += dealt;
    shooter.combat.damageDealt += dealt;
    ++shooter.combat.hits;
    if (!target.alive()) {
      ++shooter.combat.kills;
      kill(target, shooter.id);
    }
  }
  inFlight_.resize(kept);
}

void World::kill(Unit& unit, UnitId killer) {
  leaveOrder(unit);
  unit.state = UnitState::Dead;
  unit.order = OrderKind::Stop;
  unit.target = {};
  unit.deathTick = tick_;
  unit.killedBy = killer;
  unit.velocity = {};
  paths_->cancel(unit.id);
  const double wreck = settings_.combat.wreckSeconds;
  if (wreck > 0.0) {
    physics_->freeze(unit.body);
    unit.wreckUntilTick =
        tick_ + std::max<std::int64_t>(1, std::llround(wreck * settings_.tickRate));
  } else {
    physics_->removeBody(unit.body);
  }
  log(EventKind::Killed, unit, static_cast<int>(killer.index));
}

void World::steerAll() {
  const double dt = 1.0 / settings_.tickRate;
  const GridMap& map = grid_->map();
  for (Unit& unit : units_) {
    if (!unit.alive()) continue;
    const units::UnitType& type = typeOf(unit);
    Vec2 desired;
    if (unit.engaged) {
      // Halted to fight: the stall is on purpose, not a jam.
      unit.progress.restartWindow(unit.position, tick_);
    } else if (unit.state == UnitState::Parked) {
      // Hold the goal cell: a unit shoved off it steers back.
      const Cell goal[] = {unit.goalCell};
      const units::SteeringResult r =
          units::steer(goal, 0, type.size, unit.position, type.maxSpeed(), settings_.steering);
      desired = r.desiredVelocity;
    } else if (unit.state == UnitState::Moving && unit.path) {
      const Cell under{static_cast<int>(std::floor(unit.position.x)),
                       static_cast<int>(std::floor(unit.position.y))};
      double speed = type.speedOn(map.at(under));
      if (!(speed > 0.0)) speed = type.maxSpeed();
      const units::SteeringResult r =
          units::steer(*unit.path, unit.next, type.size, unit.position, speed, settings_.steering);
      unit.next = r.next;
      desired = r.desiredVelocity;
      if (r.reachedEnd) {
        if (unit.order == OrderKind::Attack) {
          // At the approach cell: wait there for the target to come into sight or move.
          unit.state = UnitState::Idle;
        } else {
          unit.state = UnitState::Parked;
          forFootprint(unit.goalCell, type.size,
                       [&](Cell c) { parkedAt_[map.indexOf(c)] = unit.id.index + 1; });
          log(EventKind::Parked, unit);
        }
      }
    }
    const Vec2 v =
        units::limitVelocity(unit.velocity, desired, type.acceleration, type.turnRate, dt);
    physics_->setVelocity(unit.body, v);
  }
}

bool World::reassignGoal(Unit& unit) {
  const units::UnitType& type = typeOf(unit);
  const Agent agent = type.agent();
  const GridMap& map = grid_->map();
  const auto& components = grid_->layer(agent).components();
  const std::uint32_t component = components[map.indexOf(nearestStandable(unit))];
  std::optional<Cell> best;
  double bestDistance = INFINITY;
  const CellRect& area = unit.goalArea;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      if (!grid_->canStand(agent, c) || components[map.indexOf(c)] != component) continue;
      bool free = true;
      forFootprint(c, type.size, [&](Cell f) {
        const std::uint32_t parked = parkedAt_[map.indexOf(f)];
        const std::uint32_t claimed = claimedBy_[map.indexOf(f)];
        free = free && (parked == 0 || parked == unit.id.index + 1) &&
               (claimed == 0 || claimed == unit.id.index + 1);
      });
      const double d = (units::anchorToCentre(c, type.size) - unit.position).length();
      if (free && d < bestDistance) {
        bestDistance = d;
        best = c;
      }
    }
  }
  if (!best || *best == unit.goalCell) return false;
  claimGoal(unit, false);
  unit.goalCell = *best;
  claimGoal(unit, true);
  return true;
}

void World::applyRules() {
  const GridMap& map = grid_->map();
  for (Unit& unit : units_) {
    if (!unit.alive()) {
      if (unit.wreckUntilTick >= 0 && tick_ >= unit.wreckUntilTick) {
        physics_->removeBody(unit.body);
        unit.wreckUntilTick = -1;
        log(EventKind::WreckCleared, unit);
      }
      continue;
    }
    const units::UnitType& type = typeOf(unit);
    const Cell anchor = units::centreToAnchor(unit.position, type.size);
    if (unit.orderTick >= 0 && unit.arrivalTick < 0 && unit.goalArea.contains(anchor)) {
      unit.arrivalTick = tick_;
      log(EventKind::Arrived, unit);
    }
    if (unit.order == OrderKind::Attack) {
      // Follow the target as it moves, about once a second (staggered by id).
      const auto second = static_cast<std::int64_t>(std::max(1.0, std::round(settings_.tickRate)));
      if (!unit.engaged && (tick_ + unit.id.index) % second == 0) pursue(unit, false);
      if (unit.order != OrderKind::Attack) continue;
    }
    if (unit.state != UnitState::Moving || unit.engaged) continue;
    const std::vector<Cell>& path = *unit.path;
    const bool movingToArea = unit.order != OrderKind::Attack;
    // The goal cell was taken by a unit that parked there first: pick the nearest free one.
    const bool nearEnd = unit.next + static_cast<std::size_t>(type.size) + 2 >= path.size();
    bool goalTaken = false;
    forFootprint(unit.goalCell, type.size, [&](Cell c) {
      const std::uint32_t owner = parkedAt_[map.indexOf(c)];
      goalTaken = goalTaken || (owner != 0 && owner != unit.id.index + 1);
    });
    if (movingToArea && nearEnd && goalTaken && reassignGoal(unit)) {
      log(EventKind::Repath, unit, 2);
      requestPath(unit);
      continue;
    }
    // Pushed off its path: the next waypoint is more than a step away, and steering straight
    // at it could cut a corner the path went around.
    if (chebyshev(anchor, path[unit.next]) > 2) {
      log(EventKind::Repath, unit, 1);
      requestPath(unit);
      unit.state = UnitState::WaitingPath;
      continue;
    }
    if (unit.progress.update(unit.position, tick_, settings_.tickRate, settings_.stuck)) {
      ++unit.repaths;
      if (unit.progress.stuckWindows() == settings_.stuck.flagAfter) {
        unit.everStuck = true;
        log(EventKind::StuckFlagged, unit);
      }
      // Near the goal, a crowd is the likely cause: a free goal cell resolves it.
      if (movingToArea && nearEnd) reassignGoal(unit);
      log(EventKind::Repath, unit, 0);
      requestPath(unit);
    }
  }
}

void World::step() {
  Stopwatch watch;
  const TickTiming before = timing_;
  for (const Command& command : pending_)
    applyCommand(command);
  pending_.clear();
  timing_.bookkeepingMicros += watch.lap();

  deliveries_.clear();
  paths_->serve(deliveries_);
  for (const PathDelivery& delivery : deliveries_)
    deliver(delivery);
  timing_.pathingMicros += watch.lap();

  const bool combat = settings_.combat.enabled;
  if (combat) chooseTargets();
  timing_.combatMicros += watch.lap();
  steerAll();
  timing_.steeringMicros += watch.lap();
  if (combat) fire();
  timing_.combatMicros += watch.lap();

  physics_->step(1.0 / settings_.tickRate);
  for (Unit& unit : units_) {
    if (!unit.alive()) continue;
    unit.position = physics_->position(unit.body);
    unit.velocity = physics_->velocity(unit.body);
  }
  timing_.physicsMicros += watch.lap();

  ++tick_;
  applyRules();
  stateHash_ = computeHash();
  timing_.bookkeepingMicros += watch.lap();
  ++timing_.ticks;
  const double tickMicros = (timing_.pathingMicros - before.pathingMicros) +
                            (timing_.combatMicros - before.combatMicros) +
                            (timing_.steeringMicros - before.steeringMicros) +
                            (timing_.physicsMicros - before.physicsMicros) +
                            (timing_.bookkeepingMicros - before.bookkeepingMicros);
  timing_.slowestTickMicros = std::max(timing_.slowestTickMicros, tickMicros);
}

TickTiming World::meanTiming() const {
  TickTiming mean = timing_;
  if (timing_.ticks > 0) {
    const auto n = static_cast<double>(timing_.ticks);
    mean.pathingMicros /= n;
    mean.combatMicros /= n;
    mean.steeringMicros /= n;
    mean.physicsMicros /= n;
    mean.bookkeepingMicros /= n;
  }
  return mean;
}

namespace {

class Fnv1a {
 public:
  void add(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      hash_ ^= (v >> (8 * i)) & 0xFFu;
      hash_ *= 0x100000001B3ull;
    }
  }
  void add(std::int64_t v) { add(static_cast<std::uint64_t>(v)); }
  void add(int v) { add(static_cast<std::int64_t>(v)); }
  void add(UnitId id) { add(static_cast<std::uint64_t>(id.index) << 32 | id.generation); }
  // Quantised to 1/1024 cell (or cell/s) so that the hash ignores float noise below that.
  void add(double v) { add(static_cast<std::int64_t>(std::llround(v * 1024.0))); }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xCBF29CE484222325ull;
};

}  // namespace

std::uint64_t World::computeHash() const {
  Fnv1a h;
  h.add(tick_);
  for (const Unit& unit : units_) {
    h.add(unit.id);
    h.add(unit.position.x);
    h.add(unit.position.y);
    h.add(unit.velocity.x);
    h.add(unit.velocity.y);
    h.add(unit.hp);
    h.add(static_cast<std::uint64_t>(unit.state));
    h.add(static_cast<std::uint64_t>(unit.order));
    h.add(unit.goalCell.x);
    h.add(unit.goalCell.y);
    h.add(unit.arrivalTick);
    h.add(unit.pathSerial);
    h.add(static_cast<std::uint64_t>(unit.next));
    h.add(unit.target);
    h.add(unit.readyTick);
    h.add(unit.wreckUntilTick);
  }
  for (const Shot& shot : inFlight_) {
    h.add(shot.shooter);
    h.add(shot.target);
    h.add(shot.damage);
    h.add(shot.landTick);
  }
  return h.value();
}

}  // namespace warpath::engine
