#pragma once
// The smallest scenario the engine tests parse to check a settings key: one infantry unit on a
// 2x8 inline map, with `extra` (whole lines, e.g. "pathing: {sliced: true}\n") among its keys.

#include <string>

#include "engine/scenario.h"

namespace warpath::testing {

inline std::string oneUnitScenario(const std::string& extra) {
  return "map:\n  rows: ['........', '........']\ncatalogue: ../assets/units.yaml\n"
         "duration: 1\nteams: [blue]\n" +
         extra +
         "groups:\n  - {team: blue, type: infantry, count: 1, spawn: {x: 0, y: 0, w: 1, h: 1},"
         " goal: {x: 6, y: 0, w: 1, h: 1}}\n";
}

// oneUnitScenario(extra) parsed as a file of the source tree's scenarios/ folder.
inline Result<engine::Scenario> parseOneUnitScenario(const std::string& extra) {
  return engine::parseScenario(oneUnitScenario(extra),
                               std::string(WARPATH_SOURCE_DIR) + "/scenarios/test_input.yaml");
}

}  // namespace warpath::testing
