// The only user of yaml-cpp. Parsing throws ScenarioError internally (at the node it concerns)
// and the public functions turn it into a result.
#include "engine/scenario.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <set>
#include <sstream>

#include "pathing/map_io.h"
#include "pathing/planner.h"

namespace warpath::engine {

using namespace pathing;
namespace fs = std::filesystem;

std::string ScenarioError::describe() const {
  if (line <= 0) return file + ": " + message;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message;
}

std::int64_t Scenario::durationTicks() const {
  return static_cast<std::int64_t>(std::llround(duration * settings.tickRate));
}

namespace {

class Parser {
 public:
  Parser(fs::path file, const FileReader& files) : file_(std::move(file)), files_(files) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    const YAML::Mark mark = node.Mark();
    throw ScenarioError{file_.string(), mark.line + 1, mark.column + 1, message};
  }
  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& message) const {
    throw ScenarioError{file_.string(), mark.line + 1, mark.column + 1, message};
  }

  const fs::path& file() const { return file_; }
  fs::path resolve(const std::string& relative) const { return file_.parent_path() / relative; }
  // The contents of the file `node` names (resolved against the scenario's folder) through the
  // file reader; fails at `node` when it has none. `what` is "map" or "catalogue".
  std::pair<fs::path, std::string> referenced(const YAML::Node& node,
                                              const std::string& what) const {
    const fs::path file = resolve(text(node, what));
    std::optional<std::string> contents = files_(file);
    if (!contents) fail(node, what + " file '" + file.string() + "' not found");
    return {file, std::move(*contents)};
  }

  void expectMap(const YAML::Node& node, const std::string& what) const {
    if (!node.IsMap()) fail(node, what + " must be a mapping");
  }
  // Rejects keys outside `allowed`, naming the first unknown one where it is written.
  void checkKeys(const YAML::Node& node, const std::string& what,
                 std::initializer_list<std::string_view> allowed) const {
    expectMap(node, what);
    for (const auto& entry : node) {
      const std::string key = entry.first.as<std::string>();
      bool known = false;
      for (std::string_view a : allowed)
        known = known || key == a;
      if (!known) {
        std::string list;
        for (std::string_view a : allowed)
          list += (list.empty() ? "" : ", ") + std::string(a);
        fail(entry.first,
             "unknown key '" + key + "' in " + what + " (expected one of: " + list + ")");
      }
    }
  }
  const YAML::Node need(const YAML::Node& node, const char* key, const std::string& what) const {
    const YAML::Node value = node[key];
    if (!value) fail(node, what + " needs '" + key + "'");
    return value;
  }

  template <class T>
  T as(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a single value");
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      fail(node, what + ": cannot read '" + node.Scalar() + "' as " +
                     (std::is_integral_v<T> ? "an integer" : "a number"));
    }
  }
  double number(const YAML::Node& node, const std::string& what, double lo, double hi) const {
    const double v = as<double>(node, what);
    if (!(v >= lo && v <= hi))
      fail(node, what + " must be between " + fmtNumber(lo) + " and " + fmtNumber(hi));
    return v;
  }
  int integer(const YAML::Node& node, const std::string& what, int lo, int hi) const {
    const int v = as<int>(node, what);
    if (v < lo || v > hi)
      fail(node, what + " must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return v;
  }
  std::string text(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a single value");
    return node.Scalar();
  }

  static std::string fmtNumber(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  }

 private:
  fs::path file_;
  const FileReader& files_;
};

Capability parseCapabilityNode(const Parser& p, const YAML::Node& node) {
  std::string joined;
  if (node.IsSequence()) {
    for (const auto& item : node)
      joined += (joined.empty() ? "" : ",") + p.text(item, "capability");
  } else {
    joined = p.text(node, "capability");
  }
  std::string error;
  const std::optional<Capability> c = parseCapability(joined, &error);
  if (!c) p.fail(node, "capability: " + error);
  return *c;
}

