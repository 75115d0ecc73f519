#include "engine/scenario_run.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

ScenarioRun::ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed)
    : scenario_(scenario),
      world_(scenario.grid, scenario.catalogue, settingsFor(scenario, seed)),
      members_(scenario.groups.size()),
      fired_(scenario.orders.size(), false) {
  for (std::size_t g = 0; g < scenario.groups.size(); ++g) {
    const GroupSpec& group = scenario.groups[g];
    for (pathing::Cell anchor : group.anchors)
      members_[g].push_back(world_.spawn(group.type, group.team, static_cast<int>(g), anchor));
    if (group.goal) issue({static_cast<int>(g)}, *group.goal);
  }
}

ScenarioRun::ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed,
                         std::vector<IssuedOrder> script)
    : scenario_(scenario),
      world_(scenario.grid, scenario.catalogue, settingsFor(scenario, seed)),
      members_(scenario.groups.size()),
      script_(std::move(script)) {
  // Spawning draws nothing from the RNG and orders wait in the world until its next step, so
  // giving the tick-0 orders in step() rather than between spawns changes nothing.
  for (std::size_t g = 0; g < scenario.groups.size(); ++g) {
    for (pathing::Cell anchor : scenario.groups[g].anchors)
      members_[g].push_back(world_.spawn(scenario.groups[g].type, scenario.groups[g].team,
                                         static_cast<int>(g), anchor));
  }
}

void ScenarioRun::issue(const std::vector<int>& groups, const pathing::CellRect& area) {
  std::vector<UnitId> ids;
  for (int g : groups) {
    const auto& m = members_[static_cast<std::size_t>(g)];
    ids.insert(ids.end(), m.begin(), m.end());
  }
  std::sort(ids.begin(), ids.end(), [](UnitId a, UnitId b) { return a.index < b.index; });
  give(std::move(ids), area);
}

void ScenarioRun::give(std::vector<UnitId> units, const pathing::CellRect& area) {
  issued_.push_back({world_.tick(), units, area});
  world_.orderMove(std::move(units), area);
}

void ScenarioRun::step() {
  if (script_) {
    for (; scriptNext_ < script_->size() && (*script_)[scriptNext_].tick <= world_.tick();
         ++scriptNext_)
      give((*script_)[scriptNext_].units, (*script_)[scriptNext_].area);
    world_.step();
    return;
  }
  for (std::size_t i = 0; i < scenario_.orders.size(); ++i) {
    if (fired_[i]) continue;
    const OrderSpec& order = scenario_.orders[i];
    bool due = false;
    if (order.at >= 0.0) {
      due = world_.tick() >= std::llround(order.at * world_.tickRate());
    } else {
      const auto& group = members_[static_cast<std::size_t>(order.whenArrived)];
      int arrived = 0;
      for (UnitId id : group) {
        const Unit* unit = world_.find(id);
        arrived += unit != nullptr && unit->arrivalTick >= 0 ? 1 : 0;
      }
      due = !group.empty() &&
            static_cast<double>(arrived) >= order.fraction * static_cast<double>(group.size());
    }
    if (due) {
      fired_[i] = true;
      issue(order.groups, order.moveTo);
    }
  }
  world_.step();
}

Report ScenarioRun::report() const {
  Report r;
  r.scenario = scenario_.name;
  r.seed = settingsFor(scenario_, std::nullopt).seed;
  r.ticks = world_.tick();
  r.simSeconds = world_.seconds();
  r.stateHash = world_.stateHash();
  r.complete = done();
  r.pathing = world_.pathService().metrics();
  const double rate = world_.tickRate();
  const std::vector<Unit>& units = world_.units();

  const auto matches = [](const Unit& u, int team, int type) {
    return (team < 0 || u.team == team) && (type < 0 || u.type == type);
  };
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

  for (std::size_t team = 0; team < scenario_.teams.size(); ++team) {
    for (std::size_t type = 0; type < scenario_.catalogue.size(); ++type) {
      ArrivalStats s;
      s.team = scenario_.teams[team];
      s.type = scenario_.catalogue[type].name;
      for (const Unit& u : units) {
        if (!matches(u, static_cast<int>(team), static_cast<int>(type))) continue;
        ++s.units;
        s.arrived += u.arrivalTick >= 0 ? 1 : 0;
        s.dead += u.hp <= 0 ? 1 : 0;
      }
      if (s.units == 0) continue;
      s.rate = static_cast<double>(s.arrived) / static_cast<double>(s.units);
      if (s.arrived > 0) {
        std::vector<double> times = arrivalTimes(static_cast<int>(team), static_cast<int>(type));
        times.resize(static_cast<std::size_t>(s.arrived));  // the finite ones come first
        s.p50 = percentile(times, 50);
        s.p90 = percentile(times, 90);
        s.max = times.back();
      }
      r.arrivals.push_back(s);
    }
  }
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
          arrived += u.arrivalTick >= 0 && u.arrivalTick <= byTick ? 1 : 0;
        }
        result.actual = total == 0 ? 0.0 : static_cast<double>(arrived) / total;
        result.pass = total > 0 && result.actual >= e.threshold;
        break;
      }
      case ExpectationKind::MaxStuck:
        result.actual = static_cast<double>(r.stuckUnits.size());
        result.pass = result.actual <= e.threshold;
        break;
      case ExpectationKind::ArrivalTime: {
        const std::vector<double> times = arrivalTimes(e.team, e.type);
        result.actual = times.empty() ? std::numeric_limits<double>::infinity()
                                      : percentile(times, e.percentile);
        result.pass = result.actual <= e.threshold;
        break;
      }
    }
    r.expectations.push_back(result);
  }
  return r;
}

}  // namespace warpath::engine
