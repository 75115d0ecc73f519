// Space-time reservations and the cooperative window search (pathing/reservation_table.h,
// pathing/cooperative_search.h).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "cooperative_request.h"
#include "pathing/aa_star.h"
#include "pathing/cooperative_search.h"
#include "pathing/inline_maps.h"
#include "pathing/map_io.h"
#include "pathing/moves.h"
#include "random_grid.h"

namespace warpath::pathing {
namespace {

TEST(ReservationTable, FootprintsOverHalfOpenIntervals) {
  ReservationTable table(10, 10);
  table.reserve({2, 2}, 3, 10, 20, 7);
  EXPECT_EQ(table.blocker({4, 4}, 1, 15, 16, 1), std::optional<std::uint32_t>(7));
  EXPECT_TRUE(table.isFree({5, 5}, 1, 15, 16, 1));   // outside the 3x3 footprint
  EXPECT_TRUE(table.isFree({2, 2}, 1, 20, 30, 1));   // the interval ends at 20
  EXPECT_TRUE(table.isFree({2, 2}, 1, 0, 10, 1));    // and starts at 10
  EXPECT_TRUE(table.isFree({2, 2}, 3, 10, 20, 7));   // its own
  EXPECT_FALSE(table.isFree({0, 0}, 3, 19, 25, 1));  // a size-3 footprint touching it
  table.reserve({1, 1}, 1, 0, kForever, 3);
  EXPECT_EQ(table.blocker({0, 0}, 3, 12, 13, 1), std::optional<std::uint32_t>(3));  // lowest
  EXPECT_EQ(table.heldBy(7).size(), 1u);
  table.release(7);
  EXPECT_TRUE(table.isFree({4, 4}, 1, 15, 16, 1));
  EXPECT_EQ(table.intervalCount(), 1u);
  table.reserve({8, 8}, 1, 0, 5, 4);
  table.forget(5);
  EXPECT_EQ(table.intervalCount(), 1u);  // the forever one stays
}

TEST(ReservationTable, KeepsOnlyTrackedCells) {
  ReservationTable table = ReservationTable::trackingNothing(4, 1);
  table.reserve({0, 0}, 1, 0, 10, 1);
  EXPECT_TRUE(table.isFree({0, 0}, 1, 0, 10, 2));
  table.track(std::vector<std::uint8_t>{1, 0, 0, 0});
  EXPECT_TRUE(table.tracks({0, 0}, 1));
  EXPECT_FALSE(table.tracks({1, 0}, 1));
  table.reserve({0, 0}, 2, 0, 10, 1);
  EXPECT_FALSE(table.isFree({0, 0}, 1, 0, 10, 2));
  EXPECT_TRUE(table.isFree({1, 0}, 1, 0, 10, 2));
}

// tracks() of a footprint (read from a per-size map) says whether any of its cells on the map is
// tracked, anchors on the edges and off the map included, and follows later track() calls.
TEST(ReservationTable, AFootprintIsTrackedWhenACellOfItIs) {
  constexpr int kWidth = 13;
  constexpr int kHeight = 9;
  SplitMix64 rng(12);
  ReservationTable table = ReservationTable::trackingNothing(kWidth, kHeight);
  std::vector<std::uint8_t> tracked(kWidth * kHeight, 0);
  for (int round = 0; round < 4; ++round) {
    std::vector<std::uint8_t> more(tracked.size(), 0);
    for (int k = 0; k < 3; ++k)
      more[static_cast<std::size_t>(rng.between(0, kWidth * kHeight - 1))] = 1;
    if (round == 2) {  // the last column and row, where footprints are clipped
      more[kWidth - 1] = 1;
      more[static_cast<std::size_t>((kHeight - 1) * kWidth + 4)] = 1;
    }
    for (std::size_t i = 0; i < more.size(); ++i)
      tracked[i] = static_cast<std::uint8_t>(tracked[i] | more[i]);
    table.track(more);
    for (int size = 1; size <= 4; ++size) {
      for (int y = -size; y < kHeight + 1; ++y) {
        for (int x = -size; x < kWidth + 1; ++x) {
          bool any = false;
          for (int dy = 0; dy < size; ++dy) {
            for (int dx = 0; dx < size; ++dx) {
              const int cx = x + dx;
              const int cy = y + dy;
              if (cx >= 0 && cy >= 0 && cx < kWidth && cy < kHeight)
                any = any || tracked[static_cast<std::size_t>(cy * kWidth + cx)] != 0;
            }
          }
          EXPECT_EQ(table.tracks({x, y}, size), any)
              << "round " << round << " size " << size << " at " << x << "," << y;
        }
      }
    }
  }
}

// Each step is a wait or one legal move lasting what its terrain says.
void expectLegal(const AnnotatedGrid& grid, const CooperativeRequest& r,
                 const std::vector<TimedCell>& steps) {
  ASSERT_FALSE(steps.empty());
  EXPECT_EQ(steps.front().cell, r.start);
  EXPECT_EQ(steps.front().tick, r.startTick);
  for (std::size_t i = 1; i < steps.size(); ++i) {
    const TimedCell& a = steps[i - 1];
    const TimedCell& b = steps[i];
    if (a.cell == b.cell) {
      EXPECT_EQ(b.tick - a.tick, r.waitTicks);
      continue;
    }
    const std::vector<Cell> move{a.cell, b.cell};
    EXPECT_EQ(findIllegalStep(grid, r.agent, move), "") << "step " << i;
    const bool diagonal = a.cell.x != b.cell.x && a.cell.y != b.cell.y;
    const bool atRest = i == 1 ? r.startsAtRest : steps[i - 2].cell == a.cell;
    EXPECT_EQ(b.tick - a.tick, (diagonal ? 15 : 10) + (atRest ? r.startTicks : 0)) << "step " << i;
  }
}

TEST(CooperativeSearch, AloneItTakesTheShortestTime) {
  // On an empty table the plan to a goal within the window costs what AA* says, in ticks.
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const AnnotatedGrid grid = randomGrid(40, 30, seed, 20);
    AnnotatedAStar astar(grid);
    CooperativeSearch search(grid);
    ReservationTable table(grid.map().width(), grid.map().height());
    for (int size = 1; size <= 2; ++size) {
      const Agent agent{size, kGround};
      const Cell start{1, 1};
      const Cell goal{36, 26};
      std::vector<Cell> path;
      if (!grid.canStand(agent, start) || !grid.canStand(agent, goal)) continue;
      const PathResult best = astar.findPath(agent, start, goal, &path);
      if (!best.found()) continue;
      ++compared;
      CooperativeRequest r = requestFor(agent, start, goal, 10000);
      r.maxWindow = 10000;
      r.expansionLimit = 1000000;
      CorridorDistance corridor(grid, agent, path, 2);
      ReverseResumableSearch whole(grid, agent, goal, start);
      for (DistanceField* field :
           {static_cast<DistanceField*>(&corridor), static_cast<DistanceField*>(&whole)}) {
        const CooperativePlan plan = search.plan(r, *field, table);
        ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal) << "seed " << seed;
        expectLegal(grid, r, plan.steps);
        // Cardinal 10 ticks, diagonal 15 (ceil of 14.14): the AA* path's own timing.
        Tick ticks = 0;
        for (std::size_t i = 1; i < path.size(); ++i)
          ticks += path[i].x != path[i - 1].x && path[i].y != path[i - 1].y ? 15 : 10;
        EXPECT_LE(plan.steps.back().tick, ticks) << "seed " << seed << " size " << size;
        EXPECT_DOUBLE_EQ(whole.distance(start), best.cost);
      }
    }
  }
  EXPECT_GE(compared, 6);
}