// Applies the fields present in `node` to `type` (a catalogue entry being overridden, or a
// new type).
void applyUnitFields(const Parser& p, const YAML::Node& node, units::UnitType& type) {
  const std::string what = "unit type '" + type.name + "'";
  p.checkKeys(node, what,
              {"size", "capability", "speed", "acceleration", "turn_rate", "radius", "hp"});
  if (node["size"]) type.size = p.integer(node["size"], what + " size", 1, 255);
  if (node["capability"]) type.capability = parseCapabilityNode(p, node["capability"]);
  if (const YAML::Node speed = node["speed"]) {
    if (speed.IsMap()) {
      for (const auto& entry : speed) {
        const std::string name = p.text(entry.first, "terrain");
        const std::optional<Terrain> t = terrainFromName(name);
        if (!t || !isTraversable(*t)) p.fail(entry.first, "unknown terrain '" + name + "'");
        type.speed[static_cast<std::size_t>(*t)] =
            p.number(entry.second, what + " speed", 0.0, 50.0);
      }
    } else {
      type.setSpeed(p.number(speed, what + " speed", 0.0, 50.0));
    }
  }
  if (node["acceleration"])
    type.acceleration = p.number(node["acceleration"], what + " acceleration", 0.0, 1000.0);
  if (node["turn_rate"])  // degrees per second in files, radians inside
    type.turnRate =
        p.number(node["turn_rate"], what + " turn_rate", 0.0, 36000.0) * std::numbers::pi / 180.0;
  if (node["radius"]) type.radius = p.number(node["radius"], what + " radius", 0.0, 128.0);
  if (node["hp"]) type.hp = p.integer(node["hp"], what + " hp", 1, 1000000);
}

// Reads `unit_types:` into `catalogue`: known names are overridden field by field, new ones
// need size, capability and speed.
void parseUnitTypes(const Parser& p, const YAML::Node& node,
                    std::vector<units::UnitType>& catalogue) {
  p.expectMap(node, "unit_types");
  for (const auto& entry : node) {
    const std::string name = p.text(entry.first, "unit type name");
    units::UnitType* type = nullptr;
    for (units::UnitType& t : catalogue)
      type = t.name == name ? &t : type;
    if (type == nullptr) {
      p.expectMap(entry.second, "unit type '" + name + "'");
      for (const char* key : {"size", "capability", "speed"})
        p.need(entry.second, key, "new unit type '" + name + "'");
      catalogue.push_back({});
      type = &catalogue.back();
      type->name = name;
    }
    applyUnitFields(p, entry.second, *type);
    const std::string problem = units::problemWith(*type);
    if (!problem.empty()) p.fail(entry.second, "unit type '" + name + "': " + problem);
  }
}

YAML::Node loadYaml(const Parser& p, std::string_view text) {
  try {
    return YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    p.fail(e.mark, e.msg);
  }
}

GridMap parseMapNode(const Parser& p, const YAML::Node& node) {
  if (node.IsScalar()) {
    const auto [file, contents] = p.referenced(node, "map");
    std::istringstream in(contents);
    Loaded<GridMap> map = parseMap(in, file.string());
    if (!map) p.fail(node, "map: " + map.error().describe());
    return std::move(map).value();
  }
  p.checkKeys(node, "map", {"rows"});
  const YAML::Node rows = p.need(node, "rows", "map");
  if (!rows.IsSequence() || rows.size() == 0) p.fail(rows, "map rows must be a non-empty list");
  // Inline rows use the .map glyphs; reading them through the .map parser keeps one reader.
  std::string text = "type octile\nheight " + std::to_string(rows.size()) + "\nwidth " +
                     std::to_string(p.text(rows[0], "map row").size()) + "\nmap\n";
  for (const auto& row : rows)
    text += p.text(row, "map row") + "\n";
  std::istringstream in(text);
  Loaded<GridMap> map = parseMap(in, "inline map");
  if (!map) {
    constexpr int kHeaderLines = 4;
    const int row = map.error().line - kHeaderLines - 1;
    if (row >= 0 && row < static_cast<int>(rows.size()))
      p.fail(rows[static_cast<std::size_t>(row)], "map row: " + map.error().message);
    p.fail(rows, "map: " + map.error().message);
  }
  return std::move(map).value();
}

