// Terrain that changes (issue 14): after any sequence of changes, the grid's repaired caches
// equal those computed from scratch on the changed map, and repaired HAA* graphs (HQ and LQ,
// uniform and weighted) find a path exactly when AA* on the changed map does, every step
// legal, never cheaper.

#include <gtest/gtest.h>

#include <map>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/haa_star.h"
#include "pathing/map_generator.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"
#include "random_changes.h"
#include "random_grid.h"
#include "support/completeness.h"

namespace warpath::pathing {
namespace {

using testing::checkCompleteness;
using testing::completenessAgents;
using testing::completenessCapabilities;
using testing::CompletenessTally;
using testing::drawCompletenessCases;

GridMap randomMap(std::uint64_t seed, int width, int height, int maxPatch) {
  return randomTerrainMap(seed, width, height, maxPatch, 12);
}

// Component ids may differ after updates; the cells they group may not.
bool samePartition(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b) {
  if (a.size() != b.size()) return false;
  std::map<std::uint32_t, std::uint32_t> aToB;
  std::map<std::uint32_t, std::uint32_t> bToA;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if ((a[i] == 0) != (b[i] == 0)) return false;
    if (a[i] == 0) continue;
    if (aToB.try_emplace(a[i], b[i]).first->second != b[i]) return false;
    if (bToA.try_emplace(b[i], a[i]).first->second != a[i]) return false;
  }
  return true;
}

std::string cell(Cell c) {
  return std::to_string(c.x) + "," + std::to_string(c.y);
}

TEST(TerrainChange, RepairedCachesEqualFreshOnes) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    AnnotatedGrid grid(randomMap(seed, 40 + 5 * static_cast<int>(seed), 37, 6));
    // Fill the caches first, so that every change repairs them.
    for (const Agent& agent : completenessAgents())
      (void)grid.layer(agent);
    RandomChanges changes{SplitMix64(seed), 9, {}};
    for (int step = 0; step < 40; ++step) {
      const std::uint64_t before = grid.revision();
      const TerrainChange change = changes.apply(grid);
      EXPECT_EQ(grid.revision(), before + (change.changed ? 1 : 0));
      const AnnotatedGrid fresh(grid.map());
      for (const Capability capability : completenessCapabilities()) {
        const auto repaired = grid.clearance(capability).values();
        const auto truth = fresh.clearance(capability).values();
        ASSERT_TRUE(std::equal(repaired.begin(), repaired.end(), truth.begin(), truth.end()))
            << "seed " << seed << " step " << step << " clearance " << capability.toString();
      }
      for (const Agent& agent : completenessAgents()) {
        const AgentLayer& repaired = grid.layer(agent);
        const AgentLayer& truth = fresh.layer(agent);
        ASSERT_TRUE(std::ranges::equal(repaired.moveMasks(), truth.moveMasks()))
            << "seed " << seed << " step " << step << " moves";
        ASSERT_TRUE(samePartition(repaired.components(), truth.components()))
            << "seed " << seed << " step " << step << " components";
      }
    }
  }
}

// Layers prepared on several threads at once are those computed one at a time on demand.
TEST(TerrainChange, LayersPreparedOnThreadsEqualOnesComputedOnDemand) {
  const GridMap map = randomMap(8, 53, 45, 6);
  const AnnotatedGrid lazy(map);
  const AnnotatedGrid prepared(map);
  const std::vector<Agent> agents = completenessAgents();
  prepared.prepare(agents, 3);
  prepared.prepare(agents, 3);  // nothing left to compute: the cached ones stay
  for (const Agent& agent : agents) {
    EXPECT_TRUE(std::ranges::equal(lazy.clearance(agent.capability).values(),
                                   prepared.clearance(agent.capability).values()));
    EXPECT_TRUE(
        std::ranges::equal(lazy.layer(agent).moveMasks(), prepared.layer(agent).moveMasks()));
    EXPECT_TRUE(
        std::ranges::equal(lazy.layer(agent).components(), prepared.layer(agent).components()));
  }
}

// Repaired on several threads (one capability each), the caches are those one thread repairs,
// component ids included.
TEST(TerrainChange, CachesRepairedOnThreadsEqualThoseOfOneThread) {
  for (std::uint64_t seed = 5; seed <= 6; ++seed) {
    const GridMap map = randomMap(seed, 47, 41, 6);
    AnnotatedGrid one(map);
    AnnotatedGrid three(map);
    three.setUpdateThreads(3);
    for (const Agent& agent : completenessAgents()) {
      (void)one.layer(agent);
      (void)three.layer(agent);
    }
    RandomChanges forOne{SplitMix64(seed), 9, {}};
    RandomChanges forThree{SplitMix64(seed), 9, {}};
    for (int step = 0; step < 30; ++step) {
      ASSERT_EQ(forOne.apply(one).area, forThree.apply(three).area);
      for (const Capability capability : completenessCapabilities()) {
        ASSERT_TRUE(std::ranges::equal(one.clearance(capability).values(),
                                       three.clearance(capability).values()))
            << "seed " << seed << " step " << step;
      }
      for (const Agent& agent : completenessAgents()) {
        ASSERT_TRUE(
            std::ranges::equal(one.layer(agent).moveMasks(), three.layer(agent).moveMasks()))
            << "seed " << seed << " step " << step;
        ASSERT_TRUE(
            std::ranges::equal(one.layer(agent).components(), three.layer(agent).components()))
            << "seed " << seed << " step " << step;
      }
    }
  }
}

