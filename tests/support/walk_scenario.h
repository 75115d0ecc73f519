#pragma once
// The small scenario the CLI picture tests run: two infantry walk across an 8x5 map (the
// pictures' shape 8:5 at any size) in 5 s (150 ticks), and are expected to arrive.
// WARPATH_SOURCE_DIR (set by CMake) locates the bundled catalogue.

#include <filesystem>
#include <fstream>
#include <string_view>

namespace warpath::testing {

// Writes the scenario, named `name`, to `file`; returns `file`.
inline std::filesystem::path writeWalkScenario(const std::filesystem::path& file,
                                               std::string_view name = "walk") {
  std::ofstream(file) << "name: " << name
                      << "\n"
                         "map: {rows: ['........', '........', '..TT....', '........', "
                         "'........']}\n"
                         "catalogue: " WARPATH_SOURCE_DIR
                         "/assets/units.yaml\n"
                         "duration: 5\nteams: [blue]\n"
                         "groups:\n  - {name: g, team: blue, type: infantry, count: 2,"
                         " spawn: {x: 0, y: 0, w: 1, h: 5}, goal: {x: 6, y: 0, w: 2, h: 5}}\n"
                         "expectations:\n"
                         "  - arrival_rate: {team: blue, type: infantry, at_least: 1.0, by: 5}\n";
  return file;
}

}  // namespace warpath::testing
