// Sliced cooperative plans (pathing/cooperative_search.h: beginPlan / updatePlan /
// finalizePlan): a plan advanced in slices of any size is the one-shot plan, bit for bit, with
// both distance fields, and no slice spends more than it was given; finalizePlanAt shifts a
// finished plan to a later start and drops it when the table changed under it.

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cooperative_request.h"
#include "pathing/aa_star.h"
#include "pathing/cooperative_search.h"
#include "pathing/inline_maps.h"
#include "pathing/map_io.h"
#include "random_grid.h"

namespace warpath::pathing {
namespace {

// Moves from rest take 3 ticks longer.
CooperativeRequest requestFrom(Agent agent, Cell start, Cell goal, Tick window) {
  CooperativeRequest r = requestFor(agent, start, goal, window);
  r.startTicks = 3;
  return r;
}

Cell standable(const AnnotatedGrid& grid, Agent agent, std::mt19937& rng) {
  std::uniform_int_distribution<int> x(0, grid.map().width() - 1);
  std::uniform_int_distribution<int> y(0, grid.map().height() - 1);
  for (;;) {
    const Cell c{x(rng), y(rng)};
    if (grid.canStand(agent, c)) return c;
  }
}

// The two heuristics: CPRA*'s corridor around the AA* path, and WHCA*'s RRA*.
std::unique_ptr<DistanceField> makeField(bool corridor, const AnnotatedGrid& grid, Agent agent,
                                         const std::vector<Cell>& path) {
  if (corridor) return std::make_unique<CorridorDistance>(grid, agent, path, 2);
  return std::make_unique<ReverseResumableSearch>(grid, agent, path.back(), path.front());
}

// Other agents' windows, planned one after another and reserved (owners from 2 on): a table
// full of reservations to plan around.
void fillTable(const AnnotatedGrid& grid, ReservationTable& table, std::mt19937& rng, int agents) {
  AnnotatedAStar astar(grid);
  CooperativeSearch search(grid);
  for (int i = 0; i < agents; ++i) {
    const Agent agent{1 + i % 2, kGround};
    const Cell start = standable(grid, agent, rng);
    const Cell goal = standable(grid, agent, rng);
    std::vector<Cell> path;
    if (!astar.findPath(agent, start, goal, &path).found()) continue;
    CooperativeRequest r = requestFrom(agent, start, goal, 80);
    r.self = static_cast<std::uint32_t>(i + 2);
    r.startTick = std::uniform_int_distribution<Tick>(0, 30)(rng);
    ReverseResumableSearch field(grid, agent, goal, start);
    const CooperativePlan plan = search.plan(r, field, table);
    if (plan.steps.empty()) continue;
    CooperativeSearch::reserve(
        table, plan.steps, agent.size, r.self,
        plan.status == CooperativeStatus::ReachedGoal ? kForever : r.holdTicks);
  }
}

struct Sliced {
  CooperativePlan plan;
  int updates = 0;
};

// Begin, updates of `slice` expansions until done (each checked to spend at most `slice`),
// finalize.
Sliced planSliced(CooperativeSearch& search, const CooperativeRequest& r, DistanceField& field,
                  const ReservationTable& table, std::uint64_t slice) {
  Sliced out;
  CooperativeStatus status = search.beginPlan(r, field, table);
  while (status == CooperativeStatus::Pending) {
    EXPECT_EQ(search.finalizePlan().status, CooperativeStatus::Pending);
    const std::uint64_t before = search.expandedSoFar();
    status = search.updatePlan(slice);
    EXPECT_LE(search.expandedSoFar() - before, slice);
    if (status == CooperativeStatus::Pending) {
      EXPECT_EQ(search.expandedSoFar() - before, slice);
    }
    ++out.updates;
  }
  out.plan = search.finalizePlan();
  return out;
}

void expectSamePlan(const CooperativePlan& sliced, const CooperativePlan& whole,
                    const std::string& what) {
  EXPECT_EQ(sliced.status, whole.status) << what;
  EXPECT_EQ(sliced.steps, whole.steps) << what;
  EXPECT_EQ(sliced.metrics.expanded, whole.metrics.expanded) << what;
  EXPECT_EQ(sliced.metrics.generated, whole.metrics.generated) << what;
  EXPECT_EQ(sliced.fieldExpanded, whole.fieldExpanded) << what;
}

TEST(SlicedCooperativeSearch, SlicesPlanWhatOneShotPlans) {
  int compared = 0;
  int paused = 0;
  std::set<CooperativeStatus> statuses;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const AnnotatedGrid grid = randomGrid(48, 36, seed, 18);
    ReservationTable table(grid.map().width(), grid.map().height());
    std::mt19937 rng(static_cast<std::uint32_t>(seed));
    fillTable(grid, table, rng, 30);
    const std::vector<std::uint8_t> room1 = passingRoom(grid, {1, kGround});
    AnnotatedAStar astar(grid);
    CooperativeSearch oneShot(grid);
    CooperativeSearch slicedSearch(grid);
    for (int query = 0; query < 6; ++query) {
      const Agent agent{1 + query % 3, kGround};
      const Cell start = standable(grid, agent, rng);
      const Cell goal = standable(grid, agent, rng);
      std::vector<Cell> path;
      if (!astar.findPath(agent, start, goal, &path).found()) continue;
      // Short and long windows, a tight expansion limit (Blocked), passing room for infantry.
      CooperativeRequest r = requestFrom(agent, start, goal, query % 2 == 0 ? 60 : 600);
      r.startTick = 10;
      r.startsAtRest = query % 2 == 1;
      if (query == 4) r.expansionLimit = 40;
      if (agent.size == 1) r.passing = &room1;
      for (const bool corridor : {true, false}) {
        const std::unique_ptr<DistanceField> reference = makeField(corridor, grid, agent, path);
        const CooperativePlan whole = oneShot.plan(r, *reference, table);
        statuses.insert(whole.status);
        EXPECT_GT(whole.fieldExpanded, 0u);
        EXPECT_EQ(whole.fieldExpanded, reference->expanded());
        for (const std::uint64_t slice : {1u, 7u, 100u}) {
          const std::unique_ptr<DistanceField> field = makeField(corridor, grid, agent, path);
          const Sliced s = planSliced(slicedSearch, r, *field, table, slice);
          const std::string what = "seed " + std::to_string(seed) + " query " +
                                   std::to_string(query) + (corridor ? " corridor" : " rra") +
                                   " slice " + std::to_string(slice);
          expectSamePlan(s.plan, whole, what);
          EXPECT_EQ(field->expanded(), reference->expanded()) << what;
          paused += s.updates - 1;
          ++compared;
        }
      }
    }
  }
  EXPECT_GE(compared, 100);
  EXPECT_GT(paused, 1000);  // the slices did cut the plans
  // Plans to the goal, to the window's end and blocked ones were all compared.
  EXPECT_TRUE(statuses.count(CooperativeStatus::ReachedGoal));
  EXPECT_TRUE(statuses.count(CooperativeStatus::Windowed));
  EXPECT_TRUE(statuses.count(CooperativeStatus::Blocked));
}

TEST(SlicedCooperativeSearch, AnswersWithoutSearchingAtBegin) {
  const AnnotatedGrid grid = randomGrid(20, 20, 3, 0);
  ReservationTable table(20, 20);
  CooperativeSearch search(grid);
  const Agent agent{1, kGround};
  const std::vector<Cell> path{{0, 0}, {1, 1}};
  ReverseResumableSearch field(grid, agent, {1, 1}, {0, 0});
  CooperativeRequest r = requestFor(agent, {0, 0}, {1, 1}, 60);
  r.waitTicks = 0;  // a broken request
  EXPECT_EQ(search.beginPlan(r, field, table), CooperativeStatus::InvalidStart);
  EXPECT_EQ(search.updatePlan(5), CooperativeStatus::InvalidStart);
  EXPECT_TRUE(search.finalizePlan().steps.empty());
  r = requestFor(agent, {0, 0}, {1, 1}, 60);
  EXPECT_EQ(search.beginPlan(r, field, table), CooperativeStatus::Pending);
  EXPECT_EQ(search.expandedSoFar(), 0u);  // nothing searched yet
}

std::vector<Cell> row(int y, int x0, int x1) {
  std::vector<Cell> cells;
  for (int x = x0; x <= x1; ++x)
    cells.push_back({x, y});
  return cells;
}

GridMap openStrip() {
  std::string text = "type octile\nheight 5\nwidth 16\nmap\n";
  for (int y = 0; y < 5; ++y)
    text += std::string(16, '.') + "\n";
  std::istringstream rows(text);
  auto map = parseMap(rows, "inline");
  EXPECT_TRUE(map) << map.error().describe();
  return map.value();
}

// A plan on an open strip 5 cells tall: {0, 2} to {12, 2}, reaching its goal.
struct Strip {
  AnnotatedGrid grid{openStrip()};
  ReservationTable table{16, 5};
  CooperativeSearch search{grid};
  Agent agent{1, kGround};
  CooperativeRequest request = requestFrom(agent, {0, 2}, {12, 2}, 400);
  std::vector<Cell> path = row(2, 0, 12);
  CorridorDistance field{grid, agent, path, 2};
};

TEST(SlicedCooperativeSearch, AFinishedPlanBegunLaterIsShiftedFromRest) {
  Strip s;
  s.search.beginPlan(s.request, s.field, s.table);
  ASSERT_EQ(s.search.updatePlan(kUnboundedExpansions), CooperativeStatus::ReachedGoal);
  const CooperativePlan now = s.search.finalizePlan();
  ASSERT_GT(now.steps.size(), 2u);
  EXPECT_EQ(s.search.finalizePlanAt(s.request.startTick).steps, now.steps);
  // Planned at speed: the first move, now from rest, takes startTicks longer.
  const CooperativePlan later = s.search.finalizePlanAt(s.request.startTick + 7);
  EXPECT_EQ(later.status, CooperativeStatus::ReachedGoal);
  ASSERT_EQ(later.steps.size(), now.steps.size());
  EXPECT_EQ(later.steps[0].tick, now.steps[0].tick + 7);
  for (std::size_t i = 1; i < now.steps.size(); ++i) {
    EXPECT_EQ(later.steps[i].cell, now.steps[i].cell);
    EXPECT_EQ(later.steps[i].tick, now.steps[i].tick + 7 + s.request.startTicks) << i;
  }
  // Planned from rest: only shifted.
  s.request.startsAtRest = true;
  s.search.beginPlan(s.request, s.field, s.table);
  s.search.updatePlan(kUnboundedExpansions);
  const CooperativePlan rest = s.search.finalizePlan();
  const CooperativePlan restLater = s.search.finalizePlanAt(s.request.startTick + 7);
  ASSERT_EQ(restLater.steps.size(), rest.steps.size());
  for (std::size_t i = 0; i < rest.steps.size(); ++i)
    EXPECT_EQ(restLater.steps[i].tick, rest.steps[i].tick + 7) << i;
}

TEST(SlicedCooperativeSearch, APlanTheTableNoLongerAllowsIsDropped) {
  Strip s;
  ASSERT_TRUE(s.grid.canStand(s.agent, {15, 4}));  // no obstacles
  s.search.beginPlan(s.request, s.field, s.table);
  s.search.updatePlan(80);  // paused, the corridor's distances known
  ASSERT_EQ(s.search.finalizePlan().status, CooperativeStatus::Pending);
  // Meanwhile a column across the strip is reserved until tick 150: the resumed search reads
  // the table as it is now. The agent's own reservations do not count.
  s.table.reserve({9, 0}, 5, 0, 150, 5);
  s.table.reserve({0, 2}, 1, 0, kForever, s.request.self);
  ASSERT_EQ(s.search.updatePlan(kUnboundedExpansions), CooperativeStatus::ReachedGoal);
  const CooperativePlan now = s.search.finalizePlan();
  EXPECT_GT(now.steps.back().tick, 150);
  const Tick delay = 4;
  EXPECT_EQ(s.search.finalizePlanAt(s.request.startTick + delay).status,
            CooperativeStatus::ReachedGoal);
  // Someone stops where the plan, begun later, would pass: the plan is dropped, the agent
  // stands at its start.
  std::size_t move = 1;
  while (now.steps[move].cell == now.steps[move - 1].cell)
    ++move;
  const TimedCell& at = now.steps[move];
  const Tick when = at.tick + delay + s.request.startTicks;
  s.table.reserve(at.cell, 1, when - 1, when + 1, 7);
  const CooperativePlan dropped = s.search.finalizePlanAt(s.request.startTick + delay);
  EXPECT_EQ(dropped.status, CooperativeStatus::Blocked);
  ASSERT_EQ(dropped.steps.size(), 1u);
  EXPECT_EQ(dropped.steps[0], (TimedCell{s.request.start, s.request.startTick + delay}));
  // Gone again: the plan stands.
  s.table.release(7);
  EXPECT_EQ(s.search.finalizePlanAt(s.request.startTick + delay).status,
            CooperativeStatus::ReachedGoal);
  // The goal, held for good once the agent gets there, is checked too.
  s.table.reserve({12, 2}, 1, 5000, 5001, 7);
  EXPECT_EQ(s.search.finalizePlanAt(s.request.startTick + delay).status,
            CooperativeStatus::Blocked);
}

}  // namespace
}  // namespace warpath::pathing
