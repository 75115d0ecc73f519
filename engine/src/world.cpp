#include "engine/world.h"

#include <algorithm>
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
  }
  return "?";
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
  units_.push_back(std::move(unit));
  log(EventKind::Spawned, units_.back());
  return units_.back().id;
}

const Unit* World::find(UnitId id) const {
  if (id.index >= units_.size() || units_[id.index].id.generation != id.generation) return nullptr;
  return &units_[id.index];
}

void World::orderMove(std::vector<UnitId> ids, CellRect area) {
  pending_.push_back({std::move(ids), area});
}

void World::log(EventKind kind, const Unit& unit, int detail) {
  events_.push_back({tick_, kind, unit.id, detail});
}

Cell World::nearestStandable(const Unit& unit) const {
  const units::UnitType& type = catalogue_[static_cast<std::size_t>(unit.type)];
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

void World::applyCommand(const MoveCommand& command) {
  const GridMap& map = grid_->map();
  std::vector<Cell> candidates;
  int candidatesType = -1;
  std::size_t cursor = 0;
  for (UnitId id : command.units) {
    if (find(id) == nullptr) continue;
    Unit& unit = units_[id.index];
    const units::UnitType& type = catalogue_[static_cast<std::size_t>(unit.type)];
    const Agent agent = type.agent();
    if (unit.type != candidatesType) {
      // Every cell of the area the type can stand on, in an order drawn from the world RNG.
      candidates.clear();
      for (int y = command.area.y; y < command.area.y + command.area.height; ++y) {
        for (int x = command.area.x; x < command.area.x + command.area.width; ++x) {
          if (grid_->canStand(agent, {x, y})) candidates.push_back({x, y});
        }
      }
      for (std::size_t i = candidates.size(); i > 1; --i)
        std::swap(candidates[i - 1], candidates[rng_.below(static_cast<std::uint32_t>(i))]);
      candidatesType = unit.type;
      cursor = 0;
    }
    if (unit.state == UnitState::Parked) {
      forFootprint(unit.goalCell, type.size, [&](Cell c) { parkedAt_[map.indexOf(c)] = 0; });
    }
    const auto& components = grid_->layer(agent).components();
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
    unit.goalArea = command.area;
    unit.orderTick = tick_;
    unit.arrivalTick = -1;
    unit.progress.reset(unit.position, tick_);
    unit.path.reset();
    log(EventKind::Ordered, unit);
    if (!goal) {
      unit.state = UnitState::NoPath;
      log(EventKind::PathFailed, unit, static_cast<int>(PathStatus::Unreachable));
      continue;
    }
    unit.goalCell = *goal;
    claimGoal(unit, true);
    unit.state = UnitState::WaitingPath;
    requestPath(unit);
  }
}

void World::claimGoal(const Unit& unit, bool claim) {
  const GridMap& map = grid_->map();
  const int size = catalogue_[static_cast<std::size_t>(unit.type)].size;
  forFootprint(unit.goalCell, size, [&](Cell c) {
    std::uint32_t& owner = claimedBy_[map.indexOf(c)];
    if (claim && owner == 0) owner = unit.id.index + 1;
    if (!claim && owner == unit.id.index + 1) owner = 0;
  });
}

void World::requestPath(Unit& unit) {
  const units::UnitType& type = catalogue_[static_cast<std::size_t>(unit.type)];
  ++unit.pathSerial;
  paths_->request({unit.id, unit.pathSerial, type.agent(), nearestStandable(unit), unit.goalCell});
}

void World::deliver(const PathDelivery& delivery) {
  if (find(delivery.unit) == nullptr) return;
  Unit& unit = units_[delivery.unit.index];
  if (delivery.serial != unit.pathSerial) return;  // superseded by a later request
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

void World::steerAll() {
  const double dt = 1.0 / settings_.tickRate;
  const GridMap& map = grid_->map();
  for (Unit& unit : units_) {
    const units::UnitType& type = catalogue_[static_cast<std::size_t>(unit.type)];
    Vec2 desired;
    if (unit.state == UnitState::Parked) {
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
        unit.state = UnitState::Parked;
        forFootprint(unit.goalCell, type.size,
                     [&](Cell c) { parkedAt_[map.indexOf(c)] = unit.id.index + 1; });
        log(EventKind::Parked, unit);
      }
    }
    const Vec2 v =
        units::limitVelocity(unit.velocity, desired, type.acceleration, type.turnRate, dt);
    physics_->setVelocity(unit.body, v);
  }
}

bool World::reassignGoal(Unit& unit) {
  const units::UnitType& type = catalogue_[static_cast<std::size_t>(unit.type)];
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
    const units::UnitType& type = catalogue_[static_cast<std::size_t>(unit.type)];
    const Cell anchor = units::centreToAnchor(unit.position, type.size);
    if (unit.orderTick >= 0 && unit.arrivalTick < 0 && unit.goalArea.contains(anchor)) {
      unit.arrivalTick = tick_;
      log(EventKind::Arrived, unit);
    }
    if (unit.state != UnitState::Moving) continue;
    const std::vector<Cell>& path = *unit.path;
    // The goal cell was taken by a unit that parked there first: pick the nearest free one.
    const bool nearEnd = unit.next + static_cast<std::size_t>(type.size) + 2 >= path.size();
    bool goalTaken = false;
    forFootprint(unit.goalCell, type.size, [&](Cell c) {
      const std::uint32_t owner = parkedAt_[map.indexOf(c)];
      goalTaken = goalTaken || (owner != 0 && owner != unit.id.index + 1);
    });
    if (nearEnd && goalTaken && reassignGoal(unit)) {
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
      if (nearEnd) reassignGoal(unit);
      log(EventKind::Repath, unit, 0);
      requestPath(unit);
    }
  }
}

void World::step() {
  Stopwatch watch;
  const TickTiming before = timing_;
  for (const MoveCommand& command : pending_)
    applyCommand(command);
  pending_.clear();
  timing_.bookkeepingMicros += watch.lap();

  deliveries_.clear();
  paths_->serve(deliveries_);
  for (const PathDelivery& delivery : deliveries_)
    deliver(delivery);
  timing_.pathingMicros += watch.lap();

  steerAll();
  timing_.steeringMicros += watch.lap();

  physics_->step(1.0 / settings_.tickRate);
  for (Unit& unit : units_) {
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
    h.add(static_cast<std::uint64_t>(unit.id.index) << 32 | unit.id.generation);
    h.add(unit.position.x);
    h.add(unit.position.y);
    h.add(unit.velocity.x);
    h.add(unit.velocity.y);
    h.add(static_cast<std::int64_t>(unit.hp));
    h.add(static_cast<std::uint64_t>(unit.state));
    h.add(static_cast<std::int64_t>(unit.goalCell.x));
    h.add(static_cast<std::int64_t>(unit.goalCell.y));
    h.add(unit.arrivalTick);
    h.add(unit.pathSerial);
    h.add(static_cast<std::uint64_t>(unit.next));
  }
  return h.value();
}

}  // namespace warpath::engine