TEST(CooperativeSearch, AMoveFromRestTakesLonger) {
  // Five cells east on open ground: 50 ticks at speed; a start from rest adds startTicks once,
  // and so does setting off again after a wait.
  const AnnotatedGrid grid(
      mapFromRows("type octile\nheight 3\nwidth 10\nmap\n..........\n..........\n..........\n"));
  const Agent agent{1, kGround};
  CooperativeSearch search(grid);
  ReservationTable table(10, 3);
  CooperativeRequest r = requestFor(agent, {0, 1}, {5, 1}, 200);
  r.startTicks = 7;
  ReverseResumableSearch field(grid, agent, r.goal, r.start);
  CooperativePlan plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  EXPECT_EQ(plan.steps.back().tick, 50);
  r.startsAtRest = true;
  plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  expectLegal(grid, r, plan.steps);
  EXPECT_EQ(plan.steps.back().tick, 57);
  // Someone crosses the whole column x = 2 during [10, 40): the agent waits once on the way.
  table.reserve({2, 0}, 1, 10, 40, 9);
  table.reserve({2, 1}, 1, 10, 40, 9);
  table.reserve({2, 2}, 1, 10, 40, 9);
  r.startsAtRest = false;
  plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  expectLegal(grid, r, plan.steps);
  bool waited = false;
  for (std::size_t i = 1; i < plan.steps.size(); ++i)
    waited = waited || plan.steps[i].cell == plan.steps[i - 1].cell;
  EXPECT_TRUE(waited);
}