CellRect parseArea(const Parser& p, const YAML::Node& node, const GridMap& map,
                   const std::string& what) {
  p.checkKeys(node, what, {"x", "y", "w", "h"});
  CellRect r;
  r.x = p.integer(p.need(node, "x", what), what + " x", 0, map.width() - 1);
  r.y = p.integer(p.need(node, "y", what), what + " y", 0, map.height() - 1);
  r.width = p.integer(p.need(node, "w", what), what + " w", 1, map.width() - r.x);
  r.height = p.integer(p.need(node, "h", what), what + " h", 1, map.height() - r.y);
  return r;
}

int indexOf(const Parser& p, const YAML::Node& node, const std::vector<std::string>& names,
            const std::string& what) {
  const std::string name = p.text(node, what);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  std::string list;
  for (const std::string& n : names)
    list += (list.empty() ? "" : ", ") + n;
  p.fail(node, "unknown " + what + " '" + name + "' (known: " + list + ")");
}

std::string describeRect(const CellRect& r) {
  return std::to_string(r.x) + "," + std::to_string(r.y) + " " + std::to_string(r.width) + "x" +
         std::to_string(r.height);
}

// Every spawn cell of `group` must reach some cell of `area` where its type can stand.
void checkReachable(const Parser& p, const YAML::Node& where, const Scenario& s,
                    const GroupSpec& group, const CellRect& area) {
  const units::UnitType& type = s.catalogue[static_cast<std::size_t>(group.type)];
  const auto& components = s.grid->layer(type.agent()).components();
  const GridMap& map = s.grid->map();
  std::set<std::uint32_t> reachable;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      if (s.grid->canStand(type.agent(), {x, y})) reachable.insert(components[map.indexOf({x, y})]);
    }
  }
  if (reachable.empty())
    p.fail(where, "goal area " + describeRect(area) + " has no cell where a " + type.name +
                      " (size " + std::to_string(type.size) + ", " + type.capability.toString() +
                      ") can stand");
  for (Cell c : group.anchors) {
    if (!reachable.contains(components[map.indexOf(c)]))
      p.fail(where, "goal area " + describeRect(area) + " is unreachable for " + type.name +
                        " of group '" + group.name + "' spawned at " + std::to_string(c.x) + "," +
                        std::to_string(c.y));
  }
}

Expectation parseExpectation(const Parser& p, const YAML::Node& node, const Scenario& s) {
  if (!node.IsMap() || node.size() != 1)
    p.fail(node,
           "an expectation is one of: arrival_rate: {...}, max_stuck: N, "
           "arrival_time: {...}");
  const auto entry = *node.begin();
  const std::string kind = p.text(entry.first, "expectation");
  const YAML::Node body = entry.second;
  std::vector<std::string> typeNames;
  for (const units::UnitType& t : s.catalogue)
    typeNames.push_back(t.name);
  Expectation e;
  const auto who = [&](const std::string& what) {
    if (body["team"]) e.team = indexOf(p, body["team"], s.teams, "team");
    if (body["type"]) e.type = indexOf(p, body["type"], typeNames, "unit type");
    return what + "(" + (e.team < 0 ? "*" : s.teams[static_cast<std::size_t>(e.team)]) + ", " +
           (e.type < 0 ? "*" : typeNames[static_cast<std::size_t>(e.type)]) + ")";
  };
  if (kind == "arrival_rate") {
    p.checkKeys(body, "arrival_rate", {"team", "type", "at_least", "by"});
    e.kind = ExpectationKind::ArrivalRate;
    e.threshold = p.number(p.need(body, "at_least", "arrival_rate"), "at_least", 0.0, 1.0);
    e.by = p.number(p.need(body, "by", "arrival_rate"), "by", 0.0, 1e6);
    e.text = who("arrival_rate") + " >= " + Parser::fmtNumber(e.threshold) + " by " +
             Parser::fmtNumber(e.by) + "s";
  } else if (kind == "max_stuck") {
    e.kind = ExpectationKind::MaxStuck;
    e.threshold = p.integer(body, "max_stuck", 0, 1000000);
    e.text = "max_stuck <= " + Parser::fmtNumber(e.threshold);
  } else if (kind == "arrival_time") {
    p.checkKeys(body, "arrival_time", {"team", "type", "percentile", "at_most"});
    e.kind = ExpectationKind::ArrivalTime;
    e.percentile = p.number(p.need(body, "percentile", "arrival_time"), "percentile", 0.0, 100.0);
    e.threshold = p.number(p.need(body, "at_most", "arrival_time"), "at_most", 0.0, 1e6);
    e.text = who("arrival_time") + " p" + Parser::fmtNumber(e.percentile) +
             " <= " + Parser::fmtNumber(e.threshold) + "s";
  } else {
    p.fail(entry.first,
           "unknown expectation '" + kind + "' (expected arrival_rate, max_stuck or arrival_time)");
  }
  return e;
}

