#include "engine/scenario_run.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "engine/state_description.h"

namespace warpath::engine {

double percentile(const std::vector<double>& sorted, double p) {
  const auto n = static_cast<double>(sorted.size());
  const auto rank = static_cast<std::size_t>(std::max(1.0, std::ceil(p / 100.0 * n)));
  return sorted[std::min(rank, sorted.size()) - 1];
}

bool Report::passed() const {
  return std::all_of(expectations.begin(), expectations.end(),
                     [](const ExpectationResult& e) { return e.pass; });
}

WorldSettings ScenarioRun::settingsFor(const Scenario& scenario,
                                       std::optional<std::uint64_t> seed) {
  WorldSettings settings = scenario.settings;
  if (seed) settings.seed = *seed;
  return settings;
}

namespace {

bool insideArea(const Unit& u, const pathing::CellRect& area, const World& world) {
  const int size = world.catalogue()[static_cast<std::size_t>(u.type)].size;
  return area.contains(units::centreToAnchor(u.position, size));
}

// One unit's share of a battle statistic.
double statOf(const Unit& u, StatKind stat) {
  switch (stat) {
    case StatKind::Kills:
      return u.combat.kills;
    case StatKind::Losses:
      return u.alive() ? 0.0 : 1.0;
    case StatKind::DamageDealt:
      return u.combat.damageDealt;
    case StatKind::DamageTaken:
      return u.combat.damageTaken;
    case StatKind::ShotsFired:
      return u.combat.shotsFired;
    case StatKind::Alive:
      return u.alive() ? 1.0 : 0.0;
  }
  return 0.0;
}

RunState initialState(const Scenario& scenario) {
  RunState s;
  s.members.resize(scenario.groups.size());
  s.spawned.assign(scenario.groups.size(), false);
  s.exited.resize(scenario.victory.size());
  s.exitedCount.assign(scenario.victory.size(), 0);
  s.holdSince.assign(scenario.victory.size(), -1);
  return s;
}

}  // namespace

namespace {

// Whether `u` is of `team` and `type` (-1: any).
bool matches(const Unit& u, int team, int type) {
  return (team < 0 || u.team == team) && (type < 0 || u.type == type);
}

// Ascending delays (time to arrive / planned time) of the units of (team, type) that were
// planned a time; those that never arrived count as +inf when `lateCounts`, else not at all.
std::vector<double> delaysOf(const std::vector<Unit>& units, int team, int type, bool lateCounts) {
  std::vector<double> delays;
  for (const Unit& u : units) {
    if (!matches(u, team, type) || u.plannedTicks <= 0) continue;
    if (u.arrivalTick >= 0) {
      delays.push_back(static_cast<double>(u.arrivalTick - u.orderTick) /
                       static_cast<double>(u.plannedTicks));
    } else if (lateCounts) {
      delays.push_back(std::numeric_limits<double>::infinity());
    }
  }
  std::sort(delays.begin(), delays.end());
  return delays;
}

DelayStats delayOf(const std::vector<Unit>& units, int team, int type) {
  std::vector<double> delays = delaysOf(units, team, type, false);
  DelayStats d;
  d.arrived = static_cast<int>(delays.size());
  if (delays.empty()) return d;
  d.p50 = percentile(delays, 50);
  d.p90 = percentile(delays, 90);
  d.max = delays.back();
  d.delays = std::move(delays);
  return d;
}

}  // namespace

std::uint64_t ScenarioRun::stateHash() const {
  return stateHash(kStateFormat);
}

std::uint64_t ScenarioRun::stateHash(std::uint32_t format) const {
  StateHasher h(format);
  h.addWord(world_.stateHash(format));
  describe(h, state_);
  h.addWord(issued_.size());
  return h.value();
}

ScenarioRun::ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed)
    : scenario_(scenario),
      seed_(settingsFor(scenario, seed).seed),
      world_(scenario.grid, scenario.catalogue, settingsFor(scenario, seed)),
      state_(initialState(scenario)),
      fired_(scenario.triggers.size(), false) {
  for (std::size_t g = 0; g < scenario.groups.size(); ++g) {
    if (!scenario.groups[g].reinforcement) spawnGroup(static_cast<int>(g), true);
  }
  fireTriggers();  // those whose condition holds at the start (`at: 0`, ...)
}

