// The path service under terrain that changes (issue 14): its graphs are repaired, and of its
// cached answers only those the change touches are dropped.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "engine/path_service.h"
#include "pathing/annotated_grid.h"
#include "support/serve_all.h"

namespace warpath::engine {
namespace {

using pathing::Cell;
using pathing::PathStatus;
using pathing::Terrain;

// Two halves joined by a bridge of ground over a river (water) and a ford far south.
pathing::GridMap river() {
  pathing::GridMap map(64, 48);
  for (int y = 0; y < 48; ++y) {
    for (int x = 28; x < 36; ++x)
      map.set({x, y}, Terrain::Water);
  }
  for (int y = 8; y < 12; ++y) {
    for (int x = 28; x < 36; ++x)
      map.set({x, y}, Terrain::Ground);  // the bridge
  }
  return map;
}

TEST(PathServiceTerrainChange, GraphsFollowTheChangeAndOnlyTouchedAnswersAreDropped) {
  for (const pathing::Algorithm algorithm :
       {pathing::Algorithm::AStar, pathing::Algorithm::HaaHigh, pathing::Algorithm::HaaLow,
        pathing::Algorithm::Hybrid}) {
    SCOPED_TRACE(std::string(pathing::toString(algorithm)));
    pathing::AnnotatedGrid grid(river());
    PathServiceSettings settings;
    settings.algorithm = algorithm;
    const pathing::Agent tank{2, pathing::Capability::of({Terrain::Ground})};
    PathService service(grid, settings, {tank.capability}, 2);
    service.request({{0, 0}, 1, tank, {4, 9}, {58, 9}});    // across the bridge
    service.request({{1, 0}, 1, tank, {4, 30}, {20, 40}});  // on the west bank only
    std::vector<PathDelivery> out = testing::serveAll(service).deliveries;
    ASSERT_EQ(out.size(), 2u);
    ASSERT_EQ(out[0].status, PathStatus::Found);
    ASSERT_EQ(out[1].status, PathStatus::Found);
    const SharedPath westBank = out[1].path;

    // The bridge is blown: water where it stood.
    const pathing::TerrainChange blown = grid.setTerrain({28, 8, 8, 4}, Terrain::Water);
    ASSERT_TRUE(blown.changed);
    service.changeTerrain(blown);
    EXPECT_EQ(service.metrics().terrainChanges, 1u);
    EXPECT_EQ(service.metrics().cacheDropped, 1u);  // the crossing, not the west-bank path
    service.request({{0, 0}, 2, tank, {4, 9}, {58, 9}});
    service.request({{1, 0}, 2, tank, {4, 30}, {20, 40}});
    out = testing::serveAll(service).deliveries;
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].status, PathStatus::Unreachable);
    EXPECT_EQ(out[1].path, westBank);  // still cached: the change did not touch it

    // A ford is laid further south: the crossing is found again, through it.
    const pathing::TerrainChange ford = grid.setTerrain({28, 36, 8, 3}, Terrain::Ground);
    service.changeTerrain(ford);
    EXPECT_EQ(service.metrics().cacheDropped, 2u);  // the failed answer may now succeed
    service.request({{0, 0}, 3, tank, {4, 9}, {58, 9}});
    out = testing::serveAll(service).deliveries;
    ASSERT_EQ(out.size(), 1u);
    ASSERT_EQ(out[0].status, PathStatus::Found);
    EXPECT_EQ(pathing::findIllegalStep(grid, tank, out[0].path->cells), "");
    bool throughFord = false;
    for (const Cell& c : out[0].path->cells)
      throughFord = throughFord || (c.x >= 28 && c.x < 36 && c.y >= 35);
    EXPECT_TRUE(throughFord);
  }
}

// A large change is repaired over several ticks within the budget; requests wait for it and
// are then answered on the changed map.
TEST(PathServiceTerrainChange, ALargeChangeIsRepairedOverSeveralTicks) {
  pathing::AnnotatedGrid grid(pathing::GridMap(160, 160));
  PathServiceSettings settings;
  settings.algorithm = pathing::Algorithm::HaaHigh;
  settings.expansionBudget = 5000;
  const pathing::Agent jeep{2, pathing::Capability::of({Terrain::Ground})};
  PathService service(grid, settings, {jeep.capability}, 2);
  // A wall across the map but for a gap at the bottom right: 150 cells of it.
  service.changeTerrain(grid.setTerrain({0, 80, 150, 2}, Terrain::Blocked));
  const std::size_t chunks = service.repairsPending();
  EXPECT_EQ(chunks, 3u);  // 150 cells in chunks of 4 clusters of 16
  service.request({{0, 0}, 1, jeep, {5, 5}, {5, 150}});
  std::vector<PathDelivery> out;
  int ticks = 0;
  while (out.empty() && ticks < 10) {
    service.serve(out);
    ++ticks;
  }
  EXPECT_GT(ticks, 1);  // the budget spread the repair
  EXPECT_EQ(service.repairsPending(), 0u);
  EXPECT_EQ(service.metrics().repairChunks, chunks);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].status, PathStatus::Found);
  EXPECT_EQ(pathing::findIllegalStep(grid, jeep, out[0].path->cells), "");
}

// Profiles merged because the map lacked a terrain are told apart once a change brings it.
TEST(PathServiceTerrainChange, ATerrainNewToTheMapSeparatesMergedCostProfiles) {
  pathing::AnnotatedGrid grid(pathing::GridMap(48, 32));
  pathing::TerrainCosts walker;
  walker.perCell[static_cast<std::size_t>(Terrain::Ground)] = 0.5;
  pathing::TerrainCosts swimmer = walker;
  swimmer.perCell[static_cast<std::size_t>(Terrain::Water)] = 1.0;
  const pathing::Capability land = pathing::Capability::of({Terrain::Ground});
  const pathing::Capability amphibious = pathing::Capability::of({Terrain::Ground, Terrain::Water});
  PathServiceSettings settings;
  settings.algorithm = pathing::Algorithm::HaaHigh;
  settings.terrainCosts = true;
  PathService service(grid, settings, {land, amphibious}, 1,
                      {{{1, land}, walker}, {{1, amphibious}, swimmer}});
  EXPECT_EQ(service.distinctCostProfiles(), 1u);  // no water on the map yet
  // A lake cuts the map in two from top to bottom.
  service.changeTerrain(grid.setTerrain({20, 0, 6, 32}, Terrain::Water));
  EXPECT_EQ(service.distinctCostProfiles(), 2u);
  service.request({{0, 0}, 1, {1, land}, {2, 5}, {45, 5}, 0});
  service.request({{1, 0}, 1, {1, amphibious}, {2, 5}, {45, 5}, 1});
  const std::vector<PathDelivery> out = testing::serveAll(service).deliveries;
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].status, PathStatus::Unreachable);
  EXPECT_EQ(out[1].status, PathStatus::Found);
}

}  // namespace
}  // namespace warpath::engine
