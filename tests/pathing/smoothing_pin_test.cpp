// HAA*'s smoothing pinned: a fingerprint of every cell of the paths it returns on mazes (where
// nearly every shortcut it weighs fails) and on open and patchwork maps (where many succeed).
// Faster smoothing must take exactly the shortcuts it took: the engine's units follow these
// paths, so a change shows here before it moves a scenario's state hash.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "pathing/cluster_abstraction.h"
#include "pathing/haa_star.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"
#include "random_grid.h"
#include "support/fingerprint.h"

namespace warpath::pathing {
namespace {

// A perfect maze of `cols` x `rows` rooms `corridor` cells wide, walls one cell thick, carved
// by a depth-first walk from the first room.
GridMap pinMaze(int cols, int rows, int corridor, std::uint64_t seed) {
  const int pitch = corridor + 1;
  GridMap map(cols * pitch + 1, rows * pitch + 1, Terrain::Blocked);
  const auto carve = [&](int x0, int y0, int width, int height) {
    for (int y = y0; y < y0 + height; ++y) {
      for (int x = x0; x < x0 + width; ++x)
        map.set({x, y}, Terrain::Ground);
    }
  };
  SplitMix64 random(seed);
  std::vector<bool> seen(static_cast<std::size_t>(cols * rows), false);
  std::vector<std::pair<int, int>> stack{{0, 0}};
  seen[0] = true;
  carve(1, 1, corridor, corridor);
  constexpr int kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  while (!stack.empty()) {
    const auto [cx, cy] = stack.back();
    int options[4];
    int count = 0;
    for (int d = 0; d < 4; ++d) {
      const int nx = cx + kSteps[d][0];
      const int ny = cy + kSteps[d][1];
      if (nx >= 0 && ny >= 0 && nx < cols && ny < rows &&
          !seen[static_cast<std::size_t>(ny * cols + nx)])
        options[count++] = d;
    }
    if (count == 0) {
      stack.pop_back();
      continue;
    }
    const int d = options[random.below(static_cast<std::uint32_t>(count))];
    const int nx = cx + kSteps[d][0];
    const int ny = cy + kSteps[d][1];
    seen[static_cast<std::size_t>(ny * cols + nx)] = true;
    // The room and the wall between the two.
    const int x0 = 1 + std::min(cx, nx) * pitch;
    const int y0 = 1 + std::min(cy, ny) * pitch;
    carve(x0, y0, kSteps[d][0] != 0 ? 2 * pitch - 1 : corridor,
          kSteps[d][1] != 0 ? 2 * pitch - 1 : corridor);
    stack.push_back({nx, ny});
  }
  return map;
}

struct PinnedRun {
  std::uint64_t fingerprint = 0;
  int queries = 0;
  int shortened = 0;    // smoothing found a path cheaper than the refined one
  int revisits = 0;     // smoothed paths that visit a cell twice
  int rawRevisits = 0;  // refined ones: loops for smoothing to cut
};

bool visitsACellTwice(std::vector<Cell> cells) {
  std::sort(cells.begin(), cells.end(),
            [](Cell a, Cell b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
  return std::adjacent_find(cells.begin(), cells.end()) != cells.end();
}

// Queries between random cells where each agent can stand, answered smoothed and unsmoothed:
// ground agents of sizes 1 and 2, or with `costs` the one size-1 agent of a weighted graph.
PinnedRun runPinQueries(const GridMap& map, std::uint64_t seed,
                        AbstractionQuality quality = AbstractionQuality::High,
                        std::optional<TerrainCosts> costs = std::nullopt) {
  const AnnotatedGrid grid(map);
  const Capability capability = costs ? costs->capability() : Capability::of({Terrain::Ground});
  const AbstractionSpec spec{.clusterSize = 16,
                             .maxAgentSize = costs ? 1 : 2,
                             .capabilities = {capability},
                             .quality = quality,
                             .costs = costs};
  const ClusterAbstraction abstraction = ClusterAbstraction::build(grid, spec);
  HierarchicalAStar smoothed(abstraction, HaaOptions{});
  HierarchicalAStar raw(abstraction, HaaOptions{.smooth = false});
  SplitMix64 random(seed);
  const auto anyCell = [&](Agent agent) {
    for (int tries = 0; tries < 10000; ++tries) {
      const Cell c{random.between(0, map.width() - 1), random.between(0, map.height() - 1)};
      if (grid.canStand(agent, c)) return c;
    }
    return Cell{-1, -1};
  };
  PinnedRun run;
  testing::Fingerprint f;
  std::vector<Cell> path;
  std::vector<Cell> unsmoothed;
  for (int size = 1; size <= spec.maxAgentSize; ++size) {
    const Agent agent{.size = size, .capability = capability};
    for (int q = 0; q < 150; ++q) {
      const Cell start = anyCell(agent);
      const Cell goal = anyCell(agent);
      if (start.x < 0 || goal.x < 0) break;
      const PathResult r = smoothed.findPath(agent, start, goal, &path);
      const PathResult u = raw.findPath(agent, start, goal, &unsmoothed);
      ++run.queries;
      f.add(static_cast<std::uint64_t>(r.status));
      for (const Cell c : path)
        f.add(c);
      if (r.found() && r.cost < u.cost - 1e-9) ++run.shortened;
      if (visitsACellTwice(path)) ++run.revisits;
      if (visitsACellTwice(unsmoothed)) ++run.rawRevisits;
    }
  }
  run.fingerprint = f.value;
  return run;
}

struct PinCase {
  const char* name;
  GridMap map;
  std::uint64_t pinned;  // the fingerprint of its paths, from the code before the reach screen
};

TEST(SmoothingPin, MazesOpenAndPatchworkMapsTakeThePinnedShortcuts) {
  const PinCase cases[] = {
      {"maze, corridors 3 wide", pinMaze(25, 25, 3, 3), 5059739425473341551u},
      {"maze, corridors 2 wide", pinMaze(30, 30, 2, 5), 6448732547460962942u},
      {"maze, corridors 4 wide", pinMaze(20, 20, 4, 7), 2776193406088344704u},
      {"random, 10 % blocked", randomBlockedMap(100, 100, 11, 10), 1382875130746604065u},
      {"patchwork", randomTerrainMap(13, 100, 100, 8, 20), 18282239086067315641u},
  };
  for (const PinCase& c : cases) {
    const PinnedRun run = runPinQueries(c.map, 17);
    // Each map must exercise smoothing, or the pin proves little.
    EXPECT_GE(run.queries, 150) << c.name;
    EXPECT_GT(run.shortened, run.queries / 10) << c.name;
    EXPECT_EQ(run.fingerprint, c.pinned) << c.name;
    EXPECT_EQ(run.revisits, 0) << c.name;
  }
}

// LQ graphs' refined paths often visit a cell twice (on these mazes, a third to two thirds of
// them): smoothing's first pass cuts those loops, and no smoothed path visits a cell twice.
TEST(SmoothingPin, LowQualityGraphsLoopsAreCutAsPinned) {
  const PinCase cases[] = {
      {"maze, corridors 2 wide", pinMaze(30, 30, 2, 5), 11635720626050430032u},
      {"maze, corridors 4 wide", pinMaze(20, 20, 4, 7), 13332942205369746414u},
  };
  for (const PinCase& c : cases) {
    const PinnedRun run = runPinQueries(c.map, 17, AbstractionQuality::Low);
    EXPECT_GT(run.rawRevisits, run.queries / 10) << c.name;
    EXPECT_EQ(run.revisits, 0) << c.name;
    EXPECT_EQ(run.fingerprint, c.pinned) << c.name;
  }
}

// Under terrain costs a shortcut must also be faster, and ends only where the path turns.
TEST(SmoothingPin, AWeightedGraphTakesThePinnedShortcuts) {
  TerrainCosts infantry;  // s per cell: speeds 1.5 on ground, 0.8 in swamp, 1 in trees
  infantry.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  infantry.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  infantry.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  const PinnedRun run =
      runPinQueries(randomTerrainMap(19, 100, 100, 8, 20), 23, AbstractionQuality::High, infantry);
  EXPECT_GE(run.queries, 150);
  EXPECT_GT(run.shortened, run.queries / 10);
  EXPECT_EQ(run.fingerprint, 14316635237735178048u);
}

}  // namespace
}  // namespace warpath::pathing