ScenarioRun::ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed,
                         std::vector<IssuedOrder> script)
    : scenario_(scenario),
      seed_(settingsFor(scenario, seed).seed),
      world_(scenario.grid, scenario.catalogue, settingsFor(scenario, seed)),
      script_(std::move(script)),
      state_(initialState(scenario)) {
  // The live run's group goals are the script's first entries: spawning draws nothing from the
  // RNG and orders wait in the world until its next step, so spawning every group before the
  // tick-0 entries changes nothing.
  for (std::size_t g = 0; g < scenario.groups.size(); ++g) {
    if (!scenario.groups[g].reinforcement) spawnGroup(static_cast<int>(g), false);
  }
  playScript();
}

// Spawns a group at its anchors and, with `orderGoal` and a goal, orders it there (in playback
// that order is the script's next entry). A group spawns once.
void ScenarioRun::spawnGroup(int g, bool orderGoal) {
  const auto gi = static_cast<std::size_t>(g);
  if (g < 0 || gi >= state_.members.size() || state_.spawned[gi]) return;
  const GroupSpec& group = scenario_.groups[gi];
  for (pathing::Cell anchor : group.anchors)
    state_.members[gi].push_back(world_.spawn(group.type, group.team, g, anchor));
  state_.spawned[gi] = true;
  if (orderGoal && group.goal) give({OrderKind::Move, state_.members[gi], *group.goal, {}});
}