ScenarioResult<std::vector<units::UnitType>> parseCatalogue(std::string_view text,
                                                            const fs::path& file) {
  // A catalogue names no other files.
  const FileReader none = [](const fs::path&) { return std::optional<std::string>(); };
  const Parser p(file, none);
  try {
    const YAML::Node root = loadYaml(p, text);
    p.checkKeys(root, "the catalogue", {"unit_types"});
    std::vector<units::UnitType> catalogue;
    parseUnitTypes(p, p.need(root, "unit_types", "the catalogue"), catalogue);
    return {std::move(catalogue), {}};
  } catch (const ScenarioError& e) {
    return {std::nullopt, e};
  } catch (const YAML::Exception& e) {
    return {std::nullopt, {file.string(), e.mark.line + 1, e.mark.column + 1, e.msg}};
  }
}

Scenario parse(const Parser& p, std::string_view text) {
  const YAML::Node root = loadYaml(p, text);
  p.checkKeys(root, "the scenario",
              {"name", "map", "catalogue", "unit_types", "seed", "tick_rate", "duration", "pathing",
               "stuck", "teams", "groups", "orders", "expectations"});
  Scenario s;
  s.file = p.file();
  s.name = root["name"] ? p.text(root["name"], "name") : p.file().stem().string();
  s.grid =
      std::make_shared<const AnnotatedGrid>(parseMapNode(p, p.need(root, "map", "the scenario")));
  const GridMap& map = s.grid->map();

  if (const YAML::Node cat = root["catalogue"]) {
    const auto [file, contents] = p.referenced(cat, "catalogue");
    ScenarioResult<std::vector<units::UnitType>> loaded = parseCatalogue(contents, file);
    if (!loaded.ok()) throw loaded.error;
    s.catalogue = std::move(*loaded.value);
  }
  if (root["unit_types"]) parseUnitTypes(p, root["unit_types"], s.catalogue);
  if (s.catalogue.empty()) p.fail(root, "no unit types: give 'catalogue' or 'unit_types'");
  std::vector<std::string> typeNames;
  for (const units::UnitType& t : s.catalogue)
    typeNames.push_back(t.name);

  if (root["seed"]) s.settings.seed = p.as<std::uint64_t>(root["seed"], "seed");
  if (root["tick_rate"])
    s.settings.tickRate = p.number(root["tick_rate"], "tick_rate", 1.0, 1000.0);
  s.duration = p.number(p.need(root, "duration", "the scenario"), "duration", 0.0, 1e6);
  if (const YAML::Node pathing = root["pathing"]) {
    p.checkKeys(pathing, "pathing", {"algo", "cluster_size", "budget", "cache"});
    if (pathing["algo"]) {
      const std::string name = p.text(pathing["algo"], "algo");
      const std::optional<Algorithm> algo = algorithmFromName(name);
      if (!algo)
        p.fail(pathing["algo"], "unknown algo '" + name + "' (aa, haa-hq, haa-lq, hybrid)");
      s.settings.pathing.algorithm = *algo;
    }
    if (pathing["cluster_size"])
      s.settings.pathing.clusterSize = p.integer(pathing["cluster_size"], "cluster_size", 2, 4096);
    if (pathing["budget"])
      s.settings.pathing.expansionBudget =
          static_cast<std::uint64_t>(p.integer(pathing["budget"], "budget", 1, 1000000000));
    if (pathing["cache"])
      s.settings.pathing.cacheCapacity =
          static_cast<std::size_t>(p.integer(pathing["cache"], "cache", 0, 100000000));
  }
  if (const YAML::Node stuck = root["stuck"]) {
    p.checkKeys(stuck, "stuck", {"seconds", "min_progress", "flag_after"});
    if (stuck["seconds"])
      s.settings.stuck.windowSeconds = p.number(stuck["seconds"], "stuck seconds", 0.01, 1e6);
    if (stuck["min_progress"])
      s.settings.stuck.minProgress = p.number(stuck["min_progress"], "min_progress", 0.0, 1e6);
    if (stuck["flag_after"])
      s.settings.stuck.flagAfter = p.integer(stuck["flag_after"], "flag_after", 1, 1000000);
  }

  const YAML::Node teams = p.need(root, "teams", "the scenario");
  if (!teams.IsSequence() || teams.size() == 0) p.fail(teams, "teams must be a non-empty list");
  for (const auto& team : teams) {
    s.teams.push_back(p.text(team, "team"));
    for (std::size_t i = 0; i + 1 < s.teams.size(); ++i) {
      if (s.teams[i] == s.teams.back()) p.fail(team, "team '" + s.teams.back() + "' given twice");
    }
  }

  const YAML::Node groups = p.need(root, "groups", "the scenario");
  if (!groups.IsSequence()) p.fail(groups, "groups must be a list");
  std::vector<std::uint8_t> occupied(map.cellCount(), 0);
  std::vector<std::string> groupNames;
  std::vector<YAML::Node> goalNodes;
  for (const auto& node : groups) {
    p.checkKeys(node, "a group", {"name", "team", "type", "count", "spawn", "goal"});
    GroupSpec g;
    g.name = node["name"] ? p.text(node["name"], "group name")
                          : "group" + std::to_string(s.groups.size() + 1);
    for (const std::string& other : groupNames) {
      if (other == g.name) p.fail(node["name"], "group '" + g.name + "' given twice");
    }
    g.team = indexOf(p, p.need(node, "team", "a group"), s.teams, "team");
    g.type = indexOf(p, p.need(node, "type", "a group"), typeNames, "unit type");
    g.count = p.integer(p.need(node, "count", "a group"), "count", 1, 1000000);
    const YAML::Node spawn = p.need(node, "spawn", "a group");
    g.spawn = parseArea(p, spawn, map, "spawn");
    const units::UnitType& type = s.catalogue[static_cast<std::size_t>(g.type)];
    g.anchors = placeUnits(*s.grid, type.agent(), g.spawn, g.count, occupied);
    if (static_cast<int>(g.anchors.size()) < g.count)
      p.fail(spawn, "spawn area " + describeRect(g.spawn) + " has room for only " +
                        std::to_string(g.anchors.size()) + " of " + std::to_string(g.count) + " " +
                        type.name + " (size " + std::to_string(type.size) + ", " +
                        type.capability.toString() + ") on terrain it can stand on");
    if (node["goal"]) {
      g.goal = parseArea(p, node["goal"], map, "goal");
      checkReachable(p, node["goal"], s, g, *g.goal);
    }
    groupNames.push_back(g.name);
    s.groups.push_back(std::move(g));
  }

  if (const YAML::Node orders = root["orders"]) {
    if (!orders.IsSequence()) p.fail(orders, "orders must be a list");
    for (const auto& node : orders) {
      p.checkKeys(node, "an order", {"at", "when", "group", "move_to"});
      OrderSpec o;
      if (node["at"] && node["when"]) p.fail(node, "an order has either 'at' or 'when', not both");
      if (node["at"]) {
        o.at = p.number(node["at"], "at", 0.0, 1e6);
      } else {
        const YAML::Node when = p.need(node, "when", "an order (or 'at')");
        p.checkKeys(when, "when", {"arrived", "fraction"});
        o.whenArrived = indexOf(p, p.need(when, "arrived", "when"), groupNames, "group");
        if (when["fraction"]) o.fraction = p.number(when["fraction"], "fraction", 0.0, 1.0);
      }
      const YAML::Node group = p.need(node, "group", "an order");
      if (group.IsSequence()) {
        for (const auto& g : group)
          o.groups.push_back(indexOf(p, g, groupNames, "group"));
      } else {
        o.groups.push_back(indexOf(p, group, groupNames, "group"));
      }
      const YAML::Node moveTo = p.need(node, "move_to", "an order");
      o.moveTo = parseArea(p, moveTo, map, "move_to");
      for (int g : o.groups)
        checkReachable(p, moveTo, s, s.groups[static_cast<std::size_t>(g)], o.moveTo);
      s.orders.push_back(std::move(o));
    }
  }

  if (const YAML::Node expectations = root["expectations"]) {
    if (!expectations.IsSequence()) p.fail(expectations, "expectations must be a list");
    for (const auto& node : expectations)
      s.expectations.push_back(parseExpectation(p, node, s));
  }
  return s;
}

}  // namespace

