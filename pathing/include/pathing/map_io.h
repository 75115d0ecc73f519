#pragma once
// MovingAI benchmark formats: octile `.map` files and `.scen` query files.
// Map:  "type octile" / "height H" / "width W" / "map", then H rows of W characters
//       ('.' 'G' ground, 'S' swamp, 'T' trees, 'W' water, '@' 'O' blocked).
// Costs: warthog's cost table (parseCostTable).
// Scen: "version 1" (tab-separated) or "version 1.0" (space-separated), then one query a
//       line: bucket, map path, map width, map height, start x, start y, goal x, goal y,
//       optimal length. Blank lines are skipped.

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pathing/error.h"
#include "pathing/grid_map.h"
#include "pathing/terrain_costs.h"

namespace warpath::pathing {

// `sourceName` is used in error messages (usually the file path).
Result<GridMap> parseMap(std::string_view text, std::string_view sourceName);
Result<GridMap> parseMap(std::istream& in, std::string_view sourceName);
// Through readFileCapped (pathing/file_read.h): at most kMapFileLimit bytes, regular files only.
Result<GridMap> loadMap(const std::filesystem::path& file);

// The canonical character of a terrain ('.', 'S', 'T', 'W', '@'); '?' for one the format
// cannot express.
char mapChar(Terrain t);

// Writes the canonical form ('.', 'S', 'T', 'W', '@'); parseMap reads it back identically.
void writeMap(const GridMap& map, std::ostream& out);
// Fails ("cannot open 'FILE' for writing: reason") when the file cannot be written.
Status saveMap(const GridMap& map, const std::filesystem::path& file);

struct ScenQuery {
  int bucket = 0;
  std::string mapName;  // as written in the file; historical, not used to find the map
  int mapWidth = 0;
  int mapHeight = 0;
  Cell start;
  Cell goal;
  double optimalLength = 0.0;
  int line = 0;  // 1-based line in the scen file, for reports
};

// Every query's coordinates are checked against the width and height the line declares.
Result<std::vector<ScenQuery>> parseScen(std::string_view text, std::string_view sourceName);
Result<std::vector<ScenQuery>> parseScen(std::istream& in, std::string_view sourceName);
// Through readFileCapped: at most kScenFileLimit bytes, regular files only.
Result<std::vector<ScenQuery>> loadScen(const std::filesystem::path& file);

// Warthog's cost tables: one line per map character, the character, blanks, its cost (a
// number >= 0; 0: impassable); blank lines are skipped. Characters of one terrain ('.' and
// 'G') must agree; blocked characters may only cost 0; terrains no line names are impassable.
// Errors name the file, the line and the problem.
Result<TerrainCosts> parseCostTable(std::string_view text, std::string_view sourceName);
// Through readFileCapped: at most kScenFileLimit bytes, regular files only.
Result<TerrainCosts> loadCostTable(const std::filesystem::path& file);

// Checks the queries against the map they are run on: declared size matches, coordinates
// inside. Errors name the scen file and line.
Status checkScenAgainstMap(const std::vector<ScenQuery>& queries, const GridMap& map,
                           std::string_view scenName);

}  // namespace warpath::pathing
