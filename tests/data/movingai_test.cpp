// Extended suite (CTest label `data`): every query of every MovingAI scen file in the shared
// data folder must reproduce its published optimal length with AA*. Built only when the data
// folder exists; the maps are read from there at run time, never copied into the repository.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/map_io.h"

namespace warpath::pathing {
namespace {

namespace fs = std::filesystem;

struct MapCase {
  std::string family;
  std::string name;
  fs::path map;
  fs::path scen;
};

// Keeps CTest's test names readable (gtest would otherwise print the bytes of the struct).
void PrintTo(const MapCase& c, std::ostream* out) {
  *out << c.map.string();
}

fs::path movingAiRoot() {
  return fs::path(WARPATH_MOVINGAI_DIR);
}

// Pairs maps/<family>/X.map with scenarios/<family>/X.map.scen, sorted for a stable order.
std::vector<MapCase> discoverCases() {
  std::vector<MapCase> cases;
  const fs::path maps = movingAiRoot() / "maps";
  std::error_code ec;
  for (const auto& family : fs::directory_iterator(maps, ec)) {
    for (const auto& entry : fs::directory_iterator(family.path(), ec)) {
      if (entry.path().extension() != ".map") continue;
      const fs::path scen = movingAiRoot() / "scenarios" / family.path().filename() /
                            (entry.path().filename().string() + ".scen");
      if (!fs::exists(scen)) continue;
      cases.push_back(
          {family.path().filename().string(), entry.path().stem().string(), entry.path(), scen});
    }
  }
  std::sort(cases.begin(), cases.end(),
            [](const MapCase& a, const MapCase& b) { return a.map < b.map; });
  return cases;
}

class MovingAiOptimality : public ::testing::TestWithParam<MapCase> {};

TEST_P(MovingAiOptimality, EveryScenQueryMatchesItsOptimalLength) {
  const MapCase& c = GetParam();
  auto map = loadMap(c.map);
  ASSERT_TRUE(map) << map.error().describe();
  auto scen = loadScen(c.scen);
  ASSERT_TRUE(scen) << scen.error().describe();
  const auto mismatch = checkScenAgainstMap(scen.value(), map.value(), c.scen.string());
  ASSERT_FALSE(mismatch) << mismatch->describe();

  const AnnotatedGrid grid(std::move(map).value());
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  int failures = 0;
  for (const ScenQuery& q : scen.value()) {
    // MovingAI semantics: size 1, capability = the start cell's movement class.
    const Agent agent{1, movingAiClassOf(grid.map().at(q.start))};
    const PathResult result = search.findPath(agent, q.start, q.goal, &path);
    const bool ok = result.found() && std::abs(result.cost - q.optimalLength) <= 0.01 &&
                    findIllegalStep(grid, agent, path).empty();
    if (!ok && ++failures <= 5) {
      ADD_FAILURE() << c.scen.string() << ":" << q.line << ": expected " << q.optimalLength
                    << ", got " << toString(result.status) << " " << result.cost;
    }
  }
  EXPECT_EQ(failures, 0) << "of " << scen.value().size() << " queries";
  EXPECT_FALSE(scen.value().empty());
}

INSTANTIATE_TEST_SUITE_P(Data, MovingAiOptimality, ::testing::ValuesIn(discoverCases()),
                         [](const ::testing::TestParamInfo<MapCase>& param) {
                           std::string name = param.param.family + "_" + param.param.name;
                           for (char& ch : name) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace warpath::pathing
