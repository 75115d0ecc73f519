// Abstraction graphs pinned whole: a fingerprint of every node, every edge in order (its cost's
// bits, annotation and cached path) and the repairs' expansion counts (the path service spends
// its budget by them), after a build and after each of a sequence of terrain changes. Faster
// intra-edge searches must settle the same cells in the same order: a change that only picks
// another path among equal-cost ones shows here, not just as a scenario's hash moving.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "pathing/cluster_abstraction.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"
#include "random_grid.h"
#include "support/fingerprint.h"

namespace warpath::pathing {
namespace {

using testing::Fingerprint;

void addGraph(Fingerprint& f, const ClusterAbstraction& g) {
  std::vector<Cell> cells;
  for (std::uint32_t n = 0; n < g.nodeCount(); ++n) {
    f.add(g.nodeCell(n));
    for (const AbstractEdge& e : g.edgesOf(n)) {
      std::uint64_t cost = 0;
      std::memcpy(&cost, &e.cost, sizeof cost);
      f.add(cost);
      f.add(static_cast<std::uint64_t>(e.target) << 24 | std::uint64_t{e.capability.mask()} << 16 |
            std::uint64_t{e.clearance} << 8 | (e.intra ? 2u : 0u) | (e.reversed ? 1u : 0u));
      cells.clear();
      g.appendEdgeCells(n, e, &cells);
      for (Cell c : cells)
        f.add(c);
    }
  }
  for (int k = 0; k < g.clusterCount(); ++k) {
    for (std::uint32_t n : g.nodesInCluster(k))
      f.add(n);
  }
  if (g.spec().levels != 2) return;
  std::vector<std::pair<std::uint32_t, const AbstractEdge*>> steps;
  for (std::uint32_t n = 0; n < g.nodeCount(); ++n) {
    for (const AbstractEdge& e : g.levelTwoEdgesOf(n)) {
      std::uint64_t cost = 0;
      std::memcpy(&cost, &e.cost, sizeof cost);
      f.add(cost);
      f.add(static_cast<std::uint64_t>(e.target) << 24 | std::uint64_t{e.capability.mask()} << 16 |
            std::uint64_t{e.clearance} << 8 | (e.reversed ? 1u : 0u));
      steps.clear();
      g.appendLevelOneSteps(n, e, Agent{e.clearance, e.capability}, &steps);
      for (const auto& [from, step] : steps)
        f.add(static_cast<std::uint64_t>(from) << 32 | step->target);
    }
  }
}

constexpr Terrain kTerrains[] = {Terrain::Ground, Terrain::Swamp, Terrain::Trees, Terrain::Water,
                                 Terrain::Blocked};

// The graph's fingerprint after it is built on a random map and then repaired after each of
// 15 random changes (terrain set or an obstacle placed or cleared).
std::uint64_t fingerprintOfRepairs(std::uint64_t seed, const AbstractionSpec& spec) {
  AnnotatedGrid grid(randomTerrainMap(seed, 61, 53, 5, 12));
  ClusterAbstraction graph = ClusterAbstraction::build(grid, spec);
  Fingerprint f;
  addGraph(f, graph);
  f.add(graph.stats().buildExpanded);
  SplitMix64 rng(seed);
  std::vector<CellRect> obstacles;
  for (int step = 0; step < 15; ++step) {
    const int kind = rng.between(0, 5);
    const CellRect area{rng.between(-2, 60), rng.between(-2, 52), rng.between(1, 9),
                        rng.between(1, 9)};
    TerrainChange change;
    if (kind == 0 && !obstacles.empty()) {
      change = grid.clearObstacle(obstacles.back());
      obstacles.pop_back();
    } else if (kind <= 2) {
      obstacles.push_back(area);
      change = grid.placeObstacle(area);
    } else {
      change = grid.setTerrain(area, kTerrains[rng.between(0, 4)]);
    }
    f.add(graph.repair(change).expanded);
    addGraph(f, graph);
  }
  return f.value;
}

AbstractionSpec catalogueSpec(int clusterSize, AbstractionQuality quality) {
  AbstractionSpec spec;
  spec.clusterSize = clusterSize;
  spec.maxAgentSize = 3;
  spec.capabilities = {Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees}),
                       Capability::of({Terrain::Ground}),
                       Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water})};
  spec.quality = quality;
  return spec;
}

TEST(AbstractionPin, CatalogueGraphsBuiltAndRepaired) {
  EXPECT_EQ(fingerprintOfRepairs(1, catalogueSpec(8, AbstractionQuality::High)),
            4201646002708704147u);
  EXPECT_EQ(fingerprintOfRepairs(2, catalogueSpec(16, AbstractionQuality::High)),
            18218118805506173212u);
  EXPECT_EQ(fingerprintOfRepairs(3, catalogueSpec(8, AbstractionQuality::Low)),
            9097106969538780189u);
  EXPECT_EQ(fingerprintOfRepairs(4, catalogueSpec(12, AbstractionQuality::Low)),
            15306790391871953827u);
}

TEST(AbstractionPin, WeightedGraphsBuiltAndRepaired) {
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  costs.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  const Capability infantry = costs.capability();
  EXPECT_EQ(fingerprintOfRepairs(
                5, weightedAbstractionSpec({1, infantry}, costs, 8, AbstractionQuality::High)),
            5683012086766148133u);
  EXPECT_EQ(fingerprintOfRepairs(
                6, weightedAbstractionSpec({2, infantry}, costs, 8, AbstractionQuality::Low)),
            7245523427445198578u);
}

// Clusters searched on several threads (AbstractionSpec::threads) give the graphs, repairs and
// expansion counts pinned above, bit for bit: more threads than clusters to redo, fewer, and
// a count that does not divide the work.
TEST(AbstractionPin, TheSameOnAnyNumberOfThreads) {
  for (const int threads : {2, 3, 8}) {
    AbstractionSpec spec = catalogueSpec(8, AbstractionQuality::High);
    spec.threads = threads;
    EXPECT_EQ(fingerprintOfRepairs(1, spec), 4201646002708704147u) << threads << " threads";
    spec = catalogueSpec(12, AbstractionQuality::Low);
    spec.threads = threads;
    EXPECT_EQ(fingerprintOfRepairs(4, spec), 15306790391871953827u) << threads << " threads";
  }
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  costs.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  AbstractionSpec weighted =
      weightedAbstractionSpec({1, costs.capability()}, costs, 8, AbstractionQuality::High);
  weighted.threads = 4;
  EXPECT_EQ(fingerprintOfRepairs(5, weighted), 5683012086766148133u);
  // Level 2's blocks are rebuilt on the threads too.
  AbstractionSpec levels = catalogueSpec(4, AbstractionQuality::High);
  levels.levels = 2;
  levels.levelTwoSize = 2;
  const std::uint64_t oneThread = fingerprintOfRepairs(7, levels);
  levels.threads = 3;
  EXPECT_EQ(fingerprintOfRepairs(7, levels), oneThread);
}

}  // namespace
}  // namespace warpath::pathing