TEST(CooperativeSearch, SharedReservationsDoNotBlock) {
  // Owner 9 holds the middle column for a long time: the agent waits for it, unless it may
  // share owner 9's reservations (a unit going the same way), while owner 4 still blocks.
  const AnnotatedGrid grid(
      mapFromRows("type octile\nheight 3\nwidth 10\nmap\n..........\n..........\n..........\n"));
  const Agent agent{1, kGround};
  CooperativeSearch search(grid);
  ReservationTable table(10, 3);
  for (int y = 0; y < 3; ++y)
    table.reserve({4, y}, 1, 0, 300, 9);
  CooperativeRequest r = requestFor(agent, {0, 1}, {8, 1}, 400);
  ReverseResumableSearch field(grid, agent, r.goal, r.start);
  CooperativePlan plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  EXPECT_GE(plan.steps.back().tick, 300);
  std::vector<std::uint8_t> sharing(10, 0);
  sharing[9] = 1;
  r.sharing = &sharing;
  plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  expectLegal(grid, r, plan.steps);
  EXPECT_EQ(plan.steps.back().tick, 80);
  table.reserve({6, 0}, 1, 0, 200, 4);
  table.reserve({6, 1}, 1, 0, 200, 4);
  table.reserve({6, 2}, 1, 0, 200, 4);
  plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  EXPECT_GE(plan.steps.back().tick, 200);
  EXPECT_LT(plan.steps.back().tick, 300);
}

// The reference for CorridorDistance: a plain Dijkstra to path.back() over the set of
// standable cells within `radius` of a path cell, +inf elsewhere; per cell index.
std::vector<double> corridorReference(const AnnotatedGrid& grid, Agent agent,
                                      const std::vector<Cell>& path, int radius) {
  const GridMap& map = grid.map();
  std::vector<char> inside(static_cast<std::size_t>(map.width() * map.height()), 0);
  for (const Cell& p : path) {
    for (int y = p.y - radius; y <= p.y + radius; ++y) {
      for (int x = p.x - radius; x <= p.x + radius; ++x) {
        if (map.contains({x, y}) && grid.canStand(agent, {x, y})) inside[map.indexOf({x, y})] = 1;
      }
    }
  }
  std::vector<double> expected(inside.size(), std::numeric_limits<double>::infinity());
  std::set<std::pair<double, std::uint32_t>> open{{0.0, map.indexOf(path.back())}};
  expected[map.indexOf(path.back())] = 0.0;
  const std::span<const std::uint8_t> moves = grid.layer(agent).moveMasks();
  while (!open.empty()) {
    const auto [g, index] = *open.begin();
    open.erase(open.begin());
    const Cell here{static_cast<int>(index) % map.width(), static_cast<int>(index) / map.width()};
    for (int d = 0; d < kDirectionCount; ++d) {
      if ((moves[index] & (1u << d)) == 0) continue;
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      const Cell next{here.x + dir.dx, here.y + dir.dy};
      const std::uint32_t n = map.indexOf(next);
      if (inside[n] == 0 || expected[n] <= g + dir.cost) continue;
      open.erase({expected[n], n});
      expected[n] = g + dir.cost;
      open.insert({expected[n], n});
    }
  }
  return expected;
}

