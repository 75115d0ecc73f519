#pragma once
// What `rts run` and `rts test` share: running a scenario to its end (or a tick limit, or an
// interrupt) and the report as JSON.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "engine/replay.h"
#include "engine/scenario.h"
#include "engine/scenario_run.h"

namespace warpath::tools {

// Loads a scenario or throws BadInput with file, line, column and problem. With `source`, keeps
// the scenario's text and every file it read there (for a replay).
engine::Scenario loadScenarioOrThrow(const std::string& file,
                                     engine::ReplaySource* source = nullptr);

// Installs SIGINT/SIGTERM handlers that ask runs to stop between ticks.
void installInterruptHandlers();
bool interruptRequested();

struct RunLimits {
  std::optional<std::int64_t> untilTick;  // stop after this tick
  // Called after every tick (progress display); may be empty.
  std::function<void(const engine::ScenarioRun&)> onTick;
};

struct RunOutcome {
  engine::Report report;
  double wallSeconds = 0.0;
  bool interrupted = false;
};

// Steps `run` until it is done (its duration ran out or the battle ended), the tick limit or
// an interrupt.
RunOutcome runToEnd(engine::ScenarioRun& run, const RunLimits& limits);

// inf (a percentile of units that never arrived) has no JSON form: null.
nlohmann::json finiteOrNull(double v);
// The report's "expectations": text, actual value (null for inf), pass and the units it counts
// against (ExpectationResult::units) of each.
nlohmann::json expectationsJson(const std::vector<engine::ExpectationResult>& expectations);
// A failed expectation's line, as `rts test` and its JUnit file give it: its text, the actual
// value and the first units it counts against ("units 1, 5 and 3 more").
std::string failureLine(const engine::ExpectationResult& e);
// How many units failureLine names, and traceHint traces, at the most.
inline constexpr std::size_t kUnitsNamed = 8;

nlohmann::json reportJson(const RunOutcome& outcome, const engine::ScenarioRun& run);

}  // namespace warpath::tools
