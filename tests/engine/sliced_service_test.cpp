// The path service with sliced searches (issue 15, `pathing: {sliced: true}`): a tick's requests
// never spend more than the budget (or one HAA* insertion, when the budget is smaller), the
// answers are those of the unsliced service in the same order, and a bundled scenario still
// reaches its arrivals.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/path_service.h"
#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "pathing/annotated_grid.h"
#include "pathing/map_generator.h"
#include "pathing/random.h"
#include "support/one_unit_scenario.h"
#include "support/scenario_files.h"
#include "support/serve_all.h"

namespace warpath::engine {
namespace {

using pathing::Algorithm;
using pathing::Cell;
using pathing::PathStatus;
using pathing::Terrain;

pathing::GridMap randomTerrain(std::uint64_t seed) {
  pathing::RandomMapSpec spec;
  spec.width = 96;
  spec.height = 80;
  spec.seed = seed;
  spec.blockedPercent = 15;
  spec.swampPercent = 15;
  spec.treesPercent = 10;
  spec.waterPercent = 10;
  spec.maxPatch = 5;
  return pathing::generateRandomMap(spec);
}

const std::vector<pathing::Agent> kAgents = {
    {1, pathing::Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees})},
    {2, pathing::Capability::of({Terrain::Ground})},
    {3, pathing::Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water})},
};

// Requests between random cells where each agent can stand (some unreachable), and repeats
// that the cache answers.
std::vector<PathRequest> requests(const pathing::AnnotatedGrid& grid, std::uint64_t seed) {
  pathing::SplitMix64 rng(seed);
  std::vector<PathRequest> out;
  for (std::uint32_t i = 0; i < 60; ++i) {
    const pathing::Agent agent = kAgents[i % kAgents.size()];
    const pathing::QuerySampler sampler(grid, agent);
    if (!sampler.canStandAnywhere()) continue;
    const pathing::Query q = i % 4 == 0 ? sampler.anyPair(rng) : sampler.reachablePair(rng);
    out.push_back({{i, 0}, 1, agent, q.start, q.goal});
    if (i % 10 == 0) out.push_back({{i + 100, 0}, 1, agent, q.start, q.goal});
  }
  return out;
}

TEST(SlicedPathService, TicksStayWithinTheBudgetAndAnswersAreTheUnslicedOnes) {
  const pathing::AnnotatedGrid grid(randomTerrain(3));
  std::vector<pathing::Capability> capabilities;
  for (const pathing::Agent& a : kAgents)
    capabilities.push_back(a.capability);
  for (const Algorithm algorithm :
       {Algorithm::AStar, Algorithm::Jps, Algorithm::HaaHigh, Algorithm::Hybrid}) {
    for (const std::uint64_t budget : {1u, 50u, 700u}) {
      SCOPED_TRACE(std::string(pathing::toString(algorithm)) + " budget " + std::to_string(budget));
      PathServiceSettings settings;
      settings.algorithm = algorithm;
      settings.clusterSize = 8;
      settings.expansionBudget = budget;
      PathService whole(grid, settings, capabilities, 3);
      settings.sliced = true;
      PathService sliced(grid, settings, capabilities, 3);
      for (const PathRequest& r : requests(grid, 11)) {
        whole.request(r);
        sliced.request(r);
      }
      const testing::Served expected = testing::serveAll(whole);
      const testing::Served got = testing::serveAll(sliced);
      ASSERT_EQ(got.deliveries.size(), expected.deliveries.size());
      for (std::size_t i = 0; i < got.deliveries.size(); ++i) {
        const PathDelivery& a = got.deliveries[i];
        const PathDelivery& b = expected.deliveries[i];
        EXPECT_EQ(a.unit, b.unit) << i;
        EXPECT_EQ(a.status, b.status) << i;
        ASSERT_EQ(a.path != nullptr, b.path != nullptr) << i;
        if (a.path) {
          EXPECT_EQ(a.path->digest, b.path->digest) << i;
        }
      }
      EXPECT_EQ(sliced.metrics().expanded, whole.metrics().expanded);
      EXPECT_EQ(sliced.metrics().searches, whole.metrics().searches);
      // A tick overruns its budget only when the budget is smaller than one insertion (one
      // cluster's cells, taken whole when nothing else was spent that tick).
      const bool hierarchical = algorithm != Algorithm::AStar && algorithm != Algorithm::Jps;
      const std::uint64_t limit = hierarchical ? std::max<std::uint64_t>(budget, 8u * 8u) : budget;
      for (std::size_t t = 0; t < got.spentPerTick.size(); ++t)
        ASSERT_LE(got.spentPerTick[t], limit) << "tick " << t;
      EXPECT_LE(sliced.metrics().maxTickExpanded, limit);
      EXPECT_GT(sliced.metrics().slices, 0u);
      // Unsliced, the request that crosses the budget runs to its end.
      EXPECT_GT(whole.metrics().maxTickExpanded, limit);
    }
  }
}