TEST(CorridorDistance, IsDijkstraInsideTheCellsNearThePath) {
  // Against the reference: equal inside, infinite outside, never below the distance on the
  // whole map.
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const AnnotatedGrid grid = randomGrid(48, 36, seed, 12);
    AnnotatedAStar astar(grid);
    const Agent agent{1 + static_cast<int>(seed % 2), kGround};
    const GridMap& map = grid.map();
    // The first cells the agent may stand on from two opposite corners.
    Cell start{-1, -1};
    Cell goal{-1, -1};
    for (int i = 0; i < map.width() * map.height() && (start.x < 0 || goal.x < 0); ++i) {
      const Cell a{i % map.width(), i / map.width()};
      const Cell b{map.width() - 1 - a.x, map.height() - 1 - a.y};
      if (start.x < 0 && grid.canStand(agent, a)) start = a;
      if (goal.x < 0 && grid.canStand(agent, b)) goal = b;
    }
    std::vector<Cell> path;
    if (!astar.findPath(agent, start, goal, &path).found()) continue;
    ++compared;
    const int radius = 1 + static_cast<int>(seed % 3);
    CorridorDistance corridor(grid, agent, path, radius);
    ReverseResumableSearch whole(grid, agent, goal, start);
    const std::vector<double> expected = corridorReference(grid, agent, path, radius);
    for (int y = -1; y <= map.height(); ++y) {
      for (int x = -1; x <= map.width(); ++x) {
        const double got = corridor.distance({x, y});
        if (!map.contains({x, y})) {
          EXPECT_TRUE(std::isinf(got));
          continue;
        }
        EXPECT_DOUBLE_EQ(got, expected[map.indexOf({x, y})])
            << "seed " << seed << " at " << x << "," << y;
        if (std::isfinite(got)) {
          EXPECT_GE(got + 1e-9, whole.distance({x, y}));
        }
      }
    }
  }
  EXPECT_GE(compared, 6);
}

TEST(CorridorDistance, DoesNotCrossTheGapBetweenTwoArmsOfAPath) {
  // A U-shaped path on open ground: down one column, along the bottom, up another. Rows the
  // two arms cross hold two stretches of the corridor with open ground between them, which is
  // outside: distances go round the U, and the ground between is unreached.
  std::ostringstream rows;
  rows << "type octile\nheight 20\nwidth 26\nmap\n";
  for (int y = 0; y < 20; ++y)
    rows << std::string(26, '.') << "\n";
  const AnnotatedGrid grid(mapFromRows(rows.str()));
  const Agent agent{1, kGround};
  std::vector<Cell> path;
  for (int y = 2; y <= 17; ++y)
    path.push_back({3, y});
  for (int x = 4; x <= 20; ++x)
    path.push_back({x, 17});
  for (int y = 16; y >= 2; --y)
    path.push_back({20, y});
  const int radius = 2;
  CorridorDistance corridor(grid, agent, path, radius);
  const std::vector<double> expected = corridorReference(grid, agent, path, radius);
  const GridMap& map = grid.map();
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      EXPECT_DOUBLE_EQ(corridor.distance({x, y}), expected[map.indexOf({x, y})])
          << "at " << x << "," << y;
    }
  }
  EXPECT_TRUE(std::isinf(corridor.distance({12, 8})));  // between the arms
  EXPECT_TRUE(std::isinf(corridor.distance({24, 8})));  // beside the right arm
  // From the top of the left arm round the U: far more than straight across (17 cells).
  EXPECT_GT(corridor.distance({3, 2}), 35.0);
}

