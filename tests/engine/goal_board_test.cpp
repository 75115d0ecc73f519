// The goal board: who holds which cells, and the digests the state hash and the rules read.

#include "engine/goal_board.h"

#include <gtest/gtest.h>

namespace warpath::engine {
namespace {

using pathing::Cell;
using pathing::CellRect;

TEST(GoalBoard, DigestsFollowTheContentNotTheHistory) {
  const pathing::GridMap map(40, 24);
  GoalBoard a(map);
  GoalBoard b(map);
  a.take(GoalLayer::Parked, {3, 3}, 2, UnitId{0, 0});
  a.take(GoalLayer::Claimed, {30, 20}, 1, UnitId{1, 0});
  b.take(GoalLayer::Claimed, {30, 20}, 1, UnitId{1, 0});
  b.take(GoalLayer::Parked, {10, 10}, 1, UnitId{2, 0});
  b.release(GoalLayer::Parked, {10, 10}, 1, UnitId{2, 0});
  b.take(GoalLayer::Parked, {3, 3}, 2, UnitId{0, 0});
  EXPECT_EQ(a.digest(), b.digest());
  const CellRect all{0, 0, 40, 24};
  EXPECT_EQ(a.digestAround(all), a.digest());
  EXPECT_EQ(a.digestAround({2, 2, 4, 4}), b.digestAround({2, 2, 4, 4}));
}

TEST(GoalBoard, ADigestAroundAnAreaMovesWithChangesInItOnly) {
  const pathing::GridMap map(40, 24);
  GoalBoard board(map);
  const CellRect area{16, 8, 8, 8};
  const std::uint64_t empty = board.digestAround(area);
  // Far away (another block): the area's digest stays.
  board.take(GoalLayer::Parked, {35, 1}, 1, UnitId{0, 0});
  EXPECT_EQ(board.digestAround(area), empty);
  EXPECT_NE(board.digest(), 0u);
  // In the area, in either layer: it moves, and comes back when the cell is let go.
  board.take(GoalLayer::Claimed, {23, 15}, 1, UnitId{1, 0});
  const std::uint64_t claimed = board.digestAround(area);
  EXPECT_NE(claimed, empty);
  board.take(GoalLayer::Parked, {16, 8}, 1, UnitId{2, 0});
  EXPECT_NE(board.digestAround(area), claimed);
  board.release(GoalLayer::Parked, {16, 8}, 1, UnitId{2, 0});
  EXPECT_EQ(board.digestAround(area), claimed);
  // A different holder of the same cell is a different board.
  board.overwrite(GoalLayer::Claimed, {23, 15}, 1, UnitId{3, 0});
  EXPECT_NE(board.digestAround(area), claimed);
  // Areas reaching off the map are clipped.
  EXPECT_EQ(board.digestAround({-5, -5, 100, 100}), board.digest());
}

}  // namespace
}  // namespace warpath::engine
