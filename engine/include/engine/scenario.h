#pragma once
// Scenario and unit-catalogue files (YAML; the schema is in docs/scenarios.md). Loading checks
// everything a run needs up front: errors name the file, line and column and the problem.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/world.h"
#include "pathing/annotated_grid.h"
#include "units/unit_type.h"

namespace warpath::engine {

struct ScenarioError {
  std::string file;
  int line = 0;    // 1-based; 0 when not tied to a place in the file
  int column = 0;  // 1-based
  std::string message;
  // "file:line:column: message" (or "file: message").
  std::string describe() const;
};

enum class ExpectationKind : std::uint8_t {
  ArrivalRate,  // fraction of units (team, type) inside their goal area by `by` >= threshold
  MaxStuck,     // units ever flagged stuck <= threshold
  ArrivalTime,  // the `percentile` of time-to-arrive (team, type) <= threshold seconds
};

struct Expectation {
  ExpectationKind kind = ExpectationKind::ArrivalRate;
  int team = -1;  // index into Scenario::teams; -1: every team
  int type = -1;  // index into Scenario::catalogue; -1: every type
  double threshold = 0.0;
  double by = 0.0;          // [Unit: s] ArrivalRate
  double percentile = 0.0;  // [Limit: 0..100] ArrivalTime
  std::string text;         // as printed, e.g. "arrival_rate(blue, tank) >= 0.9 by 120s"
};

struct GroupSpec {
  std::string name;
  int team = 0;
  int type = 0;
  int count = 0;
  pathing::CellRect spawn;
  std::optional<pathing::CellRect> goal;
  std::vector<pathing::Cell> anchors;  // spawn cells, one per unit, chosen at load
};

struct OrderSpec {
  double at = -1.0;         // [Unit: s] when >= 0, the order is due at this time
  int whenArrived = -1;     // else: group whose arrivals trigger the order
  double fraction = 1.0;    // share of that group that must have arrived
  std::vector<int> groups;  // groups ordered
  pathing::CellRect moveTo;
};

struct Scenario {
  std::filesystem::path file;
  std::string name;
  std::shared_ptr<const pathing::AnnotatedGrid> grid;
  std::vector<units::UnitType> catalogue;
  std::vector<std::string> teams;
  WorldSettings settings;
  double duration = 60.0;  // [Unit: s]
  std::vector<GroupSpec> groups;
  std::vector<OrderSpec> orders;
  std::vector<Expectation> expectations;

  std::int64_t durationTicks() const;
};

template <class T>
struct ScenarioResult {
  std::optional<T> value;
  ScenarioError error;  // meaningful when !value
  bool ok() const { return value.has_value(); }
};

// Supplies the contents of a file a scenario names (its map, its catalogue), given the path
// resolved against the scenario's folder; nullopt when there is no such file. Replays pass one
// that answers from the files they embed, so a replay never reads the disk.
using FileReader = std::function<std::optional<std::string>(const std::filesystem::path&)>;
// The whole of a regular file on disk, or nullopt.
std::optional<std::string> readDiskFile(const std::filesystem::path& file);

// `text` is read as if it were the file `file` (relative paths resolve against its folder).
// Referenced files come from `files` (default: the disk).
ScenarioResult<Scenario> parseScenario(std::string_view text, const std::filesystem::path& file);
ScenarioResult<Scenario> parseScenario(std::string_view text, const std::filesystem::path& file,
                                       const FileReader& files);
ScenarioResult<Scenario> loadScenario(const std::filesystem::path& file);
// A catalogue file: `unit_types:` mapping type names to their fields.
ScenarioResult<std::vector<units::UnitType>> loadCatalogue(const std::filesystem::path& file);

// Up to `count` anchor cells in `area` where `agent` can stand, row-major, with footprints
// that overlap neither each other nor cells already marked in `occupied` (one byte per map
// cell; the chosen footprints are marked).
std::vector<pathing::Cell> placeUnits(const pathing::AnnotatedGrid& grid, pathing::Agent agent,
                                      pathing::CellRect area, int count,
                                      std::vector<std::uint8_t>& occupied);

}  // namespace warpath::engine
