// Sliced searches (issue 15): a query advanced a few expansions at a time returns exactly what
// the one-shot call returns (status, cells, cost bit for bit, expansion counts), for every
// algorithm, agent sizes 1-3 and the catalogue's capabilities, on random multi-terrain maps.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/haa_star.h"
#include "pathing/jump_point_search.h"
#include "pathing/planner.h"
#include "pathing/terrain_costs.h"
#include "random_grid.h"
#include "support/completeness.h"

namespace warpath::pathing {
namespace {

using testing::completenessAgents;
using testing::completenessCapabilities;
using testing::CompletenessCase;
using testing::describeQuery;
using testing::drawCompletenessCases;

constexpr std::uint64_t kBatches[] = {1, 7, 100};

struct Answer {
  PathResult result;
  std::vector<Cell> path;
};

// What a sliced run saw besides its answer.
struct SlicedAnswer {
  Answer answer;
  int pendingUpdates = 0;                // updatePath calls that returned Pending
  std::uint64_t mostInOneUpdate = 0;     // the most expansions one updatePath spent
  std::uint64_t expandedSoFarAtEnd = 0;  // expandedSoFar() once done
  bool beginPending = false;
};

// Runs a begun query to its end `batch` expansions at a time.
template <class Search>
SlicedAnswer finishSliced(Search& search, PathStatus begun, std::uint64_t batch) {
  SlicedAnswer out;
  out.beginPending = begun == PathStatus::Pending;
  for (PathStatus status = begun; status == PathStatus::Pending;) {
    const std::uint64_t before = search.expandedSoFar();
    status = search.updatePath(batch);
    out.mostInOneUpdate = std::max(out.mostInOneUpdate, search.expandedSoFar() - before);
    if (status == PathStatus::Pending) ++out.pendingUpdates;
  }
  out.expandedSoFarAtEnd = search.expandedSoFar();
  out.answer.path.push_back({-1, -1});  // finalizePath must replace what the vector held
  out.answer.result = search.finalizePath(&out.answer.path);
  return out;
}

// Empty when the two answers are the same bit for bit (wall time aside), else what differs.
std::string difference(const Answer& sliced, const Answer& whole) {
  const SearchMetrics& a = sliced.result.metrics;
  const SearchMetrics& b = whole.result.metrics;
  if (sliced.result.status != whole.result.status)
    return std::string("status ") + std::string(toString(sliced.result.status)) + " vs " +
           std::string(toString(whole.result.status));
  if (std::bit_cast<std::uint64_t>(sliced.result.cost) !=
      std::bit_cast<std::uint64_t>(whole.result.cost))
    return "cost " + std::to_string(sliced.result.cost) + " vs " +
           std::to_string(whole.result.cost);
  if (a.expanded != b.expanded || a.generated != b.generated ||
      a.insertionExpanded != b.insertionExpanded || a.abstractExpanded != b.abstractExpanded ||
      a.refinementExpanded != b.refinementExpanded || a.gridExpanded != b.gridExpanded ||
      a.usedGridSearch != b.usedGridSearch)
    return "metrics: expanded " + std::to_string(a.expanded) + " vs " + std::to_string(b.expanded) +
           ", generated " + std::to_string(a.generated) + " vs " + std::to_string(b.generated);
  if (sliced.path != whole.path)
    return "paths differ (" + std::to_string(sliced.path.size()) + " vs " +
           std::to_string(whole.path.size()) + " cells)";
  return {};
}

// A planner under test: one query object for one-shot calls, another for sliced runs (so that
// neither's scratch helps the other), and the most one updatePath may spend when its batch is
// smaller (an HAA* insertion: a cluster's cells).
struct Subject {
  std::string name;
  std::function<Answer(Agent, Cell, Cell)> whole;
  std::function<SlicedAnswer(Agent, Cell, Cell, std::uint64_t)> sliced;
  std::uint64_t overrun = 0;
};

template <class Search, class Begin>
Subject subject(std::string name, std::shared_ptr<Search> whole, std::shared_ptr<Search> sliced,
                Begin begin, std::uint64_t overrun = 0) {
  Subject s;
  s.name = std::move(name);
  s.overrun = overrun;
  s.whole = [whole](Agent agent, Cell start, Cell goal) {
    Answer a;
    a.result = whole->findPath(agent, start, goal, &a.path);
    return a;
  };
  s.sliced = [sliced, begin](Agent agent, Cell start, Cell goal, std::uint64_t batch) {
    return finishSliced(*sliced, begin(*sliced, agent, start, goal), batch);
  };
  return s;
}

// Checks every subject on every case and batch size; returns how many sliced runs were
// checked and how many of them returned Pending at least once.
void expectSlicedEqualsWhole(const std::vector<Subject>& subjects,
                             const std::vector<CompletenessCase>& cases, const std::string& where,
                             int& runs, int& pendingRuns) {
  for (const Subject& s : subjects) {
    for (const CompletenessCase& c : cases) {
      const Answer whole = s.whole(c.agent, c.query.start, c.query.goal);
      for (const std::uint64_t batch : kBatches) {
        const SlicedAnswer sliced = s.sliced(c.agent, c.query.start, c.query.goal, batch);
        const std::string what = where + " " + s.name + " batch " + std::to_string(batch) + " " +
                                 describeQuery(c.agent, c.query.start, c.query.goal);
        ASSERT_EQ(difference(sliced.answer, whole), "") << what;
        // An update overruns its batch only by an insertion taken whole as its first step.
        EXPECT_LE(sliced.mostInOneUpdate, std::max(batch, s.overrun)) << what;
        EXPECT_EQ(sliced.expandedSoFarAtEnd, whole.result.metrics.expanded) << what;
        // Timed either way: a whole query once, a sliced one phase by phase (PhaseTiming), and
        // a planner's inner searches as parts of its own.
        if (whole.result.status == PathStatus::Found && whole.result.metrics.expanded > 0) {
          EXPECT_GT(whole.result.metrics.microseconds, 0.0) << what;
          EXPECT_GT(sliced.answer.result.metrics.microseconds, 0.0) << what;
        }
        // Pending exactly while unfinished: a query that needs more expansions than one
        // batch gives is Pending after the first update.
        if (whole.result.metrics.expanded > batch + s.overrun) {
          EXPECT_TRUE(sliced.beginPending) << what;
          EXPECT_GE(sliced.pendingUpdates, 1) << what;
        }
        ++runs;
        if (sliced.pendingUpdates > 0) ++pendingRuns;
      }
    }
  }
}

template <class Search>
auto beginUniform() {
  return [](Search& search, Agent agent, Cell start, Cell goal) {
    return search.beginPath(agent, start, goal);
  };
}

// A toll on the edges between clusters (congestion at the borders): constant per edge, so the
// abstract search stays exact for it.
class BorderToll : public EdgeSurcharge {
 public:
  double on(const ClusterAbstraction&, std::uint32_t, const AbstractEdge& edge,
            double) const override {
    return edge.intra ? 0.0 : 2.5;
  }
};

AbstractionSpec spec(int clusterSize, AbstractionQuality quality, bool cachePaths) {
  return AbstractionSpec{.clusterSize = clusterSize,
                         .maxAgentSize = 3,
                         .capabilities = completenessCapabilities(),
                         .quality = quality,
                         .cachePaths = cachePaths};
}

// Every algorithm, through its own class and through the Planner, with cached paths and
// without (refinement by sliced AA*), HQ and LQ graphs and two hybrid budgets.
TEST(SlicedSearch, EveryAlgorithmSlicedReturnsExactlyWhatTheUnslicedReturns) {
  int runs = 0;
  int pendingRuns = 0;
  for (int i = 0; i < 4; ++i) {
    const std::uint64_t seed = 301 + static_cast<std::uint64_t>(i);
    const AnnotatedGrid grid(randomTerrainMap(seed, 57 + 6 * i, 63 - 4 * i, 1 + 3 * i, 12 + 4 * i));
    const int clusterSize = i % 2 == 0 ? 8 : 10;
    const auto high = std::make_shared<ClusterAbstraction>(ClusterAbstraction::build(
        grid, spec(clusterSize, AbstractionQuality::High, /*cachePaths=*/i != 1)));
    const auto low = std::make_shared<ClusterAbstraction>(
        ClusterAbstraction::build(grid, spec(clusterSize, AbstractionQuality::Low, i != 2)));
    // Agents larger than the graphs serve go to AA* on the grid (HAA*'s GridOnly phase).
    const auto small = std::make_shared<ClusterAbstraction>(ClusterAbstraction::build(
        grid, AbstractionSpec{.clusterSize = clusterSize,
                              .maxAgentSize = 1,
                              .capabilities = completenessCapabilities()}));
    // A whole insertion is one step of a slice: up to a cluster's cells.
    const auto insertion = static_cast<std::uint64_t>(clusterSize * clusterSize);

    std::vector<Subject> subjects;
    subjects.push_back(subject("aa", std::make_shared<AnnotatedAStar>(grid),
                               std::make_shared<AnnotatedAStar>(grid),
                               beginUniform<AnnotatedAStar>()));
    subjects.push_back(subject("jps", std::make_shared<JumpPointSearch>(grid),
                               std::make_shared<JumpPointSearch>(grid),
                               beginUniform<JumpPointSearch>()));
    for (const auto& [name, graph] :
         {std::pair{"haa-hq", high}, std::pair{"haa-lq", low}, std::pair{"haa-size1", small}}) {
      subjects.push_back(subject(name, std::make_shared<HierarchicalAStar>(*graph),
                                 std::make_shared<HierarchicalAStar>(*graph),
                                 beginUniform<HierarchicalAStar>(), insertion));
    }
    // With a surcharge on abstract edges, through HAA* and the Planner's hybrid.
    const auto toll = std::make_shared<BorderToll>();
    subjects.push_back(subject(
        "haa-hq-toll", std::make_shared<HierarchicalAStar>(*high),
        std::make_shared<HierarchicalAStar>(*high),
        [toll](HierarchicalAStar& search, Agent agent, Cell start, Cell goal) {
          return search.beginPath(agent, start, goal, toll.get());
        },
        insertion));
    const auto wholeToll = std::make_shared<HierarchicalAStar>(*high);
    subjects.back().whole = [wholeToll, toll](Agent agent, Cell start, Cell goal) {
      Answer answer;
      answer.result = wholeToll->findPath(agent, start, goal, &answer.path, toll.get());
      return answer;
    };
    subjects.push_back(subject(
        "planner-hybrid-toll",
        std::make_shared<Planner>(grid, Algorithm::Hybrid, high.get(), HybridOptions{64}),
        std::make_shared<Planner>(grid, Algorithm::Hybrid, high.get(), HybridOptions{64}),
        [toll](Planner& search, Agent agent, Cell start, Cell goal) {
          return search.beginPath(agent, start, goal, toll.get());
        },
        insertion));
    const auto wholeHybrid =
        std::make_shared<Planner>(grid, Algorithm::Hybrid, high.get(), HybridOptions{64});
    subjects.back().whole = [wholeHybrid, toll](Agent agent, Cell start, Cell goal) {
      Answer answer;
      answer.result = wholeHybrid->findPath(agent, start, goal, &answer.path, toll.get());
      return answer;
    };
    for (const std::uint64_t tau : {64u, 4096u}) {
      subjects.push_back(subject("hybrid-" + std::to_string(tau),
                                 std::make_shared<HybridPlanner>(*high, HybridOptions{tau}),
                                 std::make_shared<HybridPlanner>(*high, HybridOptions{tau}),
                                 beginUniform<HybridPlanner>(), insertion));
      // The JPS+ attempt: tau 4 runs out on most queries, so HAA* takes over mid-slice.
      const HybridOptions jumps{tau == 64u ? 4u : tau, HybridAttempt::JumpPoints};
      subjects.push_back(subject(
          "hybrid-jps+-" + std::to_string(jumps.tau), std::make_shared<HybridPlanner>(*high, jumps),
          std::make_shared<HybridPlanner>(*high, jumps), beginUniform<HybridPlanner>(), insertion));
    }
    for (const Algorithm algorithm : {Algorithm::AStar, Algorithm::Jps, Algorithm::HaaHigh,
                                      Algorithm::HaaLow, Algorithm::Hybrid}) {
      const ClusterAbstraction* graph = algorithm == Algorithm::HaaLow ? low.get() : high.get();
      subjects.push_back(subject(std::string("planner-") + std::string(toString(algorithm)),
                                 std::make_shared<Planner>(grid, algorithm, graph),
                                 std::make_shared<Planner>(grid, algorithm, graph),
                                 beginUniform<Planner>(), insertion));
    }
    const std::vector<CompletenessCase> cases =
        drawCompletenessCases(grid, completenessAgents(3), seed * 7, 2, 3, 1);
    expectSlicedEqualsWhole(subjects, cases, "map " + std::to_string(i), runs, pendingRuns);
    if (::testing::Test::HasFatalFailure()) return;
  }
  // Many queries are invalid or answered at once, and a batch of 100 finishes many others; a
  // good share of the runs were still cut into slices.
  EXPECT_GT(pendingRuns, runs / 3);
}

// Terrain costs: AA* under a cost field and HAA* on a weighted graph, sliced.
TEST(SlicedSearch, UnderTerrainCostsSlicedReturnsExactlyWhatTheUnslicedReturns) {
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  int runs = 0;
  int pendingRuns = 0;
  for (int i = 0; i < 3; ++i) {
    const std::uint64_t seed = 401 + static_cast<std::uint64_t>(i);
    const AnnotatedGrid grid(randomTerrainMap(seed, 61, 55, 2 + 3 * i, 10 + 5 * i));
    for (int size = 1; size <= 3; ++size) {
      const Agent agent{size, Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees})};
      const auto field = std::make_shared<CostField>(grid, agent, costs);
      const auto graph = std::make_shared<ClusterAbstraction>(ClusterAbstraction::build(
          grid, weightedAbstractionSpec(agent, costs, 8, AbstractionQuality::High)));
      std::vector<Subject> subjects;
      subjects.push_back(subject("aa-costs", std::make_shared<AnnotatedAStar>(grid),
                                 std::make_shared<AnnotatedAStar>(grid),
                                 [field](AnnotatedAStar& search, Agent a, Cell start, Cell goal) {
                                   return search.beginPath(a, start, goal, *field);
                                 }));
      // The one-shot side under the same costs.
      const auto wholeAStar = std::make_shared<AnnotatedAStar>(grid);
      subjects.back().whole = [wholeAStar, field](Agent a, Cell start, Cell goal) {
        Answer answer;
        answer.result = wholeAStar->findPath(a, start, goal, &answer.path, *field);
        return answer;
      };
      subjects.push_back(subject("planner-aa-costs",
                                 std::make_shared<Planner>(grid, Algorithm::AStar, nullptr,
                                                           HybridOptions{}, HaaOptions{}, &*field),
                                 std::make_shared<Planner>(grid, Algorithm::AStar, nullptr,
                                                           HybridOptions{}, HaaOptions{}, &*field),
                                 beginUniform<Planner>()));
      subjects.push_back(subject("weighted-haa", std::make_shared<HierarchicalAStar>(*graph),
                                 std::make_shared<HierarchicalAStar>(*graph),
                                 beginUniform<HierarchicalAStar>(), 64));
      subjects.push_back(subject("weighted-hybrid",
                                 std::make_shared<HybridPlanner>(*graph, HybridOptions{100}),
                                 std::make_shared<HybridPlanner>(*graph, HybridOptions{100}),
                                 beginUniform<HybridPlanner>(), 64));
      const std::vector<CompletenessCase> cases =
          drawCompletenessCases(grid, {agent}, seed * 3 + size, 3, 4, 1, &*field);
      expectSlicedEqualsWhole(subjects, cases, "map " + std::to_string(i), runs, pendingRuns);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  EXPECT_GT(pendingRuns, runs / 2);
}

// Search limits still hold when sliced: a budget gives BudgetExhausted at the same expansion,
// a region keeps the search inside it.
TEST(SlicedSearch, LimitsHoldWhenSliced) {
  const AnnotatedGrid grid(randomTerrainMap(77, 70, 70, 4, 15));
  const Agent agent{2, Capability::of({Terrain::Ground, Terrain::Swamp})};
  const std::vector<CompletenessCase> cases =
      drawCompletenessCases(grid, {agent, {1, agent.capability}}, 5, 6, 6, 0);
  for (const SearchLimits& limits :
       {limitsOf(1, std::nullopt), limitsOf(37, std::nullopt),
        limitsOf(UINT64_MAX, CellRect{10, 10, 40, 35}), limitsOf(60, CellRect{0, 20, 70, 30})}) {
    for (const CompletenessCase& c : cases) {
      const auto check = [&](auto& whole, auto& sliced, const char* name) {
        Answer expected;
        expected.result =
            whole.findPath(c.agent, c.query.start, c.query.goal, &expected.path, limits);
        for (const std::uint64_t batch : kBatches) {
          const SlicedAnswer got = finishSliced(
              sliced, sliced.beginPath(c.agent, c.query.start, c.query.goal, limits), batch);
          EXPECT_EQ(difference(got.answer, expected), "")
              << name << " batch " << batch << " max " << limits.maxExpanded << " "
              << describeQuery(c.agent, c.query.start, c.query.goal);
        }
      };
      AnnotatedAStar wholeA(grid), slicedA(grid);
      check(wholeA, slicedA, "aa");
      JumpPointSearch wholeJ(grid), slicedJ(grid);
      check(wholeJ, slicedJ, "jps");
    }
  }
}

// Pending while unfinished, from begin to the last update; finalize says Pending with no cells
// before that; once done, more updates change nothing.
TEST(SlicedSearch, PendingUntilDoneAndNothingAfter) {
  const AnnotatedGrid grid(randomTerrainMap(5, 80, 60, 3, 10));
  const ClusterAbstraction graph =
      ClusterAbstraction::build(grid, spec(8, AbstractionQuality::High, true));
  const Agent agent{1, Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees})};
  const std::vector<CompletenessCase> cases = drawCompletenessCases(grid, {agent}, 9, 0, 8, 0);
  for (const Algorithm algorithm :
       {Algorithm::AStar, Algorithm::Jps, Algorithm::HaaHigh, Algorithm::Hybrid}) {
    Planner planner(grid, algorithm, &graph, HybridOptions{16});
    for (const CompletenessCase& c : cases) {
      const Cell start = c.query.start;
      const Cell goal = c.query.goal;
      const PathResult whole =
          Planner(grid, algorithm, &graph, HybridOptions{16}).findPath(agent, start, goal, nullptr);
      const std::string what =
          std::string(toString(algorithm)) + " " + describeQuery(agent, start, goal);
      if (whole.metrics.expanded < 2) continue;  // nothing to slice
      ASSERT_EQ(planner.beginPath(agent, start, goal), PathStatus::Pending) << what;
      EXPECT_EQ(planner.expandedSoFar(), 0u) << what;
      std::vector<Cell> cells{start};
      const PathResult early = planner.finalizePath(&cells);
      EXPECT_EQ(early.status, PathStatus::Pending) << what;
      EXPECT_TRUE(cells.empty()) << what;
      PathStatus status = PathStatus::Pending;
      int updates = 0;
      while ((status = planner.updatePath(1)) == PathStatus::Pending)
        ++updates;
      EXPECT_GE(updates, 1) << what;
      EXPECT_EQ(status, whole.status) << what;
      const std::uint64_t spent = planner.expandedSoFar();
      EXPECT_EQ(planner.updatePath(1000), whole.status) << what;
      EXPECT_EQ(planner.updatePath(0), whole.status) << what;
      EXPECT_EQ(planner.expandedSoFar(), spent) << what;
      EXPECT_EQ(planner.finalizePath(&cells).metrics.expanded, whole.metrics.expanded) << what;
      EXPECT_FALSE(cells.empty()) << what;
    }
  }
}

