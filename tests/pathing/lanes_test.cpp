// Lanes: paths kept to the right half of passages wide enough for two (pathing/lanes.h).

#include "pathing/lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/inline_maps.h"
#include "random_grid.h"

namespace warpath::pathing {
namespace {

// 40×20 ground; a river of water over columns 12..27, crossed by a bridge over rows
// bridgeTop .. bridgeTop + bridgeWidth - 1.
GridMap riverMap(int bridgeTop, int bridgeWidth) {
  GridMap map(40, 20);
  for (int y = 0; y < 20; ++y) {
    for (int x = 12; x <= 27; ++x) {
      if (y < bridgeTop || y >= bridgeTop + bridgeWidth) map.set({x, y}, Terrain::Water);
    }
  }
  return map;
}

std::vector<Cell> shortest(const AnnotatedGrid& grid, Agent agent, Cell start, Cell goal) {
  AnnotatedAStar astar(grid);
  std::vector<Cell> path;
  EXPECT_TRUE(astar.findPath(agent, start, goal, &path).found());
  return path;
}

// Legal single moves from the same start to the same goal.
void expectLegalBetween(const AnnotatedGrid& grid, Agent agent, const std::vector<Cell>& lane,
                        const std::vector<Cell>& path) {
  ASSERT_FALSE(lane.empty());
  EXPECT_EQ(lane.front(), path.front());
  EXPECT_EQ(lane.back(), path.back());
  EXPECT_EQ(findIllegalStep(grid, agent, lane), "");
}

// The rows the anchors take over the bridge's middle columns.
std::vector<int> rowsOnBridge(const std::vector<Cell>& path) {
  std::vector<int> rows;
  for (const Cell& c : path) {
    if (c.x >= 15 && c.x <= 24) rows.push_back(c.y);
  }
  return rows;
}

TEST(Lanes, TanksCrossingABridgeBothWaysKeepToOppositeHalves) {
  // A bridge six cells wide (rows 7..12): two size-3 tanks fit side by side, one per half.
  const AnnotatedGrid grid(riverMap(7, 6));
  const Agent tank{3, kGround};
  const std::vector<Cell> east = shortest(grid, tank, {2, 8}, {35, 8});
  const std::vector<Cell> eastLane = keepRight(grid, tank, east);
  expectLegalBetween(grid, tank, eastLane, east);
  // Heading east the right is south: footprints on rows 10..12.
  for (const int y : rowsOnBridge(eastLane))
    EXPECT_EQ(y, 10);
  const std::vector<Cell> west = shortest(grid, tank, {35, 9}, {2, 9});
  const std::vector<Cell> westLane = keepRight(grid, tank, west);
  expectLegalBetween(grid, tank, westLane, west);
  for (const int y : rowsOnBridge(westLane))
    EXPECT_EQ(y, 7);
  EXPECT_FALSE(rowsOnBridge(eastLane).empty());
  EXPECT_FALSE(rowsOnBridge(westLane).empty());
}

TEST(Lanes, InfantryKeepToTheRightHalfOfTheBridge) {
  const AnnotatedGrid grid(riverMap(7, 6));
  const Agent infantry{1, kGround};
  const std::vector<Cell> east = shortest(grid, infantry, {2, 7}, {35, 7});
  const std::vector<Cell> lane = keepRight(grid, infantry, east);
  expectLegalBetween(grid, infantry, lane, east);
  ASSERT_FALSE(rowsOnBridge(lane).empty());
  for (const int y : rowsOnBridge(lane))
    EXPECT_GE(y, 10);
}

TEST(Lanes, NoLanesInTheOpenNorWhereTwoCannotPass) {
  // Open ground wider than laneWidth: the path stays.
  const AnnotatedGrid open(GridMap(60, 60));
  const Agent infantry{1, kGround};
  const std::vector<Cell> across = shortest(open, infantry, {2, 30}, {57, 30});
  EXPECT_EQ(keepRight(open, infantry, across), across);
  // A bridge four cells wide has no room for two size-3 tanks: nothing to keep to.
  const AnnotatedGrid narrow(riverMap(7, 4));
  const Agent tank{3, kGround};
  const std::vector<Cell> east = shortest(narrow, tank, {2, 8}, {35, 8});
  EXPECT_EQ(keepRight(narrow, tank, east), east);
}

TEST(Lanes, NoLanesThroughAShortPassage) {
  // A river only 4 columns wide: its 6-wide bridge is shorter than a lane's run.
  GridMap map(40, 20);
  for (int y = 0; y < 20; ++y) {
    for (int x = 18; x <= 21; ++x) {
      if (y < 7 || y >= 13) map.set({x, y}, Terrain::Water);
    }
  }
  const AnnotatedGrid shortBridge(map);
  const Agent infantry{1, kGround};
  const std::vector<Cell> across = shortest(shortBridge, infantry, {2, 8}, {37, 8});
  EXPECT_EQ(keepRight(shortBridge, infantry, across), across);
  // The whole of a 30x5 map is a passage for infantry: a path along its top row moves to the
  // right half (for a detour of two diagonals), one along its bottom row is there already.
  const AnnotatedGrid strip{GridMap(30, 5)};
  const std::vector<Cell> top = shortest(strip, infantry, {0, 0}, {29, 0});
  EXPECT_NE(keepRight(strip, infantry, top), top);
  const std::vector<Cell> bottom = shortest(strip, infantry, {0, 4}, {29, 4});
  EXPECT_EQ(keepRight(strip, infantry, bottom), bottom);
  // Short of a lane's run, the same strip keeps every path.
  const AnnotatedGrid shortStrip{GridMap(8, 5)};
  const std::vector<Cell> shortTop = shortest(shortStrip, infantry, {0, 0}, {7, 0});
  EXPECT_EQ(keepRight(shortStrip, infantry, shortTop), shortTop);
}

// A crossroads: corridors 8 wide (rows and columns 28..35) across a 64×64 map, rock elsewhere.
GridMap crossroadsMap() {
  GridMap map(64, 64);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      if ((y < 28 || y > 35) && (x < 28 || x > 35)) map.set({x, y}, Terrain::Blocked);
    }
  }
  return map;
}