TEST(CooperativeSearch, WaitsOutsideAPassageSomeoneHolds) {
  // A door one cell wide: owner 2 crosses it northward; our agent, going south, may not enter
  // it while 2 is there, and may not wait inside it.
  const AnnotatedGrid grid(mapFromRows(
      "type octile\nheight 7\nwidth 7\nmap\n.......\n.......\n.......\n@@@.@@@\n.......\n"
      ".......\n.......\n"));
  const Agent agent{1, kGround};
  CooperativeSearch search(grid);
  ReservationTable table(7, 7);
  const std::vector<TimedCell> theirs{{{3, 6}, 0},  {{3, 5}, 10}, {{3, 4}, 20},
                                      {{3, 3}, 30}, {{3, 2}, 40}, {{3, 1}, 50}};
  CooperativeSearch::reserve(table, theirs, 1, 2, 0);
  CooperativeRequest r = requestFor(agent, {3, 0}, {3, 6}, 100);
  const std::vector<std::uint8_t> room = passingRoom(grid, agent);
  EXPECT_EQ(room[3 * 7 + 3], 0);  // the door
  EXPECT_EQ(room[0], 1);
  r.passing = &room;
  ReverseResumableSearch field(grid, agent, r.goal, r.start);
  const CooperativePlan plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  expectLegal(grid, r, plan.steps);
  for (std::size_t i = 0; i + 1 < plan.steps.size(); ++i) {
    const TimedCell& a = plan.steps[i];
    const TimedCell& b = plan.steps[i + 1];
    if (a.cell == b.cell) {
      EXPECT_NE(room[static_cast<std::size_t>(a.cell.y * 7 + a.cell.x)], 0);
    }
    if (b.cell == Cell{3, 3}) {
      EXPECT_GE(b.tick, 40);  // through the door after them
    }
  }
}

TEST(CooperativeSearch, TwoAgentsCannotSwapCells) {
  const AnnotatedGrid grid(mapFromRows("type octile\nheight 1\nwidth 4\nmap\n....\n"));
  const Agent agent{1, kGround};
  CooperativeSearch search(grid);
  ReservationTable table(4, 1);
  // Owner 2 moves from (2,0) to (1,0) over ticks 0-10 and stays.
  CooperativeSearch::reserve(table, std::vector<TimedCell>{{{2, 0}, 0}, {{1, 0}, 10}}, 1, 2,
                             kForever);
  const MoveSpan theirs = moveSpan(0, 10);
  const CooperativeRequest r = requestFor(agent, {1, 0}, {3, 0}, 100);
  ReverseResumableSearch field(grid, agent, r.goal, r.start);
  const CooperativePlan plan = search.plan(r, field, table);
  // They come into our cell at once and we cannot be out of it before they have left theirs:
  // no safe window (moving at once, each would pass through the other).
  EXPECT_EQ(plan.status, CooperativeStatus::Blocked);
  expectLegal(grid, r, plan.steps);
  for (std::size_t i = 1; i < plan.steps.size(); ++i) {
    if (plan.steps[i].cell != Cell{2, 0} || plan.steps[i - 1].cell == Cell{2, 0}) continue;
    const Tick t = plan.steps[i - 1].tick;
    EXPECT_GE(moveSpan(t, plan.steps[i].tick - t).enterAt, theirs.leaveBy);
  }
}

TEST(CooperativeSearch, AGoalTakenForGoodIsNeverReached) {
  const AnnotatedGrid grid(
      mapFromRows("type octile\nheight 3\nwidth 6\nmap\n......\n......\n......\n"));
  const Agent agent{1, kGround};
  CooperativeSearch search(grid);
  ReservationTable table(6, 3);
  table.reserve({5, 1}, 1, 0, kForever, 2);
  const CooperativeRequest r = requestFor(agent, {0, 1}, {5, 1}, 50);
  ReverseResumableSearch field(grid, agent, r.goal, r.start);
  const CooperativePlan plan = search.plan(r, field, table);
  EXPECT_NE(plan.status, CooperativeStatus::ReachedGoal);
  EXPECT_EQ(search.plan(requestFor(agent, {0, 1}, {9, 9}, 50), field, table).status,
            CooperativeStatus::InvalidGoal);
  CooperativeRequest bad = r;
  bad.waitTicks = 0;
  EXPECT_NE(problemWith(bad), "");
  EXPECT_EQ(problemWith(r), "");
}

