// Checks that a warmed-up AnnotatedAStar allocates nothing per query. Its own executable,
// because it replaces the global allocation functions to count calls.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "pathing/aa_star.h"
#include "pathing/map_generator.h"
#include "pathing/random.h"

namespace {
std::atomic<long> allocations{0};
}

// The replaced new and delete pair malloc with free; GCC cannot see that both are replaced.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace warpath::pathing {
namespace {

TEST(AllocationTest, WarmQueriesDoNotAllocate) {
  RandomMapSpec spec;
  spec.width = 128;
  spec.height = 128;
  spec.seed = 9;
  const AnnotatedGrid grid(generateRandomMap(spec));
  const Agent agent{1, Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees})};
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  std::vector<std::pair<Cell, Cell>> queries;
  SplitMix64 rng(3);
  for (int i = 0; i < 200; ++i) {
    queries.push_back(
        {{rng.between(0, 127), rng.between(0, 127)}, {rng.between(0, 127), rng.between(0, 127)}});
  }
  // Warm-up: the same queries grow every buffer to its high-water mark.
  int found = 0;
  for (const auto& [s, g] : queries)
    found += search.findPath(agent, s, g, &path).found();
  ASSERT_GT(found, 50);

  const long before = allocations.load();
  for (const auto& [s, g] : queries)
    search.findPath(agent, s, g, &path);
  EXPECT_EQ(allocations.load() - before, 0);
}

}  // namespace
}  // namespace warpath::pathing