// The rows a path's anchors take over columns x0..x1.
std::vector<int> rowsOver(const std::vector<Cell>& path, int x0, int x1) {
  std::vector<int> rows;
  for (const Cell& c : path) {
    if (c.x >= x0 && c.x <= x1) rows.push_back(c.y);
  }
  return rows;
}

TEST(Lanes, ALaneGoesOnThroughAJunction) {
  const AnnotatedGrid grid(crossroadsMap());
  const Agent tank{3, kGround};
  // From the west arm's middle to the east arm's top row: the shortest path drifts north.
  const std::vector<Cell> east = shortest(grid, tank, {4, 30}, {58, 28});
  const std::vector<Cell> lane = keepRight(grid, tank, east);
  expectLegalBetween(grid, tank, lane, east);
  // Heading east the right is south: the lane's row in the west arm (footprints in the south
  // half, rows 32..35) holds across the junction (columns 28..35) and into the east arm.
  const std::vector<int> westArm = rowsOver(lane, 16, 22);
  ASSERT_FALSE(westArm.empty());
  const int row = westArm.front();
  EXPECT_GE(row, 32);
  for (const int y : westArm)
    EXPECT_EQ(y, row);
  const std::vector<int> junction = rowsOver(lane, 26, 37);
  ASSERT_FALSE(junction.empty());
  for (const int y : junction)
    EXPECT_EQ(y, row);
  // As lanes were before replay format 12: the lane ends at the junction, where the path comes
  // back north toward its own line.
  const std::vector<Cell> ending =
      keepRight(grid, tank, east, {.throughJunctions = false, .holdBeyond = false});
  expectLegalBetween(grid, tank, ending, east);
  const std::vector<int> junctionBefore = rowsOver(ending, 26, 37);
  EXPECT_LT(*std::min_element(junctionBefore.begin(), junctionBefore.end()), row);
}

// `lane` keeps row `row` over anchor columns x0..x1 and is one row back (north) at the column
// just outside each end, where it starts to taper.
void expectRowHeldOver(const std::vector<Cell>& lane, int row, int x0, int x1) {
  for (const int y : rowsOver(lane, x0, x1))
    EXPECT_EQ(y, row) << "columns " << x0 << ".." << x1;
  EXPECT_EQ(rowsOver(lane, x0 - 1, x0 - 1), std::vector<int>{row - 1});
  EXPECT_EQ(rowsOver(lane, x1 + 1, x1 + 1), std::vector<int>{row - 1});
}

TEST(Lanes, ALaneHoldsTwoFootprintsBeyondItsBridge) {
  // 60×20 ground; a river over columns 22..37 crossed by a bridge six cells wide (rows 7..12),
  // with room on both banks for a longer hold than two footprints to show. A tank's footprint
  // is on the bridge from anchor column 20 to 37. Heading east its lane there is row 10 (the
  // south half); its path from the west runs along row 8.
  GridMap map(60, 20);
  for (int y = 0; y < 20; ++y) {
    for (int x = 22; x <= 37; ++x) {
      if (y < 7 || y > 12) map.set({x, y}, Terrain::Water);
    }
  }
  const AnnotatedGrid grid(map);
  const Agent tank{3, kGround};
  const std::vector<Cell> east = shortest(grid, tank, {2, 8}, {57, 8});
  const std::vector<Cell> held = keepRight(grid, tank, east);
  expectLegalBetween(grid, tank, held, east);
  // The lane's row holds for two footprints (six columns) before and after the bridge, then
  // tapers a row a cell.
  expectRowHeldOver(held, 10, 14, 43);
  // Without the hold (replay formats before 18) the lane tapers from the bridge's ends.
  const std::vector<Cell> ending = keepRight(grid, tank, east, {.holdBeyond = false});
  expectLegalBetween(grid, tank, ending, east);
  for (const int y : rowsOver(ending, 20, 37))
    EXPECT_EQ(y, 10);
  EXPECT_EQ(rowsOver(ending, 19, 19), std::vector<int>{9});
  EXPECT_EQ(rowsOver(ending, 18, 18), std::vector<int>{8});
  EXPECT_EQ(rowsOver(ending, 39, 39), std::vector<int>{8});
  // Held or not, the lane costs the same: the held stretch runs parallel to the path.
  EXPECT_NEAR(pathCost(held), pathCost(ending), 1e-9);
}

