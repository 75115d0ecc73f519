#pragma once
// Runs a loaded scenario: spawns its groups, issues its orders when due (at a time or when a
// group has arrived), steps the world and judges the expectations into a report.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/scenario.h"
#include "engine/world.h"

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
  bool operator==(const ArrivalStats&) const = default;
};

struct ExpectationResult {
  std::string text;
  double actual = 0.0;  // rate, count or seconds; +inf when a percentile has not arrived
  bool pass = false;
  bool operator==(const ExpectationResult&) const = default;
};

// Everything a run produces except wall-clock measurements (see World::meanTiming).
struct Report {
  std::string scenario;
  std::uint64_t seed = 0;
  std::int64_t ticks = 0;
  double simSeconds = 0.0;
  std::uint64_t stateHash = 0;
  bool complete = false;  // ran the whole duration
  std::vector<ArrivalStats> arrivals;
  std::vector<std::uint32_t> stuckUnits;  // ids of units ever flagged stuck
  int noPath = 0;                         // units whose goal could not be reached
  int repaths = 0;
  PathServiceMetrics pathing;
  std::vector<ExpectationResult> expectations;

  bool passed() const;
  bool operator==(const Report&) const = default;
};

// A move order as the world received it: given before step `tick` + 1 ran (the world applies
// it at the start of that step). What a replay records as the command stream.
struct IssuedOrder {
  std::int64_t tick = 0;
  std::vector<UnitId> units;  // ascending index
  pathing::CellRect area;
};

// Nearest-rank percentile of ascending `sorted`; [Limit: !sorted.empty(), p in 0..100]
double percentile(const std::vector<double>& sorted, double p);

class ScenarioRun {
 public:
  // `seed` replaces the scenario's seed when given. The scenario must outlive the run.
  explicit ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed = {});
  // Plays `script` (ascending tick) instead of the scenario's own orders: its group goals and
  // its timed and triggered orders are not evaluated, so playback never re-derives a trigger.
  // The caller checks that the script names units the scenario spawns.
  ScenarioRun(const Scenario& scenario, std::optional<std::uint64_t> seed,
              std::vector<IssuedOrder> script);

  void step();
  bool done() const { return world_.tick() >= scenario_.durationTicks(); }
  const World& world() const { return world_; }
  const Scenario& scenario() const { return scenario_; }
  Report report() const;
  // Every order given to the world so far, in the order given.
  const std::vector<IssuedOrder>& issued() const { return issued_; }

 private:
  static WorldSettings settingsFor(const Scenario& scenario, std::optional<std::uint64_t> seed);
  void issue(const std::vector<int>& groups, const pathing::CellRect& area);
  void give(std::vector<UnitId> units, const pathing::CellRect& area);

  const Scenario& scenario_;
  World world_;
  std::vector<std::vector<UnitId>> members_;  // per group
  std::vector<bool> fired_;                   // per order
  std::optional<std::vector<IssuedOrder>> script_;
  std::size_t scriptNext_ = 0;  // first order of script_ not yet given
  std::vector<IssuedOrder> issued_;
};

}  // namespace warpath::engine
