#pragma once
// Decoding: scenario and catalogue YAML into the raw structs of engine/src/scenario/raw.h. The
// only user of yaml-cpp. Each function throws Error (file, line, column, message) at the first
// node that is malformed: YAML syntax, a bound on what anchors and aliases expand to (nesting,
// nodes, list entries, inline map cells, units; docs/scenarios.md "Limits"), an unknown or
// missing key, a value of the wrong shape or type, or an unknown name of the schema's own
// (terrain, armour class, damage kind, algo, order, trigger condition, action, victory
// condition, expectation). Whether the values make sense together is for the checks.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/src/scenario/raw.h"

namespace warpath::engine::decode {

// A scenario file read a section at a time, so that the checks can take the sections in the
// order the schema gives them (the map and the files it names first) and a problem in a later
// section is not reported before one in an earlier section. Opening it reads the YAML, checks
// the bounds on what it expands to and the top-level keys.
class ScenarioFile {
 public:
  ScenarioFile(std::string_view text, const std::string& file);
  ~ScenarioFile();
  ScenarioFile(const ScenarioFile&) = delete;
  ScenarioFile& operator=(const ScenarioFile&) = delete;

  raw::Mark root() const;
  raw::Maybe<std::string> name() const;
  raw::Map map() const;
  raw::Maybe<std::string> catalogue() const;
  std::vector<raw::UnitType> unitTypes() const;
  raw::Settings settings() const;
  std::vector<raw::Field<std::string>> teams() const;
  // The groups, their units counted (the bound on units holds before any is placed).
  std::vector<raw::Group> groups() const;
  std::vector<raw::Order> orders() const;
  std::vector<raw::Trigger> triggers() const;
  std::vector<raw::Victory> victory() const;
  std::vector<raw::Expectation> expectations() const;

 private:
  struct Document;
  std::unique_ptr<Document> document_;
};

// `text` read as the catalogue file `file`: its `unit_types`.
std::vector<raw::UnitType> catalogue(std::string_view text, const std::string& file);
// The `tick_rate` and `duration` of the scenario `text`, nothing else of it.
raw::Timing timing(std::string_view text, const std::string& file);

}  // namespace warpath::engine::decode