// The grid keeps the areas of its last changes, so caches built at a revision can repair just
// what changed since: the bounding box of those changes (clipped), empty when none (a call that
// changed no cell is no change), and nullopt once more changes were made than it keeps.
TEST(TerrainChange, TheGridTellsWhatChangedSinceARevision) {
  AnnotatedGrid grid(GridMap(40, 30));
  EXPECT_EQ(grid.changedSince(0), (CellRect{0, 0, 0, 0}));
  (void)grid.setTerrain({3, 4, 2, 2}, Terrain::Water);
  (void)grid.setTerrain({3, 4, 2, 2}, Terrain::Water);  // no cell changes: no revision
  ASSERT_EQ(grid.revision(), 1u);
  (void)grid.placeObstacle({36, 27, 8, 8});  // clipped to the map
  EXPECT_EQ(grid.changedSince(0), (CellRect{3, 4, 37, 26}));
  EXPECT_EQ(grid.changedSince(1), (CellRect{36, 27, 4, 3}));
  EXPECT_EQ(grid.changedSince(2), (CellRect{0, 0, 0, 0}));
  EXPECT_FALSE(grid.changedSince(3));  // a revision the grid has not reached
  for (std::size_t i = 0; i < AnnotatedGrid::kChangesKept; ++i)
    (void)grid.setTerrain({0, 0, 1, 1}, i % 2 == 0 ? Terrain::Trees : Terrain::Ground);
  EXPECT_FALSE(grid.changedSince(0));
  EXPECT_FALSE(grid.changedSince(1));
  EXPECT_EQ(grid.changedSince(2), (CellRect{0, 0, 1, 1}));
}

TEST(TerrainChange, ObstaclesKeepTheTerrainUnderneath) {
  GridMap map(12, 8);
  map.set({4, 4}, Terrain::Swamp);
  AnnotatedGrid grid(map);
  const Agent tank{2, Capability::of({Terrain::Ground})};
  EXPECT_TRUE(grid.canStand(tank, {2, 2}));
  EXPECT_TRUE(grid.placeObstacle({3, 3, 2, 2}).changed);
  EXPECT_TRUE(grid.placeObstacle({4, 3, 2, 2}).changed);  // overlaps the first
  EXPECT_EQ(grid.map().at({4, 4}), Terrain::Blocked);
  EXPECT_FALSE(grid.canStand(tank, {2, 2}));
  // Terrain set under an obstacle shows once the obstacle is gone.
  EXPECT_FALSE(grid.setTerrain({5, 3, 1, 1}, Terrain::Water).changed);
  EXPECT_TRUE(grid.clearObstacle({3, 3, 2, 2}).changed);
  EXPECT_EQ(grid.map().at({3, 3}), Terrain::Ground);
  EXPECT_EQ(grid.map().at({4, 4}), Terrain::Blocked);  // the second still stands there
  EXPECT_TRUE(grid.clearObstacle({4, 3, 2, 2}).changed);
  EXPECT_EQ(grid.map().at({4, 4}), Terrain::Swamp);
  EXPECT_EQ(grid.map().at({5, 3}), Terrain::Water);
  EXPECT_THROW((void)grid.clearObstacle({4, 3, 1, 1}), std::invalid_argument);
  // Nothing changes off the map.
  const TerrainChange off = grid.setTerrain({20, 20, 3, 3}, Terrain::Blocked);
  EXPECT_FALSE(off.changed);
  EXPECT_EQ(off.area.width * off.area.height, 0);
}

TEST(TerrainChange, CostFieldUpdateEqualsAFreshField) {
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  costs.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  AnnotatedGrid grid(randomMap(9, 48, 40, 5));
  for (int size = 1; size <= 3; ++size) {
    const Agent agent{size, costs.capability()};
    CostField field(grid, agent, costs);
    RandomChanges changes{SplitMix64(static_cast<std::uint64_t>(size) * 31), 7, {}};
    for (int step = 0; step < 25; ++step) {
      const TerrainChange change = changes.apply(grid);
      if (change.changed) field.update(grid, change.area);
      const CostField fresh(grid, agent, costs);
      for (std::uint32_t i = 0; i < grid.map().cellCount(); ++i)
        ASSERT_EQ(field.at(i), fresh.at(i))
            << "size " << size << " step " << step << " anchor " << cell(grid.map().cellAt(i));
      EXPECT_LE(field.cheapest(), fresh.cheapest());
    }
  }
}

