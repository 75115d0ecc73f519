// Terrain costs (pathing/terrain_costs.h) and weighted Annotated A*: optimal against a brute-force
// Dijkstra on random multi-terrain maps.

#include "pathing/terrain_costs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/map_generator.h"
#include "pathing/map_io.h"
#include "pathing/moves.h"

namespace warpath::pathing {
namespace {

const Capability kLand = Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees});

// Infantry-like: 1 / (1.5, 0.8, 1.0) cells per second on ground, swamp, trees.
TerrainCosts infantryCosts() {
  TerrainCosts c;
  c.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  c.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  c.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0 / 1.0;
  return c;
}

// Every anchor's cheapest cost to `goal` by Dijkstra over the agent's legal moves, each move
// priced from the terrains under the footprints directly (the model, not CostField).
std::vector<double> bruteForce(const AnnotatedGrid& grid, Agent agent, const TerrainCosts& costs,
                               Cell goal) {
  const GridMap& map = grid.map();
  const auto footprint = [&](Cell a) {
    double worst = 0.0;
    for (int dy = 0; dy < agent.size; ++dy) {
      for (int dx = 0; dx < agent.size; ++dx) {
        const Terrain t = map.at({a.x + dx, a.y + dy});
        const double c = isTraversable(t) ? costs.perCell[static_cast<std::size_t>(t)] : 0.0;
        worst = std::max(worst, c > 0.0 ? c : std::numeric_limits<double>::infinity());
      }
    }
    return worst;
  };
  const auto moveCost = [&](Cell a, const Direction& d) {
    const Cell b{a.x + d.dx, a.y + d.dy};
    if (d.cardinalA < 0) return (footprint(a) + footprint(b)) / 2.0;
    return std::sqrt(2.0) *
           (footprint(a) + footprint(b) + footprint({b.x, a.y}) + footprint({a.x, b.y})) / 4.0;
  };
  std::vector<double> dist(map.cellCount(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  dist[map.indexOf(goal)] = 0.0;
  open.push({0.0, map.indexOf(goal)});
  const std::span<const std::uint8_t> moves = grid.layer(agent).moveMasks();
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > dist[i]) continue;
    const Cell c = map.cellAt(i);
    for (int k = 0; k < kDirectionCount; ++k) {
      if ((moves[i] & (1u << k)) == 0) continue;  // moves are symmetric
      const Direction& dir = kDirections[static_cast<std::size_t>(k)];
      const Cell n{c.x + dir.dx, c.y + dir.dy};
      const double nd =
          d + moveCost(n, kDirections[static_cast<std::size_t>(oppositeDirection(k))]);
      if (nd < dist[map.indexOf(n)]) {
        dist[map.indexOf(n)] = nd;
        open.push({nd, map.indexOf(n)});
      }
    }
  }
  return dist;
}

TEST(TerrainCosts, UniformCostsGiveTheUnweightedLengths) {
  RandomMapSpec spec;
  spec.width = 48;
  spec.height = 40;
  const AnnotatedGrid grid(generateRandomMap(spec));
  const Agent agent{1, kLand};
  const CostField uniform(grid, agent, TerrainCosts::uniform(kLand));
  EXPECT_EQ(uniform.cheapest(), 1.0);
  AnnotatedAStar astar(grid);
  SplitMix64 rng(7);
  const QuerySampler sampler(grid, agent);
  for (int q = 0; q < 50; ++q) {
    const Query query = sampler.reachablePair(rng);
    const PathResult plain = astar.findPath(agent, query.start, query.goal, nullptr);
    std::vector<Cell> path;
    const PathResult weighted = astar.findPath(agent, query.start, query.goal, &path, uniform);
    ASSERT_TRUE(weighted.found());
    EXPECT_NEAR(weighted.cost, plain.cost, 1e-9);
    EXPECT_NEAR(uniform.pathCost(path), weighted.cost, 1e-9);
  }
}

