#pragma once
// Running a scenario to its end in the engine tests.

#include <cstdint>

#include "engine/scenario_run.h"

namespace warpath::testing {

// Steps `run` until it is done.
inline void runOut(engine::ScenarioRun& run) {
  while (!run.done())
    run.step();
}

// The report of `scenario` run to its end at `seed`.
inline engine::Report runToEnd(const engine::Scenario& scenario, std::uint64_t seed) {
  engine::ScenarioRun run(scenario, seed);
  runOut(run);
  return run.report();
}

}  // namespace warpath::testing