// A repair keeps the graph's statistics by difference: they must equal a count of the graph.
void expectStatsCounted(const ClusterAbstraction& g, const std::string& label) {
  std::size_t nodes = 0;
  std::size_t inter = 0;
  std::size_t intra = 0;
  for (int k = 0; k < g.clusterCount(); ++k) {
    for (std::uint32_t n : g.nodesInCluster(k)) {
      ++nodes;
      EXPECT_FALSE(g.edgesOf(n).empty()) << label << ": a listed node without edges";
      for (const AbstractEdge& e : g.edgesOf(n))
        ++(e.intra ? intra : inter);
    }
  }
  EXPECT_EQ(g.stats().nodes, nodes) << label;
  EXPECT_EQ(g.stats().interEdges, inter / 2) << label;
  EXPECT_EQ(g.stats().intraEdges, intra / 2) << label;
}

// The property of issue 14: repaired graphs stay complete and sound on the changed map.
TEST(TerrainChange, RepairedGraphsFindAPathExactlyWhenAStarDoes) {
  CompletenessTally tally;
  int repairs = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
      AnnotatedGrid grid(randomMap(seed * 13, 50 + 6 * static_cast<int>(seed), 44, 5));
      AbstractionSpec spec;
      spec.clusterSize = 8 + 4 * static_cast<int>(seed % 2);
      spec.maxAgentSize = 3;
      spec.capabilities = completenessCapabilities();
      spec.quality = quality;
      spec.cachePaths = seed != 2;
      ClusterAbstraction abstraction = ClusterAbstraction::build(grid, spec);
      HierarchicalAStar haa(abstraction);
      // Insertion tables made before the changes must follow them (clusterRevision): unsmoothed,
      // with cached paths, every answer costs what the insertion by search finds.
      HierarchicalAStar tabled(abstraction, HaaOptions{.insertion = InsertionMode::Tables});
      HierarchicalAStar rawTabled(abstraction,
                                  HaaOptions{.smooth = false, .insertion = InsertionMode::Tables});
      HierarchicalAStar rawSearched(abstraction, HaaOptions{.smooth = false});
      for (const Agent& agent : completenessAgents())
        tabled.prepare(agent);
      RandomChanges changes{SplitMix64(seed * 101), 10, {}};
      for (int step = 0; step < 12; ++step) {
        const TerrainChange change = changes.apply(grid);
        abstraction.repair(change);
        repairs += change.changed ? 1 : 0;
        // AA* on a grid built afresh from the changed map is the truth.
        const AnnotatedGrid fresh(grid.map());
        const auto cases = drawCompletenessCases(
            fresh, completenessAgents(), seed * 1000 + static_cast<std::uint64_t>(step), 1, 3, 1);
        std::ostringstream label;
        label << "seed " << seed << " " << kAbstractionQualityNames.name(quality) << " step "
              << step << " after " << change.area.width << "x" << change.area.height << " at "
              << cell({change.area.x, change.area.y});
        checkCompleteness(fresh, cases, haa, label.str(), tally);
        checkCompleteness(fresh, cases, tabled, label.str() + ", insertion tables", tally);
        for (const auto& c : cases) {
          const PathResult byTables =
              rawTabled.findPath(c.agent, c.query.start, c.query.goal, nullptr);
          const PathResult bySearch =
              rawSearched.findPath(c.agent, c.query.start, c.query.goal, nullptr);
          ASSERT_EQ(byTables.status, bySearch.status) << label.str();
          if (bySearch.found() && spec.cachePaths) {
            EXPECT_NEAR(byTables.cost, bySearch.cost, 1e-3) << label.str();
          }
        }
        expectStatsCounted(abstraction, label.str());
      }
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(repairs, 50);
  EXPECT_GT(tally.found, 1000);
  EXPECT_GT(tally.notFound, 100);
}

TEST(TerrainChange, RepairedWeightedGraphsStayCompleteUnderCosts) {
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 0.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 2.0;
  costs.perCell[static_cast<std::size_t>(Terrain::Water)] = 1.0;
  CompletenessTally tally;
  for (int size = 1; size <= 3; ++size) {
    for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
      AnnotatedGrid grid(randomMap(77 + static_cast<std::uint64_t>(size), 52, 46, 6));
      const Agent agent{size, costs.capability()};
      ClusterAbstraction abstraction =
          ClusterAbstraction::build(grid, weightedAbstractionSpec(agent, costs, 8, quality));
      HierarchicalAStar haa(abstraction);
      RandomChanges changes{SplitMix64(static_cast<std::uint64_t>(size) * 7 + 3), 8, {}};
      for (int step = 0; step < 10; ++step) {
        const TerrainChange change = changes.apply(grid);
        abstraction.repair(change);
        const AnnotatedGrid fresh(grid.map());
        const CostField field(fresh, agent, costs);
        const auto cases = drawCompletenessCases(
            fresh, {agent}, static_cast<std::uint64_t>(size * 100 + step), 2, 8, 1, &field);
        std::ostringstream label;
        label << "size " << size << " " << kAbstractionQualityNames.name(quality) << " step "
              << step;
        checkCompleteness(fresh, cases, haa, label.str(), tally);
      }
    }
  }
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 300);
}

}  // namespace
}  // namespace warpath::pathing