TEST(TerrainCosts, WeightedAnnotatedAStarIsOptimalAgainstDijkstra) {
  const TerrainCosts costs = infantryCosts();
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    RandomMapSpec spec;
    spec.width = 40;
    spec.height = 32;
    spec.seed = seed;
    spec.blockedPercent = 15;
    spec.swampPercent = 20;
    spec.treesPercent = 15;
    const AnnotatedGrid grid(generateRandomMap(spec));
    AnnotatedAStar astar(grid);
    for (int size = 1; size <= 3; ++size) {
      const Agent agent{size, costs.capability()};
      const CostField field(grid, agent, costs);
      const QuerySampler sampler(grid, agent);
      if (!sampler.hasReachablePair()) continue;
      SplitMix64 rng(seed * 10 + static_cast<std::uint64_t>(size));
      for (int q = 0; q < 8; ++q) {
        const Query query = sampler.reachablePair(rng);
        const std::vector<double> best = bruteForce(grid, agent, costs, query.goal);
        const double expected = best[grid.map().indexOf(query.start)];
        std::vector<Cell> path;
        const PathResult r = astar.findPath(agent, query.start, query.goal, &path, field);
        ASSERT_TRUE(r.found()) << "seed " << seed << " size " << size;
        EXPECT_NEAR(r.cost, expected, 1e-9) << "seed " << seed << " size " << size;
        EXPECT_NEAR(field.pathCost(path), r.cost, 1e-9);
        EXPECT_EQ(findIllegalStep(grid, agent, path), "");
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 100);
}

TEST(TerrainCosts, AFootprintPaysItsSlowestTerrain) {
  GridMap map(6, 6);
  map.set({3, 3}, Terrain::Swamp);
  const AnnotatedGrid grid(std::move(map));
  const TerrainCosts costs = infantryCosts();
  const CostField small(grid, {1, kLand}, costs);
  const CostField big(grid, {2, kLand}, costs);
  EXPECT_DOUBLE_EQ(small.at(grid.map().indexOf({2, 2})), 1.0 / 1.5);
  EXPECT_DOUBLE_EQ(small.at(grid.map().indexOf({3, 3})), 1.0 / 0.8);
  EXPECT_DOUBLE_EQ(big.at(grid.map().indexOf({2, 2})), 1.0 / 0.8);  // covers (3, 3)
  EXPECT_DOUBLE_EQ(big.at(grid.map().indexOf({0, 0})), 1.0 / 1.5);
  EXPECT_TRUE(std::isinf(big.at(grid.map().indexOf({5, 5}))));  // the footprint leaves the map
  // A cardinal move: the mean of its two anchors; a diagonal: √2 times the mean of four.
  EXPECT_DOUBLE_EQ(small.moveCost({2, 3}, directionOf(1, 0)), (1.0 / 1.5 + 1.0 / 0.8) / 2.0);
  EXPECT_DOUBLE_EQ(small.moveCost({2, 2}, directionOf(1, 1)),
                   kSqrt2 * (3.0 / 1.5 + 1.0 / 0.8) / 4.0);
}

TEST(TerrainCosts, InfantryGoRoundASwampWhenThatIsFaster) {
  // A swamp 7 cells wide across the straight line: going round it is longer and faster.
  GridMap map(21, 9);
  for (int y = 0; y < 6; ++y) {
    for (int x = 7; x <= 13; ++x)
      map.set({x, y}, Terrain::Swamp);
  }
  const AnnotatedGrid grid(std::move(map));
  const Agent agent{1, kLand};
  const CostField field(grid, agent, infantryCosts());
  AnnotatedAStar astar(grid);
  std::vector<Cell> weighted;
  ASSERT_TRUE(astar.findPath(agent, {1, 2}, {19, 2}, &weighted, field).found());
  for (const Cell& c : weighted)
    EXPECT_NE(grid.map().at(c), Terrain::Swamp) << c.x << "," << c.y;
  std::vector<Cell> uniform;
  ASSERT_TRUE(astar.findPath(agent, {1, 2}, {19, 2}, &uniform).found());
  EXPECT_LT(field.pathCost(weighted), field.pathCost(uniform));
  EXPECT_GT(pathCost(weighted), pathCost(uniform));
}

TEST(TerrainCosts, ReadsWarthogCostTables) {
  const Result<TerrainCosts> ok = parseCostTable(". 1.5\nG\t1.5\n\nS 4\nT 0\n@ 0\n", "c.txt");
  ASSERT_TRUE(ok.ok()) << ok.error().describe();
  EXPECT_EQ(ok.value().perCell[static_cast<std::size_t>(Terrain::Ground)], 1.5);
  EXPECT_EQ(ok.value().perCell[static_cast<std::size_t>(Terrain::Swamp)], 4.0);
  // Trees cost 0 and water is not named: both impassable.
  EXPECT_EQ(ok.value().capability(), Capability::of({Terrain::Ground, Terrain::Swamp}));
  const std::pair<const char*, const char*> bad[] = {
      {". 1\nX 2\n", "c.txt:2: unknown map character 'X'"},
      {". 1\nG 2\n", "c.txt:2: 'G' is ground, whose cost line 1 already set to"},
      {". -1\n", "c.txt:1: cost of '.' must be a number >= 0, found '-1'"},
      {"@ 3\n", "c.txt:1: '@' is blocked terrain: its cost must be 0, found '3'"},
      {"S\n", "c.txt:1: missing cost after 'S'"},
      {"\n", "c.txt:1: empty cost table"},
  };
  for (const auto& [text, message] : bad) {
    const Result<TerrainCosts> r = parseCostTable(text, "c.txt");
    ASSERT_FALSE(r.ok()) << text;
    EXPECT_EQ(r.error().describe().rfind(message, 0), 0u) << r.error().describe();
  }
}

}  // namespace
}  // namespace warpath::pathing