TEST(CooperativeSearch, ALargeAgentStepsOutOfAKeptOutBandARowAtATime) {
  // A band of kept-out cells 3 rows deep (the stream out of a passage) under a size-3 agent
  // whose goal lies below it. Stepping out takes 3 moves down, and the first two land on
  // footprints as kept out by their highest level: stepwise, each lowers the cells at that
  // level (9, 6, 3, 0), so the agent steps out at once, never waiting in the band.
  const int side = 12;
  std::string rows = "type octile\nheight 12\nwidth 12\nmap\n";
  for (int y = 0; y < side; ++y)
    rows += std::string(side, '.') + "\n";
  const AnnotatedGrid grid(mapFromRows(rows));
  const Agent agent{3, kGround};
  std::vector<std::uint8_t> keepOut(side * side, 0);
  for (int y = 3; y <= 5; ++y) {
    for (int x = 0; x < side; ++x)
      keepOut[static_cast<std::size_t>(y * side + x)] = 1;
  }
  const auto keptOutCells = [&](Cell anchor) {
    int n = 0;
    for (int dy = 0; dy < 3; ++dy) {
      for (int dx = 0; dx < 3; ++dx)
        n += keepOut[static_cast<std::size_t>((anchor.y + dy) * side + anchor.x + dx)];
    }
    return n;
  };
  CooperativeSearch search(grid);
  ReservationTable table(side, side);
  CooperativeRequest r = requestFor(agent, {4, 3}, {4, 8}, 100);
  r.keepOut = &keepOut;
  ReverseResumableSearch field(grid, agent, r.goal, r.start);
  const CooperativePlan plan = search.plan(r, field, table);
  ASSERT_EQ(plan.status, CooperativeStatus::ReachedGoal);
  expectLegal(grid, r, plan.steps);
  ASSERT_GE(plan.steps.size(), 4u);
  for (std::size_t i = 1; i < plan.steps.size(); ++i) {
    const int before = keptOutCells(plan.steps[i - 1].cell);
    if (before > 0) {
      EXPECT_LT(keptOutCells(plan.steps[i].cell), before) << "step " << i;
    }
  }
  EXPECT_EQ(plan.steps.back().tick, 50);  // 5 moves down, none waited

  // Below the band held by another until tick 40: waiting where it stands for the way down
  // would be quickest, but a kept-out agent does not wait in the band, even at its start. It
  // steps out upward (and, kept out of the band, waits there).
  for (int x = 0; x + 3 <= side; ++x)
    table.reserve({x, 6}, 3, 0, 40, 2);
  const CooperativePlan aside = search.plan(r, field, table);
  ASSERT_EQ(aside.status, CooperativeStatus::Windowed);
  expectLegal(grid, r, aside.steps);
  for (std::size_t i = 1; i < aside.steps.size(); ++i) {
    if (keptOutCells(aside.steps[i - 1].cell) > 0) {
      EXPECT_NE(aside.steps[i].cell, aside.steps[i - 1].cell) << "step " << i;
    }
  }
  EXPECT_EQ(aside.steps.back().cell, (Cell{4, 0}));

  // By the highest level alone no move out of the band is allowed, and the agent may wait
  // where it starts: it waits there, blocked.
  r.keepOutExit = KeepOutExit::HighestLevel;
  const CooperativePlan stuck = search.plan(r, field, table);
  EXPECT_EQ(stuck.status, CooperativeStatus::Blocked);
  for (const TimedCell& step : stuck.steps)
    EXPECT_EQ(step.cell, r.start);
}

TEST(CooperativeSearch, ContestedCellsAreThePassages) {
  const AnnotatedGrid grid(mapFromRows(
      "type octile\nheight 7\nwidth 7\nmap\n.......\n.......\n.......\n@@@.@@@\n.......\n"
      ".......\n.......\n"));
  const Agent agent{1, kGround};
  const std::vector<std::uint8_t> contested =
      contestedCells(grid, std::span<const Agent>(&agent, 1));
  EXPECT_EQ(contested[3 * 7 + 3], 1);  // the door
  EXPECT_EQ(contested[0], 0);          // open ground
}