// A query abandoned half-way leaves nothing behind: a new one begun on the same object
// returns what a fresh object returns, and so does the abandoned one when begun again.
TEST(SlicedSearch, AQueryCanBeAbandonedForANewOne) {
  const AnnotatedGrid grid(randomTerrainMap(17, 75, 66, 5, 18));
  const ClusterAbstraction high =
      ClusterAbstraction::build(grid, spec(8, AbstractionQuality::High, false));
  const std::vector<CompletenessCase> cases =
      drawCompletenessCases(grid, completenessAgents(3), 23, 0, 2, 0);
  for (const Algorithm algorithm :
       {Algorithm::AStar, Algorithm::Jps, Algorithm::HaaHigh, Algorithm::Hybrid}) {
    Planner reused(grid, algorithm, &high, HybridOptions{64});
    for (std::size_t k = 0; k + 1 < cases.size(); ++k) {
      const CompletenessCase& first = cases[k];
      const CompletenessCase& second = cases[k + 1];
      const std::string what = std::string(toString(algorithm)) + " " +
                               describeQuery(second.agent, second.query.start, second.query.goal);
      for (const std::uint64_t abandonAfter : {1u, 5u, 40u}) {
        reused.beginPath(first.agent, first.query.start, first.query.goal);
        for (std::uint64_t u = 0; u < abandonAfter; ++u)
          reused.updatePath(3);
        for (const CompletenessCase* c : {&second, &first}) {
          Planner fresh(grid, algorithm, &high, HybridOptions{64});
          Answer expected;
          expected.result = fresh.findPath(c->agent, c->query.start, c->query.goal, &expected.path);
          const SlicedAnswer got =
              finishSliced(reused, reused.beginPath(c->agent, c->query.start, c->query.goal), 7);
          ASSERT_EQ(difference(got.answer, expected), "") << what << " after " << abandonAfter;
        }
      }
    }
  }
}

}  // namespace
}  // namespace warpath::pathing
