// HAA* queries are thread-safe on a shared abstraction: several query objects on several
// threads, including agents whose grid layers are first built during the run, give exactly
// the answers of one query object on one thread.

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "pathing/cluster_abstraction.h"
#include "pathing/haa_star.h"
#include "pathing/map_generator.h"
#include "pathing/random.h"

namespace warpath::pathing {
namespace {

struct Answer {
  PathStatus status;
  double cost;
  std::vector<Cell> path;
};

TEST(HaaThreadsTest, ConcurrentQueriesMatchSerialOnes) {
  RandomMapSpec mapSpec;
  mapSpec.width = 120;
  mapSpec.height = 90;
  mapSpec.seed = 77;
  const AnnotatedGrid grid(generateRandomMap(mapSpec));
  AbstractionSpec spec;
  spec.clusterSize = 12;
  spec.maxAgentSize = 2;
  spec.capabilities = {Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees}),
                       Capability::of({Terrain::Ground})};
  const ClusterAbstraction graph = ClusterAbstraction::build(grid, spec);

  // Sizes up to 3: size 3 is not served by the graph, so its grid layer is built lazily,
  // concurrently, on first use.
  struct Job {
    Agent agent;
    Cell start;
    Cell goal;
  };
  std::vector<Job> queries;
  SplitMix64 rng(5);
  while (queries.size() < 300) {
    const Agent agent{rng.between(1, 3), spec.capabilities[rng.below(2)]};
    const Cell s{rng.between(0, mapSpec.width - 1), rng.between(0, mapSpec.height - 1)};
    const Cell g{rng.between(0, mapSpec.width - 1), rng.between(0, mapSpec.height - 1)};
    queries.push_back({agent, s, g});
  }

  constexpr int kThreads = 3;
  std::vector<std::vector<Answer>> answers(kThreads);
  std::vector<std::thread> workers;
  for (int t = 0; t < kThreads; ++t) {
    workers.emplace_back([&, t] {
      HierarchicalAStar search(graph);
      for (std::size_t i = 0; i < queries.size(); ++i) {
        // Each thread walks the list from a different place, so first uses collide.
        const Job& q = queries[(i + static_cast<std::size_t>(t) * 97) % queries.size()];
        Answer a;
        const PathResult r = search.findPath(q.agent, q.start, q.goal, &a.path);
        a.status = r.status;
        a.cost = r.cost;
        answers[static_cast<std::size_t>(t)].push_back(std::move(a));
      }
    });
  }
  for (std::thread& w : workers)
    w.join();

  HierarchicalAStar serial(graph);
  int found = 0;
  for (int t = 0; t < kThreads; ++t) {
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const Job& q = queries[(i + static_cast<std::size_t>(t) * 97) % queries.size()];
      std::vector<Cell> path;
      const PathResult r = serial.findPath(q.agent, q.start, q.goal, &path);
      const Answer& a = answers[static_cast<std::size_t>(t)][i];
      ASSERT_EQ(a.status, r.status) << "thread " << t << " query " << i;
      ASSERT_EQ(a.cost, r.cost) << "thread " << t << " query " << i;
      ASSERT_EQ(a.path, r.found() ? path : std::vector<Cell>{}) << "thread " << t << " query " << i;
      found += r.found();
    }
  }
  EXPECT_GT(found, 100);  // the comparison covered real paths, not only rejections
}

}  // namespace
}  // namespace warpath::pathing
