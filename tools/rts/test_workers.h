#pragma once
// Runs `rts test`'s cases in worker processes: one fork per case, at most `jobs` at a time.
// A case runs alone in its process, so a crash, an abort or a leak of one case is that case's
// error and never the run's, and the results are those of a run one case after another (the
// simulation is deterministic and single-threaded).

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "rts/test_cases.h"

namespace warpath::tools {

// [Limit: worker processes]
inline constexpr int kMaxJobs = 256;

// Calls `done(index, result)` in this process as each case finishes, in the order they finish.
// After an interrupt (installInterruptHandlers) starts no more cases and asks the running ones
// to stop; they come back as errors ("interrupted at tick N"). Returns how many cases started
// (the first ones, in order).
std::size_t runInWorkers(const std::vector<TestCase>& cases, int jobs,
                         const std::function<void(std::size_t, CaseResult)>& done);

}  // namespace warpath::tools