// A notch in a wall's edge blocks nobody: traffic goes by just below it. A door does (its sides
// meet only through it), and so does a corridor longer than 2s + 1 (3 here) though open ground
// runs round it close by.
TEST(CooperativeSearch, DentsHavePassingRoomDoorsAndCorridorsDoNot) {
  const AnnotatedGrid grid(
      mapFromRows("type octile\nheight 13\nwidth 16\nmap\n"
                  "@@@@@@@@@@@@@@@@\n"
                  "@@@@@.@@@@@@@@@@\n"
                  "................\n"
                  "................\n"
                  "...@@@@@@@@@@...\n"
                  "................\n"
                  "...@@@@@@@@@@...\n"
                  "................\n"
                  "................\n"
                  "@@@@@@@.@@@@@@@@\n"
                  "................\n"
                  "................\n"
                  "................\n"));
  const Agent agent{1, kGround};
  const auto at = [](const std::vector<std::uint8_t>& cells, int x, int y) {
    return cells[static_cast<std::size_t>(y * 16 + x)];
  };
  const std::vector<std::uint8_t> open = passingRoom(grid, agent, Dents::Open);
  const std::vector<std::uint8_t> narrow = passingRoom(grid, agent, Dents::Narrow);
  EXPECT_EQ(at(narrow, 5, 1), 0);  // the notch: no 2x2 square holds it
  EXPECT_EQ(at(open, 5, 1), 1);    // ... but it is a dent
  for (int x = 3; x <= 12; ++x) {
    EXPECT_EQ(at(narrow, x, 5), 0) << x;
    EXPECT_EQ(at(open, x, 5), 0) << x;  // the corridor, 10 long
  }
  EXPECT_EQ(at(open, 7, 9), 0);  // the door
  EXPECT_EQ(at(narrow, 7, 9), 0);
  for (std::size_t i = 0; i < open.size(); ++i) {
    if (i != 1 * 16 + 5) {
      EXPECT_EQ(open[i], narrow[i]) << i;  // only the dent changed
    }
  }
  const std::vector<std::uint8_t> contested =
      contestedCells(grid, std::span<const Agent>(&agent, 1), Dents::Open);
  EXPECT_EQ(at(contested, 5, 1), 0);
  EXPECT_EQ(at(contested, 7, 5), 1);
  EXPECT_EQ(at(contested, 7, 9), 1);
  EXPECT_EQ(at(contestedCells(grid, std::span<const Agent>(&agent, 1), Dents::Narrow), 5, 1), 1);
}

// A size-2 agent between a small rock and a pond, 3 cells apart: it cannot pass another there,
// but others go round the rock close by; in a gap 3 cells wide in a wall across the map (open
// ground on both sides) it is a passage.
TEST(CooperativeSearch, AGapRoundASmallRockIsADentAndAGapInAWallIsNot) {
  const AnnotatedGrid grid(
      mapFromRows("type octile\nheight 16\nwidth 14\nmap\n"
                  "..............\n"
                  "..............\n"
                  "..............\n"
                  "..............\n"
                  "....@@...WWWWW\n"
                  "....@@...WWWWW\n"
                  "..............\n"
                  "..............\n"
                  "..............\n"
                  "..............\n"
                  "@@@@@@...@@@@@\n"
                  "..............\n"
                  "..............\n"
                  "..............\n"
                  "..............\n"
                  "..............\n"));
  const Agent agent{2, kGround};
  const std::vector<std::uint8_t> open = passingRoom(grid, agent, Dents::Open);
  const std::vector<std::uint8_t> narrow = passingRoom(grid, agent, Dents::Narrow);
  const auto at = [](const std::vector<std::uint8_t>& cells, int x, int y) {
    return cells[static_cast<std::size_t>(y * 14 + x)];
  };
  EXPECT_EQ(at(narrow, 6, 4), 0);  // between the rock and the pond
  EXPECT_EQ(at(open, 6, 4), 1);
  EXPECT_EQ(at(narrow, 6, 10), 0);  // the gap in the wall
  EXPECT_EQ(at(open, 6, 10), 0);
}

}  // namespace
}  // namespace warpath::pathing