// A search under way is dropped with its unit, and begun again after a change of terrain (its
// answer is then the one on the changed map).
TEST(SlicedPathService, CancelAndTerrainChangesAbandonTheSearchUnderWay) {
  pathing::AnnotatedGrid grid(randomTerrain(5));
  const pathing::Agent infantry = kAgents[0];
  PathServiceSettings settings;
  settings.algorithm = Algorithm::Hybrid;
  settings.clusterSize = 8;
  settings.expansionBudget = 5;
  settings.sliced = true;
  PathService service(grid, settings, {infantry.capability}, 1);
  const pathing::QuerySampler sampler(grid, infantry);
  pathing::SplitMix64 rng(2);
  const pathing::Query far = sampler.reachablePair(rng);
  const pathing::Query other = sampler.reachablePair(rng);

  std::vector<PathDelivery> out;
  service.request({{0, 0}, 1, infantry, far.start, far.goal});
  service.request({{1, 0}, 1, infantry, other.start, other.goal});
  service.serve(out);
  ASSERT_TRUE(out.empty());
  ASSERT_GT(service.slicedExpanded(), 0u);
  service.cancel({0, 0});
  EXPECT_EQ(service.slicedExpanded(), 0u);
  const testing::Served rest = testing::serveAll(service);
  ASSERT_EQ(rest.deliveries.size(), 1u);
  EXPECT_EQ(rest.deliveries[0].unit, (UnitId{1, 0}));

  // Halfway through a search the map changes: it starts over on the changed map.
  service.request({{2, 0}, 1, infantry, far.start, far.goal});
  service.serve(out);
  ASSERT_GT(service.slicedExpanded(), 0u);
  const pathing::TerrainChange change = grid.setTerrain({0, 0, 4, 4}, Terrain::Blocked);
  service.changeTerrain(change);
  EXPECT_EQ(service.slicedExpanded(), 0u);
  const testing::Served after = testing::serveAll(service);
  ASSERT_EQ(after.deliveries.size(), 1u);
  PathServiceSettings fresh = settings;
  fresh.sliced = false;
  PathService reference(grid, fresh, {infantry.capability}, 1);
  reference.request({{2, 0}, 1, infantry, far.start, far.goal});
  const testing::Served expected = testing::serveAll(reference);
  ASSERT_EQ(expected.deliveries.size(), 1u);
  EXPECT_EQ(after.deliveries[0].status, expected.deliveries[0].status);
  ASSERT_EQ(after.deliveries[0].path != nullptr, expected.deliveries[0].path != nullptr);
  if (after.deliveries[0].path) {
    EXPECT_EQ(after.deliveries[0].path->digest, expected.deliveries[0].path->digest);
  }
}

Report runToEnd(const Scenario& s) {
  ScenarioRun r(s);
  while (!r.done())
    r.step();
  return r.report();
}