TEST(Lanes, ALaneHoldsFiveFootprintsBeyondABridgeFiveFootprintsWide) {
  // 80×24 ground; a river over columns 32..47 crossed by a bridge 15 cells wide (rows 4..18):
  // five tank footprints across. A tank's footprint is on the bridge from anchor column 30 to
  // 47. Heading east from row 5 its lane there is row 12 (the south half).
  GridMap map(80, 24);
  for (int y = 0; y < 24; ++y) {
    for (int x = 32; x <= 47; ++x) {
      if (y < 4 || y > 18) map.set({x, y}, Terrain::Water);
    }
  }
  const AnnotatedGrid grid(map);
  const Agent tank{3, kGround};
  const std::vector<Cell> east = shortest(grid, tank, {2, 5}, {75, 5});
  const std::vector<Cell> held = keepRight(grid, tank, east);
  expectLegalBetween(grid, tank, held, east);
  // Five footprints (15 columns) before and after the bridge, then a row a cell.
  expectRowHeldOver(held, 12, 15, 62);
  // Two footprints, as on narrower passages (the six-wide bridge above) and in replay formats
  // before 20.
  const std::vector<Cell> near = keepRight(grid, tank, east, {.holdFartherWhereWide = false});
  expectLegalBetween(grid, tank, near, east);
  expectRowHeldOver(near, 12, 24, 53);
  EXPECT_NEAR(pathCost(held), pathCost(near), 1e-9);
  // A bridge one row narrower (four footprints) holds two footprints only.
  for (int x = 32; x <= 47; ++x)
    map.set({x, 18}, Terrain::Water);
  const AnnotatedGrid narrower(map);
  EXPECT_EQ(keepRight(narrower, tank, east),
            keepRight(narrower, tank, east, {.holdFartherWhereWide = false}));
}

TEST(Lanes, AJeepOnABridgeSixteenWideShiftsHalfItsWidth) {
  // 80×24 ground; a river over columns 32..47 crossed by a bridge 16 cells wide (rows 4..19),
  // bridge16_mixed's and bridge_2000's. A jeep heading east along the north edge (row 4) has
  // its lane 8 rows south (row 12), and the diagonal steps there and back cost more than the
  // fixed allowance of 6 cells for a size-2 agent.
  GridMap map(80, 24);
  for (int y = 0; y < 24; ++y) {
    for (int x = 32; x <= 47; ++x) {
      if (y < 4 || y > 19) map.set({x, y}, Terrain::Water);
    }
  }
  const AnnotatedGrid grid(map);
  const Agent jeep{2, kGround};
  const std::vector<Cell> east = shortest(grid, jeep, {2, 4}, {75, 4});
  const std::vector<Cell> lane = keepRight(grid, jeep, east);
  expectLegalBetween(grid, jeep, lane, east);
  for (const int y : rowsOver(lane, 32, 46))
    EXPECT_EQ(y, 12);
  EXPECT_GT(pathCost(lane) - pathCost(east), 6.0);
  EXPECT_LE(pathCost(lane) - pathCost(east), 8.0);
  // Before replay format 22 the lane was dropped for its cost.
  EXPECT_EQ(keepRight(grid, jeep, east, {.detourByShift = false}), east);
}

TEST(Lanes, AlwaysLegalOnRandomMaps) {
  int shifted = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const AnnotatedGrid grid = randomGrid(40, 30, seed, 20);
    AnnotatedAStar astar(grid);
    for (int size = 1; size <= 2; ++size) {
      const Agent agent{size, kGround};
      std::vector<Cell> path;  // corner to corner, where the agent can go
      if (!astar.findPath(agent, {1, 1}, {36, 26}, &path).found()) continue;
      const std::vector<Cell> lane = keepRight(grid, agent, path);
      expectLegalBetween(grid, agent, lane, path);
      // A lane is a short detour: a few cells per footprint side, or its shift (at most half
      // the widest passage with lanes) there and back.
      const double allowed = std::max(2.0 * size + 2.0, static_cast<double>(laneWidth(size)));
      EXPECT_LE(pathCost(lane), pathCost(path) + allowed + 1e-9) << seed;
      if (lane != path) ++shifted;
    }
  }
  EXPECT_GT(shifted, 0);  // the random maps have passages that get lanes
}

}  // namespace
}  // namespace warpath::pathing
