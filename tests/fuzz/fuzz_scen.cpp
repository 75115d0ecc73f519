// libFuzzer harness: MovingAI .scen text through pathing::parseScen, then the queries that
// parse checked against a small map (pathing::checkScenAgainstMap), as `rts bench scen` does.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "pathing/grid_map.h"
#include "pathing/map_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace warpath;
  using namespace warpath::pathing;
  if (size > fuzz::kMaxInput) return -1;
  std::istringstream in{std::string(fuzz::asText(data, size))};
  const Result<std::vector<ScenQuery>> loaded = parseScen(in, "fuzz.scen");
  if (!loaded) {
    if (loaded.error().describe().empty()) std::abort();
    return 0;
  }
  const std::vector<ScenQuery>& queries = loaded.value();
  for (const ScenQuery& q : queries) {
    // parseScen promises coordinates inside the size each line declares.
    if (q.start.x < 0 || q.start.y < 0 || q.start.x >= q.mapWidth || q.start.y >= q.mapHeight ||
        q.goal.x < 0 || q.goal.y < 0 || q.goal.x >= q.mapWidth || q.goal.y >= q.mapHeight)
      std::abort();
  }
  // The bundled fixture's size (tests/fixtures/small.map): most seeds name a map this size.
  const GridMap fixture(6, 4);
  (void)checkScenAgainstMap(queries, fixture, "fuzz.scen");
  // Against a map of the size every query declares, nothing can be wrong.
  if (!queries.empty()) {
    const ScenQuery& first = queries.front();
    bool oneSize = first.mapWidth >= 1 && first.mapHeight >= 1 &&
                   std::int64_t{first.mapWidth} * first.mapHeight <= fuzz::kMaxExtraCells;
    for (const ScenQuery& q : queries)
      oneSize = oneSize && q.mapWidth == first.mapWidth && q.mapHeight == first.mapHeight;
    if (oneSize) {
      const GridMap same(first.mapWidth, first.mapHeight);
      if (!checkScenAgainstMap(queries, same, "fuzz.scen").ok()) std::abort();
    }
  }
  return 0;
}