// A bundled scenario with a budget small enough that searches span ticks: no tick spends more
// than the budget and one batch of window searches, every expectation still holds and
// every group has as many arrivals as the scenario as bundled (whose budget no tick reaches);
// the run is deterministic. (Unsliced with the small budget, timings shift and one tank of the
// demo fails to arrive in time, so that run is not the reference.)
TEST(SlicedPathService, ABundledScenarioReachesTheSameArrivals) {
  Scenario s = testing::bundledScenario("demo");
  ASSERT_FALSE(s.settings.pathing.sliced);
  const Report bundled = runToEnd(s);
  s.settings.pathing.expansionBudget = 400;
  const Report unsliced = runToEnd(s);
  s.settings.pathing.sliced = true;
  const Report sliced = runToEnd(s);
  const int cluster = s.settings.pathing.clusterSize;
  EXPECT_GT(unsliced.pathing.maxTickExpanded, s.settings.pathing.expansionBudget);
  // The budget holds a whole insertion, so no tick's searches spend more than the budget, and
  // the windows at most one batch more (when the spatial searches left less).
  ASSERT_GE(s.settings.pathing.expansionBudget, static_cast<std::uint64_t>(cluster * cluster));
  EXPECT_LE(sliced.pathing.maxTickExpanded, s.settings.pathing.expansionBudget + kWindowBatch);
  EXPECT_GT(sliced.pathing.slices, 0u);
  EXPECT_TRUE(sliced.passed());
  ASSERT_EQ(sliced.arrivals.size(), bundled.arrivals.size());
  for (std::size_t i = 0; i < sliced.arrivals.size(); ++i) {
    EXPECT_EQ(sliced.arrivals[i].units, bundled.arrivals[i].units) << i;
    EXPECT_EQ(sliced.arrivals[i].arrived, bundled.arrivals[i].arrived) << i;
  }
  const Report again = runToEnd(s);
  EXPECT_EQ(again.stateHash, sliced.stateHash);
  EXPECT_EQ(again, sliced);
}

// The window searches share the tick's budget (replay format 9): at the door (60 infantry) and
// in the 4-wide corridor (two tanks head on) with a budget of 300, far below what a window
// search takes there, searches pause and resume, no tick spends more than the budget and one
// batch, every unit arrives as the scenario expects, and the run is deterministic.
TEST(SlicedPathService, WindowSearchesPauseAtTheBudgetAtChokepoints) {
  for (const std::string name : {"chokepoints/door_30v30", "chokepoints/corridor_tanks_4"}) {
    Scenario s = testing::bundledScenario(name);
    ASSERT_TRUE(s.settings.pathing.cooperative && s.settings.pathing.slicedWindows) << name;
    s.settings.pathing.sliced = true;
    s.settings.pathing.expansionBudget = 300;
    const Report sliced = runToEnd(s);
    EXPECT_GT(sliced.pathing.windowSlices, 10u) << name;
    EXPECT_LE(sliced.pathing.maxTickExpanded, s.settings.pathing.expansionBudget + kWindowBatch)
        << name;
    EXPECT_TRUE(sliced.passed()) << name;
    for (const ArrivalStats& a : sliced.arrivals)
      EXPECT_EQ(a.arrived, a.units) << name;
    const Report again = runToEnd(s);
    EXPECT_EQ(again.stateHash, sliced.stateHash) << name;
    EXPECT_EQ(again, sliced) << name;
    // Run whole, the same windows overrun the budget by far.
    s.settings.pathing.sliced = false;
    EXPECT_GT(runToEnd(s).pathing.maxTickExpanded,
              s.settings.pathing.expansionBudget + kWindowBatch)
        << name;
  }
}

// The scenario key: `pathing: {sliced: true}`, default false.
TEST(SlicedPathService, TheScenarioKeyParses) {
  Result<Scenario> off = testing::parseOneUnitScenario("");
  ASSERT_TRUE(off.ok()) << off.error().describe();
  EXPECT_FALSE(off.value().settings.pathing.sliced);
  Result<Scenario> on = testing::parseOneUnitScenario("pathing: {sliced: true}\n");
  ASSERT_TRUE(on.ok()) << on.error().describe();
  EXPECT_TRUE(on.value().settings.pathing.sliced);
  EXPECT_FALSE(testing::parseOneUnitScenario("pathing: {sliced: 3}\n").ok());
}

}  // namespace
}  // namespace warpath::engine