std::vector<UnitId> ScenarioRun::living(const std::vector<int>& groups) const {
  std::vector<UnitId> ids;
  for (int g : groups) {
    if (g < 0 || static_cast<std::size_t>(g) >= state_.members.size()) continue;
    for (UnitId id : state_.members[static_cast<std::size_t>(g)]) {
      const Unit* unit = world_.find(id);
      if (unit != nullptr && unit->alive()) ids.push_back(id);
    }
  }
  std::sort(ids.begin(), ids.end(), [](UnitId a, UnitId b) { return a.index < b.index; });
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

void ScenarioRun::give(Command command) {
  issued_.push_back({world_.tick(), IssuedKind::Order, command, -1});
  world_.order(std::move(command));
}

void ScenarioRun::setTerrain(pathing::CellRect area, pathing::Terrain terrain) {
  Command where;
  where.area = area;
  issued_.push_back({world_.tick(), IssuedKind::SetTerrain, where, static_cast<int>(terrain)});
  world_.setTerrain(area, terrain);
}

void ScenarioRun::endBattle(int team, std::string how) {
  if (state_.ended) return;
  state_.ended = true;
  state_.winner = team;
  victory_ = std::move(how);
  state_.endTick = world_.tick();
}

// The script's entries due by the current tick, in order.
void ScenarioRun::playScript() {
  const std::vector<IssuedOrder>& script = *script_;
  for (; scriptNext_ < script.size() && script[scriptNext_].tick <= world_.tick() && !state_.ended;
       ++scriptNext_) {
    const IssuedOrder& entry = script[scriptNext_];
    switch (entry.kind) {
      case IssuedKind::Order:
        give(entry.command);
        break;
      case IssuedKind::Reinforce:
        if (entry.group < 0 || static_cast<std::size_t>(entry.group) >= state_.members.size() ||
            state_.spawned[static_cast<std::size_t>(entry.group)])
          break;
        issued_.push_back({world_.tick(), IssuedKind::Reinforce, {}, entry.group});
        spawnGroup(entry.group, false);
        break;
      case IssuedKind::EndBattle: {
        const int team =
            entry.group >= 0 && static_cast<std::size_t>(entry.group) < scenario_.teams.size()
                ? entry.group
                : -1;
        issued_.push_back({world_.tick(), IssuedKind::EndBattle, {}, team});
        endBattle(team, "end_battle (played from the script)");
        break;
      }
      case IssuedKind::SetTerrain:
        setTerrain(entry.command.area, static_cast<pathing::Terrain>(entry.group));
        break;
    }
  }
}

bool ScenarioRun::triggerDue(const TriggerSpec& trigger) const {
  const auto groupOf = [&]() -> const std::vector<UnitId>* {
    if (trigger.group < 0 || static_cast<std::size_t>(trigger.group) >= state_.members.size())
      return nullptr;
    return &state_.members[static_cast<std::size_t>(trigger.group)];
  };
  switch (trigger.kind) {
    case TriggerKind::At:
      return world_.tick() >= std::llround(trigger.at * world_.tickRate());
    case TriggerKind::Arrived: {
      const std::vector<UnitId>* group = groupOf();
      if (group == nullptr || group->empty()) return false;
      int arrived = 0;
      for (UnitId id : *group) {
        const Unit* unit = world_.find(id);
        arrived += unit != nullptr && unit->arrivalTick >= 0 ? 1 : 0;
      }
      return static_cast<double>(arrived) >= trigger.fraction * static_cast<double>(group->size());
    }
    case TriggerKind::TeamBelow:
      return world_.aliveCount(trigger.team) < trigger.count;
    case TriggerKind::Enters: {
      const std::vector<UnitId>* group = groupOf();
      if (group == nullptr) return false;
      int inside = 0;
      for (UnitId id : *group) {
        const Unit* unit = world_.find(id);
        if (unit != nullptr && unit->alive() && insideArea(*unit, trigger.area, world_)) ++inside;
      }
      return inside >= trigger.count;
    }
    case TriggerKind::Dies: {
      const std::vector<UnitId>* group = groupOf();
      if (group == nullptr) return false;
      int dead = 0;
      for (UnitId id : *group) {
        const Unit* unit = world_.find(id);
        dead += unit != nullptr && !unit->alive() ? 1 : 0;
      }
      return dead >= trigger.count;
    }
  }
  return false;
}

void ScenarioRun::runAction(const TriggerSpec& trigger, const ActionSpec& action) {
  switch (action.kind) {
    case ActionKind::Order: {
      Command command;
      command.kind = action.order;
      command.units = living(action.groups);
      if (action.order == OrderKind::Move || action.order == OrderKind::AttackMove)
        command.area = action.area;
      if (action.order == OrderKind::Attack) command.targets = living(action.targetGroups);
      give(std::move(command));
      break;
    }
    case ActionKind::Reinforce:
      if (action.group < 0 || static_cast<std::size_t>(action.group) >= state_.members.size() ||
          state_.spawned[static_cast<std::size_t>(action.group)])
        break;  // a group comes in once
      issued_.push_back({world_.tick(), IssuedKind::Reinforce, {}, action.group});
      spawnGroup(action.group, true);  // its goal order is recorded after the reinforcement
      break;
    case ActionKind::EndBattle:
      issued_.push_back({world_.tick(), IssuedKind::EndBattle, {}, action.team});
      endBattle(action.team, "end_battle by trigger " + trigger.name);
      break;
    case ActionKind::SetTerrain:
      setTerrain(action.area, action.terrain);
      break;
  }
}

void ScenarioRun::fireTriggers() {
  for (std::size_t i = 0; i < scenario_.triggers.size() && !state_.ended; ++i) {
    if (fired_[i]) continue;
    const TriggerSpec& trigger = scenario_.triggers[i];
    if (!triggerDue(trigger)) continue;
    fired_[i] = true;
    triggersFired_.push_back(trigger.name);
    for (const ActionSpec& action : trigger.actions) {
      if (state_.ended) break;  // nothing is done after the end of the battle
      runAction(trigger, action);
    }
  }
}

void ScenarioRun::judgeVictory() {
  const std::vector<Unit>& units = world_.units();
  for (std::size_t v = 0; v < scenario_.victory.size() && !state_.ended; ++v) {
    const VictorySpec& spec = scenario_.victory[v];
    bool met = false;
    switch (spec.kind) {
      case VictoryKind::Eliminate: {
        met = world_.aliveCount(spec.team) > 0;
        for (std::size_t t = 0; t < scenario_.teams.size() && met; ++t) {
          if (static_cast<int>(t) != spec.team && world_.aliveCount(static_cast<int>(t)) > 0)
            met = false;
        }
        break;
      }
      case VictoryKind::Exit: {
        std::vector<bool>& exited = state_.exited[v];
        exited.resize(units.size(), false);
        for (const Unit& u : units) {
          if (u.team != spec.team || !u.alive() || exited[u.id.index]) continue;
          if (insideArea(u, spec.area, world_)) {
            exited[u.id.index] = true;
            ++state_.exitedCount[v];
          }
        }
        met = state_.exitedCount[v] >= spec.count;
        break;
      }
      case VictoryKind::HoldArea: {
        bool ours = false;
        bool theirs = false;
        for (const Unit& u : units) {
          if (!u.alive() || !insideArea(u, spec.area, world_)) continue;
          (u.team == spec.team ? ours : theirs) = true;
        }
        if (!ours || theirs) {
          state_.holdSince[v] = -1;
          break;
        }
        if (state_.holdSince[v] < 0) state_.holdSince[v] = world_.tick();
        met = world_.tick() - state_.holdSince[v] >= std::llround(spec.seconds * world_.tickRate());
        break;
      }
    }
    if (met) endBattle(spec.team, spec.text.empty() ? describe(spec, scenario_.teams) : spec.text);
  }
}

void ScenarioRun::step() {
  if (state_.ended) return;
  world_.step();
  judgeVictory();
  if (script_) {
    playScript();
  } else {
    fireTriggers();
  }
}

Report ScenarioRun::report() const {
  Report r;
  r.scenario = scenario_.name;
  r.seed = seed_;
  r.ticks = world_.tick();
  r.simSeconds = world_.seconds();
  r.stateHash = stateHash();
  r.complete = done();
  if (state_.winner >= 0) r.winner = scenario_.teams[static_cast<std::size_t>(state_.winner)];
  r.victory = victory_;
  r.endTick = state_.endTick;
  r.triggersFired = triggersFired_;
  r.pathing = world_.pathService().metrics();
  const double rate = world_.tickRate();
  const std::vector<Unit>& units = world_.units();

  // Ascending times-to-arrive of the matching units; +inf for those not (yet) arrived.
  const auto arrivalTimes = [&](int team, int type) {
    std::vector<double> times;
    for (const Unit& u : units) {
      if (!matches(u, team, type)) continue;
      times.push_back(u.arrivalTick >= 0 ? static_cast<double>(u.arrivalTick - u.orderTick) / rate
                                         : std::numeric_limits<double>::infinity());
    }
    std::sort(times.begin(), times.end());
    return times;
  };

  // Arrivals and battle statistics per (team, type), from one pass over the pair's units.
  for (std::size_t team = 0; team < scenario_.teams.size(); ++team) {
    for (std::size_t type = 0; type < scenario_.catalogue.size(); ++type) {
      ArrivalStats s;
      BattleStats b;
      s.team = b.team = scenario_.teams[team];
      s.type = b.type = scenario_.catalogue[type].name;
      for (const Unit& u : units) {
        if (!matches(u, static_cast<int>(team), static_cast<int>(type))) continue;
        ++s.units;
        if (u.arrivalTick >= 0) {
          ++s.arrived;
          s.arrivedAt.push_back(static_cast<double>(u.arrivalTick) / rate);
        }
        s.dead += u.hp <= 0 ? 1 : 0;
        (u.alive() ? b.alive : b.losses) += 1;
        b.kills += u.combat.kills;
        b.shotsFired += u.combat.shotsFired;
        b.hits += u.combat.hits;
        b.damageDealt += u.combat.damageDealt;
        b.damageTaken += u.combat.damageTaken;
      }
      if (s.units == 0) continue;
      std::sort(s.arrivedAt.begin(), s.arrivedAt.end());
      b.units = s.units;
      s.rate = static_cast<double>(s.arrived) / static_cast<double>(s.units);
      if (s.arrived > 0) {
        std::vector<double> times = arrivalTimes(static_cast<int>(team), static_cast<int>(type));
        times.resize(static_cast<std::size_t>(s.arrived));  // the finite ones come first
        s.p50 = percentile(times, 50);
        s.p90 = percentile(times, 90);
        s.max = times.back();
      }
      r.arrivals.push_back(s);
      r.battle.push_back(b);
      r.movement.delay.push_back(delayOf(units, static_cast<int>(team), static_cast<int>(type)));
      r.movement.delay.back().team = s.team;
      r.movement.delay.back().type = s.type;
    }
  }
  const PathServiceSettings& pathing = world_.settings().pathing;
  r.movement.cooperative = pathing.cooperative;
  r.movement.window = pathing.window;
  r.movement.counters = world_.state().movement;
  r.movement.maxWaitSeconds = static_cast<double>(r.movement.counters.maxWaitTicks) / rate;
  for (const Unit& u : units) {
    if (u.everStuck) r.stuckUnits.push_back(u.id.index);
    r.noPath += u.state == UnitState::NoPath ? 1 : 0;
    r.repaths += u.repaths;
  }

  for (const Expectation& e : scenario_.expectations) {
    ExpectationResult result;
    result.text = e.text;
    switch (e.kind) {
      case ExpectationKind::ArrivalRate: {
        int total = 0;
        int arrived = 0;
        const auto byTick = std::llround(e.by * rate);
        for (const Unit& u : units) {
          if (!matches(u, e.team, e.type)) continue;
          ++total;
          const bool inTime = u.arrivalTick >= 0 && u.arrivalTick <= byTick;
          arrived += inTime ? 1 : 0;
          if (!inTime) result.units.push_back(u.id.index);
        }
        result.actual = total == 0 ? 0.0 : static_cast<double>(arrived) / total;
        result.pass = total > 0 && result.actual >= e.threshold;
        break;
      }
      case ExpectationKind::MaxStuck:
        result.actual = static_cast<double>(r.stuckUnits.size());
        result.pass = result.actual <= e.threshold;
        result.units = r.stuckUnits;
        break;
      case ExpectationKind::ArrivalTime: {
        const std::vector<double> times = arrivalTimes(e.team, e.type);
        result.actual = times.empty() ? std::numeric_limits<double>::infinity()
                                      : percentile(times, e.percentile);
        result.pass = result.actual <= e.threshold;
        for (const Unit& u : units) {
          if (matches(u, e.team, e.type) &&
              (u.arrivalTick < 0 ||
               static_cast<double>(u.arrivalTick - u.orderTick) / rate > e.threshold))
            result.units.push_back(u.id.index);
        }
        break;
      }
      case ExpectationKind::Delay: {
        const std::vector<double> delays = delaysOf(units, e.team, e.type, true);
        result.actual = delays.empty() ? std::numeric_limits<double>::infinity()
                                       : percentile(delays, e.percentile);
        result.pass = result.actual <= e.threshold;
        for (const Unit& u : units) {
          if (matches(u, e.team, e.type) && u.plannedTicks > 0 &&
              (u.arrivalTick < 0 || static_cast<double>(u.arrivalTick - u.orderTick) /
                                            static_cast<double>(u.plannedTicks) >
                                        e.threshold))
            result.units.push_back(u.id.index);
        }
        break;
      }
      case ExpectationKind::MaxWait:
        result.actual = r.movement.maxWaitSeconds;
        result.pass = result.actual <= e.threshold;
        break;
      case ExpectationKind::MaxDeadlocks:
        result.actual = static_cast<double>(r.movement.counters.deadlocksBroken);
        result.pass = result.actual <= e.threshold;
        break;
      case ExpectationKind::Winner:
        result.actual = state_.winner;
        result.pass = state_.winner == e.team;
        break;
      case ExpectationKind::Stat: {
        double sum = 0.0;
        for (const Unit& u : units) {
          if (matches(u, e.team, e.type)) sum += statOf(u, e.stat);
        }
        result.actual = sum;
        result.pass = e.atMost ? sum <= e.threshold : sum >= e.threshold;
        break;
      }
    }
    r.expectations.push_back(result);
  }
  return r;
}

}  // namespace warpath::engine
