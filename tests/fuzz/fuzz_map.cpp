// libFuzzer harness: MovingAI .map text through pathing::parseMap. A map that parses must
// write back and parse to the same map; on small maps one AA* query for an agent drawn from
// the input must return a legal path (pathing::findIllegalStep) when it finds one.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "pathing/aa_star.h"
#include "pathing/annotated_grid.h"
#include "pathing/map_io.h"

namespace {

using namespace warpath;
using namespace warpath::pathing;

void searchOnce(GridMap map, fuzz::Choices& choices) {
  const int width = map.width();
  const int height = map.height();
  const AnnotatedGrid grid(std::move(map));
  const Agent agent{1 + choices.below(3),
                    Capability::fromMask(static_cast<std::uint8_t>(1 + choices.below(15)))};
  const Cell start{choices.below(width), choices.below(height)};
  const Cell goal{choices.below(width), choices.below(height)};
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  const PathResult result = search.findPath(agent, start, goal, &path);
  if (result.found()) {
    if (path.empty() || !(path.front() == start) || !(path.back() == goal)) std::abort();
    if (!findIllegalStep(grid, agent, path).empty()) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > fuzz::kMaxInput) return -1;
  const std::string_view text = fuzz::asText(data, size);
  std::istringstream in{std::string(text)};
  Result<GridMap> loaded = parseMap(in, "fuzz.map");
  if (!loaded) {
    if (loaded.error().describe().empty()) std::abort();
    return 0;
  }
  GridMap& map = loaded.value();

  // Round trip: the canonical form reads back as the same map.
  std::ostringstream out;
  writeMap(map, out);
  std::istringstream back(out.str());
  Result<GridMap> again = parseMap(back, "fuzz-written.map");
  if (!again || !(again.value() == map)) std::abort();

  if (map.width() >= 1 && map.height() >= 1 &&
      std::int64_t{map.width()} * map.height() <= fuzz::kMaxExtraCells) {
    fuzz::Choices choices(text);
    searchOnce(std::move(map), choices);
  }
  return 0;
}
