// `rts bench movement`: runs scenarios at several seeds with cooperative movement on and off
// and prints one row per (scenario, mode): how many seeds passed, arrival, delay (time to
// arrive / planned time), stuck units, deadlocks broken and milliseconds per tick. The
// with/without table of docs/cooperative.md comes from here.

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/scenario_support.h"

namespace warpath::tools {
namespace {

struct MovementBenchOptions {
  std::vector<std::string> scenarios;
  int seeds = 3;
  std::string modes = "both";
  std::optional<std::int64_t> until;
  bool json = false;
};

struct ModeRow {
  std::string scenario;
  bool cooperative = true;
  int runs = 0;
  int passed = 0;
  double arrivalRate = 1.0;  // the worst (team, type) rate over the seeds
  double delayP50 = 0.0;     // the worst over the seeds of the worst (team, type)
  double delayP90 = 0.0;
  double delayMax = 0.0;
  int stuck = 0;  // summed over the seeds
  std::int64_t deadlocksBroken = 0;
  std::int64_t giveWays = 0;
  double maxWaitSeconds = 0.0;
  double msPerTick = 0.0;  // mean over the seeds
};

ModeRow runMode(const engine::Scenario& base, const std::string& name, bool cooperative,
                const MovementBenchOptions& options) {
  engine::Scenario scenario = base;
  scenario.settings.pathing.cooperative = cooperative;
  ModeRow row;
  row.scenario = name;
  row.cooperative = cooperative;
  double ms = 0.0;
  for (int seed = 1; seed <= options.seeds && !interruptRequested(); ++seed) {
    engine::ScenarioRun run(scenario, static_cast<std::uint64_t>(seed));
    RunLimits limits;
    limits.untilTick = options.until;
    const RunOutcome outcome = runToEnd(run, limits);
    const engine::Report& r = outcome.report;
    ++row.runs;
    row.passed += r.passed() ? 1 : 0;
    for (const engine::ArrivalStats& a : r.arrivals)
      row.arrivalRate = std::min(row.arrivalRate, a.rate);
    for (const engine::DelayStats& d : r.movement.delay) {
      row.delayP50 = std::max(row.delayP50, d.p50);
      row.delayP90 = std::max(row.delayP90, d.p90);
      row.delayMax = std::max(row.delayMax, d.max);
    }
    row.stuck += static_cast<int>(r.stuckUnits.size());
    row.deadlocksBroken += r.movement.counters.deadlocksBroken;
    row.giveWays += r.movement.counters.giveWays;
    row.maxWaitSeconds = std::max(row.maxWaitSeconds, r.movement.maxWaitSeconds);
    ms += 1000.0 * outcome.wallSeconds / static_cast<double>(std::max<std::int64_t>(1, r.ticks));
  }
  row.msPerTick = row.runs > 0 ? ms / row.runs : 0.0;
  return row;
}

int runMovementBench(const MovementBenchOptions& options) {
  std::vector<bool> modes;
  if (options.modes == "both" || options.modes == "on") modes.push_back(true);
  if (options.modes == "both" || options.modes == "off") modes.push_back(false);
  installInterruptHandlers();
  std::vector<ModeRow> rows;
  for (const std::string& file : options.scenarios) {
    const engine::Scenario scenario = loadScenarioOrThrow(file);
    const std::string name = std::filesystem::path(file).stem().string();
    for (const bool cooperative : modes)
      rows.push_back(runMode(scenario, name, cooperative, options));
  }
  if (options.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const ModeRow& r : rows) {
      out.push_back({{"scenario", r.scenario},
                     {"cooperative", r.cooperative},
                     {"runs", r.runs},
                     {"passed", r.passed},
                     {"min_arrival_rate", r.arrivalRate},
                     {"delay_p50", r.delayP50},
                     {"delay_p90", r.delayP90},
                     {"delay_max", r.delayMax},
                     {"stuck", r.stuck},
                     {"deadlocks_broken", r.deadlocksBroken},
                     {"give_ways", r.giveWays},
                     {"max_wait_s", r.maxWaitSeconds},
                     {"ms_per_tick", r.msPerTick}});
    }
    fmt::print("{}\n", out.dump(2));
    return 0;
  }
  fmt::print(
      "| scenario | cooperative | seeds passed | min arrival | delay p50 | delay p90 | delay max | "
      "stuck | deadlocks broken | give-ways | max wait s | ms/tick |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const ModeRow& r : rows) {
    fmt::print(
        "| {} | {} | {}/{} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {} | {} | {} | {:.1f} | "
        "{:.2f} |\n",
        r.scenario, r.cooperative ? "on" : "off", r.passed, r.runs, r.arrivalRate, r.delayP50,
        r.delayP90, r.delayMax, r.stuck, r.deadlocksBroken, r.giveWays, r.maxWaitSeconds,
        r.msPerTick);
  }
  return 0;
}

}  // namespace

void registerBenchMovementCommand(CLI::App& bench, CommandRunner& run) {
  auto [cmd, options] = addSubcommand(
      bench, run, "movement",
      "Run scenarios at seeds 1..N with cooperative movement on and off; one row per mode",
      runMovementBench);
  cmd->add_option("scenarios", options->scenarios, "Scenario YAML files")->required();
  cmd->add_option("--seeds", options->seeds, "Seeds 1..N")->check(CLI::Range(1, 1000));
  cmd->add_option("--modes", options->modes, "both, on (cooperative) or off")
      ->check(CLI::IsMember({"both", "on", "off"}));
  cmd->add_option("--until", options->until, "Stop each run after this tick")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_flag("--json", options->json, "One JSON array instead of a Markdown table");
}

}  // namespace warpath::tools
