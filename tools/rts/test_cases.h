#pragma once
// The cases of `rts test`: which (scenario, seed) pairs a run holds, which of them a shard
// takes, running one, and a case's result as JSON (what a worker process sends back, and what
// a report folder's summary keeps for `rts test merge`).

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scenario_run.h"

namespace warpath::tools {

struct TestCase {
  // The case's key, stable across machines and checkouts: the scenario file's name relative to
  // the folder it was found in (its base name when given as a file), "#seed" appended when
  // --seeds was given: "demo.yaml", "demo.yaml#5". Shards are picked by it.
  std::string name;
  std::string file;                   // the path to load, as given on the command line
  std::optional<std::uint64_t> seed;  // empty: the file's own seed
};

// The part of a run that shards split: shard `index` of `count` takes the cases whose name
// hashes to it. Shards count from 0, as Kubernetes' JOB_COMPLETION_INDEX does.
struct Shard {
  int index = 0;
  int count = 1;  // [Limit: 1..kMaxShards]
};
inline constexpr int kMaxShards = 100000;
// [Limit: cases in one run]
inline constexpr std::size_t kMaxCases = 1000000;

// "1,2,5", "1..10" or a mix ("1..3,7"), in the order given; throws BadInput naming --seeds.
std::vector<std::uint64_t> parseSeeds(std::string_view text);
// "K/N" with 0 <= K < N; throws BadInput naming --shard.
Shard parseShard(std::string_view text);
// Whether `name` falls in `shard`: FNV-1a of the name's bytes, mixed by one SplitMix64 step,
// scaled to the shard count. Never change it: shards of one run must agree.
bool inShard(std::string_view name, const Shard& shard);

// The cases of `inputs` (folders, whose *.yaml and *.yml files are taken in name order, and
// scenario files), each at every seed of `seeds` or, with none, at the file's own. Throws
// BadInput for an input that is neither a folder nor a regular file, or two files that would
// give cases the same name.
std::vector<TestCase> collectCases(const std::vector<std::string>& inputs,
                                   const std::vector<std::uint64_t>& seeds);

enum class CaseStatus {
  Pass,    // every expectation held
  Fail,    // ran to its end; an expectation failed
  Error,   // did not run to its end: a bad file, a crash, an interrupt
  NotRun,  // never started (the run was interrupted first)
};

struct CaseResult {
  std::string name;
  std::string file;
  bool seedGiven = false;             // the case's seed came from --seeds
  std::optional<std::uint64_t> seed;  // the seed run; empty when the file did not load
  CaseStatus status = CaseStatus::NotRun;
  std::string message;   // for an error: what went wrong ("file:line:col: ...", "crashed ...")
  double seconds = 0.0;  // wall time of the case, loading included
  std::size_t units = 0;
  std::int64_t ticks = 0;
  std::string winner;
  std::string stateHash;  // as in the report: 16 hex digits; empty when it did not run
  std::vector<engine::ExpectationResult> expectations;
  nlohmann::json report;   // the whole `rts run --report` JSON; null when it did not run
  std::string reportFile;  // where the report folder keeps it, relative to the folder
};

// A result that has not run, for `testCase`.
CaseResult notRun(const TestCase& testCase);
// Loads and runs `testCase` to its end (or an interrupt) in this process; never throws.
CaseResult runCase(const TestCase& testCase);

std::string_view toString(CaseStatus status);

// A result as JSON: with the whole report (what a worker sends), or without it (a summary's
// entry, naming the report file instead).
nlohmann::json caseJson(const CaseResult& result, bool withReport);
// Back from caseJson; throws BadInput naming `where` when the JSON is not one.
CaseResult caseFromJson(const nlohmann::json& j, const std::string& where);

// The console lines of a case as `rts test` has always printed them: "PASS file (64 units,
// 2700 ticks, 1.23 s)" (with " seed N" after the file when --seeds gave it), then each failed
// expectation with its actual value; "FAIL file: problem" for a file that did not load.
void printCase(const CaseResult& result);

}  // namespace warpath::tools