std::vector<Cell> placeUnits(const AnnotatedGrid& grid, Agent agent, CellRect area, int count,
                             std::vector<std::uint8_t>& occupied) {
  const GridMap& map = grid.map();
  std::vector<Cell> anchors;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      if (static_cast<int>(anchors.size()) >= count) return anchors;
      if (!grid.canStand(agent, {x, y})) continue;
      bool free = true;
      for (int dy = 0; dy < agent.size && free; ++dy) {
        for (int dx = 0; dx < agent.size && free; ++dx)
          free = occupied[map.indexOf({x + dx, y + dy})] == 0;
      }
      if (!free) continue;
      for (int dy = 0; dy < agent.size; ++dy) {
        for (int dx = 0; dx < agent.size; ++dx)
          occupied[map.indexOf({x + dx, y + dy})] = 1;
      }
      anchors.push_back({x, y});
    }
  }
  return anchors;
}

std::optional<std::string> readDiskFile(const fs::path& file) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream out;
  out << in.rdbuf();
  return std::move(out).str();
}

ScenarioResult<Scenario> parseScenario(std::string_view text, const fs::path& file) {
  return parseScenario(text, file, readDiskFile);
}

ScenarioResult<Scenario> parseScenario(std::string_view text, const fs::path& file,
                                       const FileReader& files) {
  try {
    return {parse(Parser(file, files), text), {}};
  } catch (const ScenarioError& e) {
    return {std::nullopt, e};
  } catch (const YAML::Exception& e) {
    return {std::nullopt, {file.string(), e.mark.line + 1, e.mark.column + 1, e.msg}};
  }
}

ScenarioResult<Scenario> loadScenario(const fs::path& file) {
  const std::optional<std::string> text = readDiskFile(file);
  if (!text) return {std::nullopt, {file.string(), 0, 0, "cannot open the scenario file"}};
  return parseScenario(*text, file);
}

ScenarioResult<std::vector<units::UnitType>> loadCatalogue(const fs::path& file) {
  const std::optional<std::string> text = readDiskFile(file);
  if (!text) return {std::nullopt, {file.string(), 0, 0, "cannot open the catalogue file"}};
  return parseCatalogue(*text, file);
}

}  // namespace warpath::engine
