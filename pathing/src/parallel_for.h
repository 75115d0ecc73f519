// Tasks run on several threads whose results do not depend on which thread ran them
// (AbstractionSpec::threads): callers keep one scratch per worker and one result per task, and
// join the results in task order afterwards.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace warpath::pathing {

// The workers parallelFor(count, threads, ...) uses: at least 1, at most one per task.
inline std::size_t workersFor(std::size_t count, int threads) {
  return std::max<std::size_t>(1, std::min(count, static_cast<std::size_t>(std::max(1, threads))));
}

// Calls task(worker, i) once for every i in [0, count), on workersFor(count, threads) threads
// (worker 0 is the calling thread; each takes the next index not taken). Once every thread has
// stopped, rethrows the exception of the lowest worker whose task threw; the tasks not yet
// begun then do not run.
template <class Task>
void parallelFor(std::size_t count, int threads, Task task) {
  const std::size_t workers = workersFor(count, threads);
  if (workers == 1) {
    for (std::size_t i = 0; i < count; ++i)
      task(std::size_t{0}, i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> failed(workers);
  const auto work = [&](std::size_t worker) {
    try {
      for (std::size_t i = next++; i < count; i = next++)
        task(worker, i);
    } catch (...) {
      failed[worker] = std::current_exception();
      next = count;
    }
  };
  {
    std::vector<std::jthread> pool;
    pool.reserve(workers - 1);
    for (std::size_t w = 1; w < workers; ++w)
      pool.emplace_back(work, w);
    work(0);
  }
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace warpath::pathing
