// Writes a seed replay for fuzz_replay the way `rts run SCENARIO --replay FILE` does, without
// the CLI (whose render dependencies the fuzz build does not compile):
//   make_replay_seed SCENARIO OUT TICKS [HASH_EVERY]
// Runs the scenario for TICKS ticks (or to its end) and finishes the replay as stopped (or
// complete). Exit 0 on success, 2 with the problem on stderr.

#include <cstdint>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "engine/replay.h"
#include "engine/scenario_run.h"

int main(int argc, char** argv) {
  using namespace warpath;
  using namespace warpath::engine;
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: %s SCENARIO OUT TICKS [HASH_EVERY]\n", argv[0]);
    return 2;
  }
  try {
    const std::int64_t ticks = std::stoll(argv[3]);
    ReplaySource source;
    const Result<Scenario> scenario = loadRecordedScenario(argv[1], source);
    if (!scenario.ok()) {
      std::fprintf(stderr, "%s\n", scenario.error().describe().c_str());
      return 2;
    }
    source.seed = scenario.value().settings.seed;
    source.hashEvery = argc == 5 ? std::stoll(argv[4]) : 1;
    ScenarioRun run(scenario.value());
    Result<ReplayWriter> writer = ReplayWriter::open(argv[2], source);
    if (!writer.ok()) {
      std::fprintf(stderr, "%s\n", writer.error().describe().c_str());
      return 2;
    }
    Status status = writer.value().record(run);
    while (status && !run.done() && run.world().tick() < ticks) {
      run.step();
      status = writer.value().record(run);
    }
    if (status)
      status = writer.value().finish(run, run.done() ? ReplayEnd::Complete : ReplayEnd::Stopped);
    if (!status) {
      std::fprintf(stderr, "%s\n", status.error().describe().c_str());
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_replay_seed: %s\n", e.what());
    return 2;
  }
  return 0;
}
