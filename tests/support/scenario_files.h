#pragma once
// Scenarios the engine tests load: YAML text parsed as if it were a file (errors name it), and
// the bundled files under scenarios/. Needs WARPATH_SOURCE_DIR (the source tree).

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "engine/scenario.h"

namespace warpath::testing {

inline const std::string kScenariosDir = std::string(WARPATH_SOURCE_DIR) + "/scenarios/";

// `text` parsed as the file `file`; a parse error fails the calling test (an empty scenario
// comes back).
inline engine::Scenario parsedScenario(const std::string& text, const std::string& file) {
  Result<engine::Scenario> r = engine::parseScenario(text, file);
  EXPECT_TRUE(r.ok()) << r.error().describe() << "\n" << text;
  return r.ok() ? std::move(r).value() : engine::Scenario{};
}

// The error parsing `text` as the file `file` gives; accepting it fails the calling test.
inline Error scenarioError(const std::string& text, const std::string& file) {
  const Result<engine::Scenario> r = engine::parseScenario(text, file);
  EXPECT_FALSE(r.ok()) << text;
  return r.ok() ? Error{} : r.error();
}

// The bundled scenarios/`name`.yaml ("demo", "chokepoints/door_30v30").
inline engine::Scenario bundledScenario(const std::string& name) {
  Result<engine::Scenario> r = engine::loadScenario(kScenariosDir + name + ".yaml");
  EXPECT_TRUE(r.ok()) << r.error().describe();
  return r.ok() ? std::move(r).value() : engine::Scenario{};
}

}  // namespace warpath::testing
