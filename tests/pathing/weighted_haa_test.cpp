// HAA* and the hybrid planner under terrain costs (issue 13): on random multi-terrain maps, for
// cost profiles like the catalogue's and sizes 1-3, a weighted graph finds a path exactly when
// weighted AA* does, every path is legal, its cost is what it says, and none is cheaper than the
// weighted optimum.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/haa_star.h"
#include "pathing/map_generator.h"
#include "pathing/planner.h"
#include "pathing/terrain_costs.h"
#include "random_grid.h"
#include "support/completeness.h"

namespace warpath::pathing {
namespace {

using testing::checkCompleteness;
using testing::CompletenessCase;
using testing::CompletenessTally;
using testing::drawCompletenessCases;

TerrainCosts costsOf(std::initializer_list<std::pair<Terrain, double>> speeds) {
  TerrainCosts costs;
  for (const auto& [terrain, speed] : speeds)
    costs.perCell[static_cast<std::size_t>(terrain)] = 1.0 / speed;
  return costs;
}

struct Profile {
  const char* name;
  TerrainCosts costs;
};

// Speeds like the catalogue's, and one where a swamp is four times slower than ground.
std::vector<Profile> profiles() {
  return {
      {"infantry", costsOf({{Terrain::Ground, 1.5}, {Terrain::Swamp, 0.8}, {Terrain::Trees, 1.0}})},
      {"amphibious",
       costsOf({{Terrain::Ground, 2.0}, {Terrain::Swamp, 1.2}, {Terrain::Water, 1.0}})},
      {"slow swamp", costsOf({{Terrain::Ground, 2.0}, {Terrain::Swamp, 0.5}})},
  };
}

GridMap randomMap(std::uint64_t seed, int width, int height, int maxPatch, int blocked) {
  return randomTerrainMap(seed, width, height, maxPatch, blocked);
}

TEST(WeightedHaaStar, CompleteLegalAndNeverCheaperThanWeightedAStar) {
  CompletenessTally high;
  CompletenessTally low;
  for (int i = 0; i < 6; ++i) {
    const std::uint64_t seed = 41 + static_cast<std::uint64_t>(i);
    const AnnotatedGrid grid(randomMap(seed, 53 + 7 * i, 61 - 3 * i, 1 + (i * 3) % 9, 8 + 3 * i));
    for (const Profile& profile : profiles()) {
      for (int size = 1; size <= 3; ++size) {
        const Agent agent{size, profile.costs.capability()};
        const CostField field(grid, agent, profile.costs);
        const std::vector<CompletenessCase> cases = drawCompletenessCases(
            grid, {agent}, seed * 7 + static_cast<std::uint64_t>(size), 6, 14, 2, &field);
        for (int clusterSize : {8, 16}) {
          for (AbstractionQuality quality : {AbstractionQuality::High, AbstractionQuality::Low}) {
            for (bool cachePaths : {true, false}) {
              if (!cachePaths && clusterSize != 8) continue;
              AbstractionSpec spec =
                  weightedAbstractionSpec(agent, profile.costs, clusterSize, quality);
              spec.cachePaths = cachePaths;
              ASSERT_EQ(problemWith(spec), "");
              const ClusterAbstraction abstraction = ClusterAbstraction::build(grid, spec);
              ASSERT_TRUE(abstraction.supports(agent));
              std::ostringstream label;
              label << "map seed " << seed << ", " << profile.name << " size " << size
                    << ", cluster " << clusterSize << " " << kAbstractionQualityNames.name(quality)
                    << (cachePaths ? "" : " uncached");
              CompletenessTally& tally = quality == AbstractionQuality::High ? high : low;
              HierarchicalAStar smoothed(abstraction, HaaOptions{.smooth = true});
              HierarchicalAStar raw(abstraction, HaaOptions{.smooth = false});
              checkCompleteness(grid, cases, smoothed, label.str() + " smoothed", tally);
              checkCompleteness(grid, cases, raw, label.str() + " unsmoothed", tally);
              HybridPlanner hybrid(abstraction, HybridOptions{.tau = 256});
              checkCompleteness(grid, cases, hybrid, label.str() + " hybrid", tally);
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(high.failures + low.failures, 0);
  EXPECT_GT(high.found, 4000);
  EXPECT_GT(high.notFound, 500);
  // Loose bounds: the benchmarks measure the error (docs/benchmarks.md); these catch a graph
  // that ignores the costs, whose paths wade where they should go round.
  EXPECT_LT(high.meanError(), 0.05) << "HQ mean error";
  EXPECT_LT(low.meanError(), 0.08) << "LQ mean error";
}

// A border half swamp and half ground gets a transition on each half, so a crossing is chosen
// by cost: a swamp-shy agent crosses on the ground half even when the straight line is swamp.
TEST(WeightedHaaStar, TransitionsAreChosenByCost) {
  GridMap map(32, 16);
  for (int y = 0; y < 16; ++y) {
    for (int x = 12; x < 20; ++x) {
      if (y < 11) map.set({x, y}, Terrain::Swamp);
    }
  }
  const AnnotatedGrid grid(std::move(map));
  const TerrainCosts costs = costsOf({{Terrain::Ground, 2.0}, {Terrain::Swamp, 0.25}});
  const Agent agent{1, costs.capability()};
  const CostField field(grid, agent, costs);
  const ClusterAbstraction weighted = ClusterAbstraction::build(
      grid, weightedAbstractionSpec(agent, costs, 16, AbstractionQuality::High));
  AnnotatedAStar astar(grid);
  const PathResult optimum = astar.findPath(agent, {2, 3}, {29, 3}, nullptr, field);
  ASSERT_TRUE(optimum.found());
  HierarchicalAStar haa(weighted);
  std::vector<Cell> path;
  const PathResult r = haa.findPath(agent, {2, 3}, {29, 3}, &path);
  ASSERT_TRUE(r.found());
  for (const Cell& c : path)
    EXPECT_NE(grid.map().at(c), Terrain::Swamp) << c.x << "," << c.y;
  EXPECT_NEAR(field.pathCost(path), r.cost, 1e-9);
  EXPECT_LT(r.cost, optimum.cost * 1.05);

  // The same graph in the uniform model has one transition per border and wades.
  AbstractionSpec uniformSpec = weightedAbstractionSpec(agent, costs, 16, AbstractionQuality::High);
  uniformSpec.costs.reset();
  const ClusterAbstraction uniform = ClusterAbstraction::build(grid, uniformSpec);
  EXPECT_GT(weighted.stats().nodes, uniform.stats().nodes);
  HierarchicalAStar plain(uniform);
  ASSERT_TRUE(plain.findPath(agent, {2, 3}, {29, 3}, &path).found());
  EXPECT_GT(field.pathCost(path), r.cost * 1.5);
}

TEST(WeightedHaaStar, SpecsAreValidated) {
  const TerrainCosts costs = costsOf({{Terrain::Ground, 1.0}});
  AbstractionSpec spec{
      .capabilities = {Capability::of({Terrain::Ground}), Capability::of({Terrain::Water})},
      .costs = costs};
  EXPECT_EQ(problemWith(spec),
            "capabilities must hold exactly one capability when costs are "
            "given (got 2)");
  spec.capabilities = {Capability::of({Terrain::Ground, Terrain::Swamp})};
  EXPECT_EQ(problemWith(spec), "costs must give a cost to every terrain of capabilities[0]");
  spec.capabilities = {Capability::of({Terrain::Ground})};
  EXPECT_EQ(problemWith(spec), "");
}

// A weighted graph serves its one agent; others are planned in the uniform model by AA*.
TEST(WeightedHaaStar, ServesOnlyItsAgent) {
  const AnnotatedGrid grid(randomMap(5, 40, 40, 4, 10));
  const TerrainCosts costs = profiles()[0].costs;
  const Agent tank{2, costs.capability()};
  const ClusterAbstraction abstraction = ClusterAbstraction::build(
      grid, weightedAbstractionSpec(tank, costs, 8, AbstractionQuality::High));
  EXPECT_TRUE(abstraction.supports(tank));
  EXPECT_FALSE(abstraction.supports({1, costs.capability()}));
  EXPECT_FALSE(abstraction.supports({3, costs.capability()}));
  ASSERT_NE(abstraction.costs(), nullptr);
  const Agent small{1, costs.capability()};
  const std::vector<CompletenessCase> cases = drawCompletenessCases(grid, {small}, 3, 4, 8, 0);
  HierarchicalAStar haa(abstraction);
  CompletenessTally tally;
  checkCompleteness(grid, cases, haa, "unserved size", tally);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.found, 5);
}

// AA* through the planner facade plans under the costs it is given.
TEST(WeightedHaaStar, PlannerFacadePassesCostsToAStar) {
  const AnnotatedGrid grid(randomMap(9, 48, 40, 5, 12));
  const TerrainCosts costs = profiles()[2].costs;
  const Agent agent{1, costs.capability()};
  const CostField field(grid, agent, costs);
  const std::vector<CompletenessCase> cases =
      drawCompletenessCases(grid, {agent}, 4, 4, 12, 2, &field);
  Planner planner(grid, Algorithm::AStar, nullptr, {}, {}, &field);
  CompletenessTally tally;
  checkCompleteness(grid, cases, planner, "aa with costs", tally);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_DOUBLE_EQ(tally.meanError(), 0.0);
  EXPECT_GT(tally.found, 10);
}

}  // namespace
}  // namespace warpath::pathing
