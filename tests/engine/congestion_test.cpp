// The queues of congestion-aware routes (engine/congestion.h): which cells make narrow places,
// the first-come-first-served wait, bookings replaced and cancelled, and the surcharge the
// abstract search gets.

#include "engine/congestion.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "pathing/cluster_abstraction.h"
#include "pathing/map_io.h"
#include "support/wall_with_gaps.h"

namespace warpath::engine {
namespace {

using pathing::Agent;
using pathing::Capability;
using pathing::Cell;
using pathing::Terrain;

const Capability kGround = Capability::of({Terrain::Ground});
const Agent kWalker{1, kGround};
constexpr double kSpeed = 1.5;  // [Unit: cells/s]

// A straight path along row `y` from column 2 to 45.
std::vector<Cell> along(int y) {
  std::vector<Cell> cells;
  for (int x = 2; x <= 45; ++x)
    cells.push_back({x, y});
  return cells;
}

UnitId unit(std::uint32_t index) {
  return UnitId{index, 0};
}

TEST(Congestion, AQueueFormsAtANarrowPlaceFirstComeFirstServed) {
  const pathing::AnnotatedGrid grid(testing::wallWithTwoGaps(48, 24, 22, 16));
  Congestion congestion(grid, 16);
  const std::vector<Cell> path = along(6);
  EXPECT_EQ(congestion.waitAlong(kWalker, kSpeed, path, 0.0), 0.0);
  EXPECT_EQ(congestion.queuesAt(0.0), 0u);
  // Ten units on the same path at once: each holds the 2-wide gap 1/3 s (two files of bodies
  // 3/4 cell wide, a cell apart at 1.5 cells/s), so the eleventh waits about 10/3 s there.
  for (std::uint32_t i = 0; i < 10; ++i)
    congestion.book(unit(i), kWalker, kSpeed, path, 0.0);
  EXPECT_EQ(congestion.queuesAt(0.0), 1u);
  const double wait = congestion.waitAlong(kWalker, kSpeed, path, 0.0);
  EXPECT_NEAR(wait, 10.0 / 3.0, 1e-9);
  // Arriving after the queue has gone: no wait.
  EXPECT_EQ(congestion.waitAlong(kWalker, kSpeed, path, 20.0), 0.0);
  // The other gap and open rows have no queue.
  EXPECT_EQ(congestion.waitAlong(kWalker, kSpeed, along(17), 0.0), 0.0);
  EXPECT_EQ(congestion.waitAlong(kWalker, kSpeed, along(1), 0.0), 0.0);
  // A unit's new path replaces its bookings; cancelled ones go.
  congestion.book(unit(0), kWalker, kSpeed, along(17), 0.0);
  EXPECT_NEAR(congestion.waitAlong(kWalker, kSpeed, path, 0.0), 9.0 / 3.0, 1e-9);
  // Alone at the 3-wide gap (four files): the next unit there waits its 1/6 s.
  EXPECT_NEAR(congestion.waitAlong(kWalker, kSpeed, along(17), 0.0), 1.0 / (kSpeed * 4), 1e-9);
  for (std::uint32_t i = 1; i < 10; ++i)
    congestion.cancel(unit(i));
  EXPECT_EQ(congestion.waitAlong(kWalker, kSpeed, path, 0.0), 0.0);
  // A change of terrain drops every booking.
  congestion.terrainChanged();
  EXPECT_EQ(congestion.queuesAt(0.0), 0u);
  EXPECT_EQ(congestion.waitAlong(kWalker, kSpeed, along(17), 0.0), 0.0);
}

TEST(Congestion, TheSurchargeIsTheWaitAtTheTimeTheSearchGetsThere) {
  const pathing::AnnotatedGrid grid(testing::wallWithTwoGaps(48, 24, 22, 16));
  const pathing::ClusterAbstraction graph = pathing::ClusterAbstraction::build(
      grid,
      pathing::AbstractionSpec{.clusterSize = 16, .maxAgentSize = 1, .capabilities = {kGround}});
  Congestion congestion(grid, 16);
  // 60 units reach the gap 20 cells on, at 13.3 s; its queue ends 20 s later.
  for (std::uint32_t i = 0; i < 60; ++i)
    congestion.book(unit(i), kWalker, kSpeed, along(6), 0.0);
  const Congestion::Surcharge cells(congestion, kWalker, kSpeed, 0.0, false);
  const Congestion::Surcharge seconds(congestion, kWalker, kSpeed, 0.0, true);
  // Every edge of the graph, reached 20 cells from the start (when the queue is there): those
  // that enter the narrow gap get its wait (in cells at the unit's speed, or in seconds), the
  // rest nothing; reached 6 cells later, 6 cells less. Reached at once, before the crowd,
  // nothing.
  int through = 0;
  for (std::uint32_t n = 0; n < graph.nodeCount(); ++n) {
    for (const pathing::AbstractEdge& e : graph.edgesOf(n)) {
      std::vector<Cell> walk{graph.nodeCell(n)};
      graph.appendEdgeCells(n, e, &walk);
      bool entersGap = false;
      for (std::size_t i = 1; i < walk.size(); ++i) {
        const auto inGap = [](Cell c) { return c.x >= 22 && c.x <= 25 && c.y <= 7; };
        entersGap = entersGap || (inGap(walk[i]) && !inGap(walk[i - 1]));
      }
      const double inCells = cells.on(graph, n, e, 20.0);
      const double inSeconds = seconds.on(graph, n, e, 20.0 / kSpeed);
      if (!entersGap) {
        EXPECT_EQ(inCells, 0.0);
        continue;
      }
      ++through;
      EXPECT_GT(inCells, 0.0);
      EXPECT_NEAR(inCells, inSeconds * kSpeed, 1e-9);
      EXPECT_NEAR(cells.on(graph, n, e, 26.0), inCells - 6.0, 1e-9);
      EXPECT_EQ(cells.on(graph, n, e, 0.0), 0.0);
    }
  }
  EXPECT_GT(through, 0);
}

}  // namespace
}  // namespace warpath::engine
