// The only user of yaml-cpp. Parsing throws Error internally (at the node it concerns)
// and the public functions turn it into a result.
#include "engine/scenario.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>

#include "pathing/map_io.h"
#include "pathing/planner.h"

namespace warpath::engine {

using namespace pathing;
namespace fs = std::filesystem;

std::int64_t Scenario::durationTicks() const {
  return static_cast<std::int64_t>(std::llround(duration * settings.tickRate));
}

namespace {

class Parser {
 public:
  Parser(fs::path file, const FileReader& files) : file_(std::move(file)), files_(files) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    const YAML::Mark mark = node.Mark();
    throw Error{file_.string(), mark.line + 1, mark.column + 1, message};
  }
  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& message) const {
    throw Error{file_.string(), mark.line + 1, mark.column + 1, message};
  }

  const fs::path& file() const { return file_; }
  fs::path resolve(const std::string& relative) const { return file_.parent_path() / relative; }
  // The contents of the file `node` names (resolved against the scenario's folder) through the
  // file reader; fails at `node` when it has none or cannot read it ("map: FILE: is a
  // directory"). `what` is "map" or "catalogue".
  std::pair<fs::path, std::string> referenced(const YAML::Node& node, const std::string& what,
                                              FileLimit limit) const {
    const fs::path file = resolve(text(node, what));
    Result<std::string> contents = files_(file, limit);
    if (!contents) {
      if (contents.error().message == kNoSuchFile)
        fail(node, what + " file '" + file.string() + "' not found");
      fail(node, what + ": " + contents.error().describe());
    }
    return {file, std::move(contents).value()};
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
  bool boolean(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a single value");
    bool v = false;
    if (!YAML::convert<bool>::decode(node, v))
      fail(node, what + " must be true or false, not '" + node.Scalar() + "'");
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

  // What checkReachable has worked out already: the map components a unit type can reach in an
  // area, and the (group, area) pairs found reachable. Aliases can repeat one order or goal
  // thousands of times; each is checked once.
  using AreaKey = std::tuple<int, int, int, int, int>;
  mutable std::map<AreaKey, std::set<std::uint32_t>> reachableComponents;
  mutable std::set<std::pair<std::string, AreaKey>> reachableGroups;

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
  const Result<Capability> c = parseCapability(joined);
  if (!c) p.fail(node, "capability: " + c.error().describe());
  return c.value();
}

units::ArmourClass parseArmourClass(const Parser& p, const YAML::Node& node,
                                    const std::string& what) {
  const std::string name = p.text(node, what);
  const std::optional<units::ArmourClass> a = units::armourClassFromName(name);
  if (!a)
    p.fail(node, "unknown armour class '" + name + "' (" + units::kArmourClassNames.list() + ")");
  return *a;
}

units::DamageKind parseDamageKind(const Parser& p, const YAML::Node& node,
                                  const std::string& what) {
  const std::string name = p.text(node, what);
  const std::optional<units::DamageKind> k = units::damageKindFromName(name);
  if (!k)
    p.fail(node, "unknown damage kind '" + name + "' (" + units::kDamageKindNames.list() + ")");
  return *k;
}

// `weapon:` of a unit type: `none`, or the fields to set. A type that already has a weapon
// keeps the fields not given; a new weapon needs kind, damage, range and cooldown.
void parseWeapon(const Parser& p, const YAML::Node& node, units::UnitType& type,
                 const std::string& owner) {
  const std::string what = owner + " weapon";
  if (node.IsScalar()) {
    if (node.Scalar() != "none")
      p.fail(node, what +
                       " must be 'none' or a mapping {name, kind, damage, range, cooldown, "
                       "projectile_speed, targets, priority}");
    type.weapon.reset();
    return;
  }
  p.checkKeys(
      node, what,
      {"name", "kind", "damage", "range", "cooldown", "projectile_speed", "targets", "priority"});
  units::Weapon w;
  if (type.weapon) {
    w = *type.weapon;
  } else {
    for (const char* key : {"kind", "damage", "range", "cooldown"})
      p.need(node, key, "a new " + what);
  }
  if (node["kind"]) {
    w.kind = parseDamageKind(p, node["kind"], what + " kind");
    if (!type.weapon && !node["name"]) w.name = std::string(units::damageKindName(w.kind));
  }
  if (node["name"]) w.name = p.text(node["name"], what + " name");
  if (node["damage"]) w.damage = p.integer(node["damage"], what + " damage", 0, 1000000);
  const auto positive = [&](const char* key, double hi) {
    const YAML::Node v = node[key];
    const double x = p.number(v, what + " " + key, 0.0, hi);
    if (!(x > 0.0)) p.fail(v, what + " " + key + " must be greater than 0");
    return x;
  };
  if (node["range"]) w.range = positive("range", 4096.0);
  if (node["cooldown"]) w.cooldown = positive("cooldown", 3600.0);
  if (node["projectile_speed"])
    w.projectileSpeed = p.number(node["projectile_speed"], what + " projectile_speed", 0.0, 1e6);
  if (const YAML::Node targets = node["targets"]) {
    units::TargetMask mask;
    if (targets.IsSequence()) {
      for (const auto& item : targets)
        mask.bits = static_cast<std::uint8_t>(
            mask.bits | units::TargetMask::of({parseArmourClass(p, item, what + " targets")}).bits);
    } else {
      mask = units::TargetMask::of({parseArmourClass(p, targets, what + " targets")});
    }
    if (mask.bits == 0) p.fail(targets, what + " targets must name at least one armour class");
    w.targets = mask;
  }
  if (const YAML::Node priority = node["priority"]) {
    p.expectMap(priority, what + " priority");
    for (const auto& entry : priority) {
      const units::ArmourClass a = parseArmourClass(p, entry.first, what + " priority");
      w.priority[static_cast<std::size_t>(a)] =
          static_cast<std::uint8_t>(p.integer(entry.second, what + " priority rank", 0, 255));
    }
  }
  const std::string problem = units::problemWith(w);
  if (!problem.empty()) p.fail(node, what + ": " + problem);
  type.weapon = std::move(w);
}

// Applies the fields present in `node` to `type` (a catalogue entry being overridden, or a
// new type).
void applyUnitFields(const Parser& p, const YAML::Node& node, units::UnitType& type) {
  const std::string what = "unit type '" + type.name + "'";
  p.checkKeys(node, what,
              {"size", "capability", "speed", "acceleration", "turn_rate", "radius", "hp", "armour",
               "weapon"});
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
  if (node["armour"]) type.armour = parseArmourClass(p, node["armour"], what + " armour");
  if (node["weapon"]) parseWeapon(p, node["weapon"], type, what);
}

// Reads `unit_types:` into `catalogue`: known names are overridden field by field, new ones
// need size, capability and speed (armour defaults by name, see units::defaultArmourFor, else
// infantry; no weapon unless given).
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
      type->armour = units::defaultArmourFor(name).value_or(units::ArmourClass::Infantry);
    }
    applyUnitFields(p, entry.second, *type);
    const std::string problem = units::problemWith(*type);
    if (!problem.empty()) p.fail(entry.second, "unit type '" + name + "': " + problem);
  }
}

// Bounds on what a scenario or catalogue may expand to. yaml-cpp keeps one node for an anchor
// and every alias of it, but reading walks each alias in full: an 80 KB file can stand for an
// 8192x8192 map or millions of groups. The limits are checked before anything is built from the
// file (docs/scenarios.md, "Limits").
constexpr int kMaxNesting = 64;                 // levels of mappings and lists
constexpr std::size_t kMaxYamlNodes = 250'000;  // nodes, every alias counted in full
constexpr std::size_t kMaxListEntries = 1'000;  // entries of one list or mapping (map rows: cells)
constexpr std::size_t kMaxInlineMapCells = std::size_t{1} << 20;  // 1024x1024
constexpr long long kMaxUnits = 20'000;  // the sum of every group's count, reinforcements included

// Walks the document as the parser will read it, aliases expanded, and fails at the first node
// past a limit. `key` is the mapping key the node sits under (empty at the root), to name the
// list in messages.
void checkExpansion(const Parser& p, const YAML::Node& node, const std::string& key, int depth,
                    std::size_t& nodes) {
  if (++nodes > kMaxYamlNodes)
    p.fail(node, "the file expands to more than " + std::to_string(kMaxYamlNodes) +
                     " YAML nodes (anchors and aliases repeat what they name)");
  if (depth > kMaxNesting)
    p.fail(node, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
  if (!node.IsSequence() && !node.IsMap()) return;
  if (key != "rows" && node.size() > kMaxListEntries)
    p.fail(node, (key.empty() ? "the file" : "'" + key + "'") + " has " +
                     std::to_string(node.size()) + " entries, more than the " +
                     std::to_string(kMaxListEntries) + " allowed");
  if (node.IsSequence()) {
    for (const auto& item : node)
      checkExpansion(p, item, key, depth + 1, nodes);
    return;
  }
  for (const auto& entry : node) {
    checkExpansion(p, entry.first, key, depth + 1, nodes);
    const std::string inner = entry.first.IsScalar() ? entry.first.Scalar() : key;
    checkExpansion(p, entry.second, inner, depth + 1, nodes);
  }
}

YAML::Node loadYaml(const Parser& p, std::string_view text) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::DeepRecursion& e) {
    p.fail(e.mark, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
  } catch (const YAML::ParserException& e) {
    p.fail(e.mark, e.msg);
  }
  std::size_t nodes = 0;
  checkExpansion(p, root, "", 0, nodes);
  return root;
}

// Before any unit is placed: the groups' counts (each read as parse() will) add up to at most
// kMaxUnits. Counts that do not read as integers are left for parse() to report.
void checkUnitTotal(const Parser& p, const YAML::Node& groups) {
  long long total = 0;
  for (const auto& node : groups) {
    if (!node.IsMap() || !node["count"] || !node["count"].IsScalar()) continue;
    long long count = 0;
    if (!YAML::convert<long long>::decode(node["count"], count) || count < 1) continue;
    total += std::min<long long>(count, kMaxUnits + 1);
    if (total > kMaxUnits)
      p.fail(node["count"], "the groups have more than " + std::to_string(kMaxUnits) +
                                " units in all (the limit for one scenario)");
  }
}

GridMap parseMapNode(const Parser& p, const YAML::Node& node) {
  if (node.IsScalar()) {
    const auto [file, contents] = p.referenced(node, "map", kMapFileLimit);
    Result<GridMap> map = parseMap(std::string_view(contents), file.string());
    if (!map) p.fail(node, "map: " + map.error().describe());
    return std::move(map).value();
  }
  p.checkKeys(node, "map", {"rows"});
  const YAML::Node rows = p.need(node, "rows", "map");
  if (!rows.IsSequence() || rows.size() == 0) p.fail(rows, "map rows must be a non-empty list");
  // Inline rows use the .map glyphs; reading them through the .map parser keeps one reader.
  // Aliases may repeat a row: the cells are counted before the map is built.
  const std::size_t width = p.text(rows[0], "map row").size();
  const auto tooMany = [&] {
    p.fail(rows, "the inline map has " + std::to_string(rows.size()) + " rows of " +
                     std::to_string(width) + " cells, more than the " +
                     std::to_string(kMaxInlineMapCells) + " cells allowed: give a .map file");
  };
  if (rows.size() > kMaxInlineMapCells / std::max<std::size_t>(width, 1)) tooMany();
  std::string text = "type octile\nheight " + std::to_string(rows.size()) + "\nwidth " +
                     std::to_string(width) + "\nmap\n";
  std::size_t cells = 0;
  for (const auto& row : rows) {
    const std::string glyphs = p.text(row, "map row");
    cells += glyphs.size();
    if (cells > kMaxInlineMapCells) tooMany();
    text += glyphs + "\n";
  }
  Result<GridMap> map = parseMap(std::string_view(text), "inline map");
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
  const Parser::AreaKey key{group.type, area.x, area.y, area.width, area.height};
  if (p.reachableGroups.contains({group.name, key})) return;
  const units::UnitType& type = s.catalogue[static_cast<std::size_t>(group.type)];
  const auto& components = s.grid->layer(type.agent()).components();
  const GridMap& map = s.grid->map();
  auto [found, isNew] = p.reachableComponents.try_emplace(key);
  std::set<std::uint32_t>& reachable = found->second;
  if (isNew) {
    for (int y = area.y; y < area.y + area.height; ++y) {
      for (int x = area.x; x < area.x + area.width; ++x) {
        if (s.grid->canStand(type.agent(), {x, y}))
          reachable.insert(components[map.indexOf({x, y})]);
      }
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
  p.reachableGroups.insert({group.name, key});
}

std::vector<std::string> groupNamesOf(const Scenario& s) {
  std::vector<std::string> names;
  for (const GroupSpec& g : s.groups)
    names.push_back(g.name);
  return names;
}

// A team name, or `none` (-1): the winner expectation and the end_battle action.
int teamOrNone(const Parser& p, const YAML::Node& node, const Scenario& s,
               const std::string& what) {
  if (p.text(node, what) == "none") return -1;
  const std::string name = node.Scalar();
  for (std::size_t i = 0; i < s.teams.size(); ++i) {
    if (s.teams[i] == name) return static_cast<int>(i);
  }
  std::string list;
  for (const std::string& n : s.teams)
    list += (list.empty() ? "" : ", ") + n;
  p.fail(node, "unknown team '" + name + "' in " + what + " (known: " + list + "; or none)");
}

// Every expectation key: the kinds named by their own key, then the statistics.
std::string expectationKeys() {
  return kExpectationKindNames.list() + ", " + kStatKindNames.list(", ", " or ");
}

Expectation parseExpectation(const Parser& p, const YAML::Node& node, const Scenario& s) {
  if (!node.IsMap() || node.size() != 1)
    p.fail(node, "an expectation is one key, one of: " + expectationKeys());
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
  } else if (kind == "winner") {
    e.kind = ExpectationKind::Winner;
    e.team = teamOrNone(p, body, s, "winner");
    e.text = "winner == " +
             (e.team < 0 ? std::string("none") : s.teams[static_cast<std::size_t>(e.team)]);
  } else if (const std::optional<StatKind> stat = kStatKindNames.parse(kind)) {
    p.checkKeys(body, kind, {"team", "type", "at_most", "at_least"});
    e.kind = ExpectationKind::Stat;
    e.stat = *stat;
    if (static_cast<bool>(body["at_most"]) == static_cast<bool>(body["at_least"]))
      p.fail(body, kind + " needs exactly one of 'at_most' and 'at_least'");
    e.atMost = static_cast<bool>(body["at_most"]);
    const char* bound = e.atMost ? "at_most" : "at_least";
    e.threshold = p.number(body[bound], bound, 0.0, 1e12);
    e.text = who(kind) + (e.atMost ? " <= " : " >= ") + Parser::fmtNumber(e.threshold);
  } else {
    p.fail(entry.first, "unknown expectation '" + kind + "' (expected " + expectationKeys() + ")");
  }
  return e;
}

// `GROUP` or `[GROUP, ...]`: at least one, none twice.
std::vector<int> parseGroupList(const Parser& p, const YAML::Node& node,
                                const std::vector<std::string>& names, const std::string& what) {
  std::vector<int> out;
  const auto add = [&](const YAML::Node& item) {
    const int g = indexOf(p, item, names, "group");
    if (std::find(out.begin(), out.end(), g) != out.end())
      p.fail(item, "group '" + names[static_cast<std::size_t>(g)] + "' named twice in " + what);
    out.push_back(g);
  };
  if (node.IsSequence()) {
    if (node.size() == 0) p.fail(node, what + " needs at least one group");
    for (const auto& item : node)
      add(item);
  } else {
    add(node);
  }
  return out;
}

// An Order action from the keys `order` (default move), `group`, `move_to` and `target` of
// `node` (the caller has checked that no other key is there).
ActionSpec parseOrderAction(const Parser& p, const YAML::Node& node, const Scenario& s,
                            const std::string& what) {
  const std::vector<std::string> groupNames = groupNamesOf(s);
  ActionSpec a;
  a.kind = ActionKind::Order;
  if (const YAML::Node order = node["order"]) {
    const std::string name = p.text(order, "order");
    const std::optional<OrderKind> kind = orderKindFromName(name);
    if (!kind)
      p.fail(order,
             "unknown order '" + name + "' (expected " + kOrderKindNames.list(", ", " or ") + ")");
    a.order = *kind;
  }
  a.groups = parseGroupList(p, p.need(node, "group", what), groupNames, "'group'");
  const std::string kindText = "order '" + std::string(toString(a.order)) + "'";
  if (a.order == OrderKind::Move || a.order == OrderKind::AttackMove) {
    if (node["target"]) p.fail(node["target"], kindText + " takes 'move_to', not 'target'");
    const YAML::Node moveTo = p.need(node, "move_to", kindText);
    a.area = parseArea(p, moveTo, s.grid->map(), "move_to");
    for (int g : a.groups)
      checkReachable(p, moveTo, s, s.groups[static_cast<std::size_t>(g)], a.area);
  } else if (a.order == OrderKind::Attack) {
    if (node["move_to"]) p.fail(node["move_to"], kindText + " takes 'target', not 'move_to'");
    const YAML::Node target = p.need(node, "target", kindText);
    a.targetGroups = parseGroupList(p, target, groupNames, "'target'");
    for (std::size_t i = 0; i < a.targetGroups.size(); ++i) {
      const GroupSpec& enemy = s.groups[static_cast<std::size_t>(a.targetGroups[i])];
      for (int g : a.groups) {
        const GroupSpec& own = s.groups[static_cast<std::size_t>(g)];
        if (own.team == enemy.team)
          p.fail(target.IsSequence() ? target[i] : target,
                 "attack target '" + enemy.name + "' is on team '" +
                     s.teams[static_cast<std::size_t>(enemy.team)] +
                     "', the team of ordered group '" + own.name + "': targets must be enemies");
      }
    }
  } else {
    for (const char* key : {"move_to", "target"}) {
      if (node[key]) p.fail(node[key], kindText + " takes neither 'move_to' nor 'target'");
    }
  }
  return a;
}

// A trigger's `when:`: exactly one condition.
void parseCondition(const Parser& p, const YAML::Node& when, const Scenario& s, TriggerSpec& t) {
  const std::string one =
      "exactly one of: at: SECONDS, arrived: {group, fraction}, team_below: {team, count}, "
      "enters: {group, area, count}, dies: {group, count}";
  if (!when.IsMap() || when.size() == 0) p.fail(when, "a trigger's 'when' is " + one);
  if (when.size() > 1)
    p.fail(when, "a trigger's 'when' has " + std::to_string(when.size()) + " conditions; give " +
                     one + " (use two triggers for either of two)");
  const std::vector<std::string> groupNames = groupNamesOf(s);
  const auto entry = *when.begin();
  const std::string kind = p.text(entry.first, "condition");
  const YAML::Node body = entry.second;
  // `count` of a group's units: 1 by default, at most the group's size.
  const auto groupCount = [&](const char* what) {
    if (!body["count"]) return 1;
    const GroupSpec& g = s.groups[static_cast<std::size_t>(t.group)];
    return p.integer(body["count"], std::string(what) + " count (group '" + g.name + "')", 1,
                     g.count);
  };
  if (kind == "at") {
    t.kind = TriggerKind::At;
    t.at = p.number(body, "at", 0.0, 1e6);
  } else if (kind == "arrived") {
    p.checkKeys(body, "arrived", {"group", "fraction"});
    t.kind = TriggerKind::Arrived;
    t.group = indexOf(p, p.need(body, "group", "arrived"), groupNames, "group");
    if (body["fraction"]) t.fraction = p.number(body["fraction"], "fraction", 0.0, 1.0);
  } else if (kind == "team_below") {
    p.checkKeys(body, "team_below", {"team", "count"});
    t.kind = TriggerKind::TeamBelow;
    t.team = indexOf(p, p.need(body, "team", "team_below"), s.teams, "team");
    t.count = p.integer(p.need(body, "count", "team_below"), "team_below count", 1, 100000000);
  } else if (kind == "enters") {
    p.checkKeys(body, "enters", {"group", "area", "count"});
    t.kind = TriggerKind::Enters;
    t.group = indexOf(p, p.need(body, "group", "enters"), groupNames, "group");
    t.area = parseArea(p, p.need(body, "area", "enters"), s.grid->map(), "enters area");
    t.count = groupCount("enters");
  } else if (kind == "dies") {
    p.checkKeys(body, "dies", {"group", "count"});
    t.kind = TriggerKind::Dies;
    t.group = indexOf(p, p.need(body, "group", "dies"), groupNames, "group");
    t.count = groupCount("dies");
  } else {
    p.fail(entry.first, "unknown trigger condition '" + kind + "' (expected " +
                            kTriggerKindNames.list(", ", " or ") + ")");
  }
}

// One entry of a trigger's `do:`. `reinforcedBy` holds, per group, the trigger that already
// brings it in (empty when none).
ActionSpec parseAction(const Parser& p, const YAML::Node& node, const Scenario& s,
                       const std::string& trigger, std::vector<std::string>& reinforcedBy) {
  const std::string one =
      "an action is exactly one of: {order: KIND, group, move_to or target}, "
      "{reinforce: GROUP}, {end_battle: TEAM or none}";
  if (!node.IsMap()) p.fail(node, one);
  const int kinds =
      (node["order"] ? 1 : 0) + (node["reinforce"] ? 1 : 0) + (node["end_battle"] ? 1 : 0);
  if (kinds != 1) p.fail(node, one);
  if (node["order"]) {
    p.checkKeys(node, "an order action", {"order", "group", "move_to", "target"});
    return parseOrderAction(p, node, s, "an order action");
  }
  ActionSpec a;
  if (const YAML::Node reinforce = node["reinforce"]) {
    p.checkKeys(node, "a reinforce action", {"reinforce"});
    a.kind = ActionKind::Reinforce;
    a.group = indexOf(p, reinforce, groupNamesOf(s), "group");
    const GroupSpec& g = s.groups[static_cast<std::size_t>(a.group)];
    if (!g.reinforcement)
      p.fail(reinforce, "group '" + g.name +
                            "' is not a reinforcement group (it spawns at the start; give it "
                            "'reinforcement: true')");
    std::string& by = reinforcedBy[static_cast<std::size_t>(a.group)];
    if (!by.empty())
      p.fail(reinforce, "group '" + g.name + "' is already brought in by trigger '" + by + "'");
    by = trigger;
    return a;
  }
  p.checkKeys(node, "an end_battle action", {"end_battle"});
  a.kind = ActionKind::EndBattle;
  a.team = teamOrNone(p, node["end_battle"], s, "end_battle");
  return a;
}

VictorySpec parseVictory(const Parser& p, const YAML::Node& node, const Scenario& s) {
  const std::string one =
      "a victory condition is exactly one of: eliminate: TEAM, hold: {team, area, seconds}, "
      "exit: {team, area, count}";
  if (!node.IsMap() || node.size() != 1) p.fail(node, one);
  const auto entry = *node.begin();
  const std::string kind = p.text(entry.first, "victory condition");
  const YAML::Node body = entry.second;
  VictorySpec v;
  if (kind == "eliminate") {
    v.kind = VictoryKind::Eliminate;
    v.team = indexOf(p, body, s.teams, "team");
  } else if (kind == "hold") {
    p.checkKeys(body, "hold", {"team", "area", "seconds"});
    v.kind = VictoryKind::HoldArea;
    v.team = indexOf(p, p.need(body, "team", "hold"), s.teams, "team");
    v.area = parseArea(p, p.need(body, "area", "hold"), s.grid->map(), "hold area");
    v.seconds = p.number(p.need(body, "seconds", "hold"), "hold seconds", 0.0, 1e6);
  } else if (kind == "exit") {
    p.checkKeys(body, "exit", {"team", "area", "count"});
    v.kind = VictoryKind::Exit;
    v.team = indexOf(p, p.need(body, "team", "exit"), s.teams, "team");
    v.area = parseArea(p, p.need(body, "area", "exit"), s.grid->map(), "exit area");
    int units = 0;
    for (const GroupSpec& g : s.groups)
      units += g.team == v.team ? g.count : 0;
    const std::string& team = s.teams[static_cast<std::size_t>(v.team)];
    const YAML::Node count = p.need(body, "count", "exit");
    v.count = p.integer(count, "exit count", 1, 100000000);
    if (v.count > units)
      p.fail(count, "exit count " + std::to_string(v.count) + " is more than team '" + team +
                        "' has (" + std::to_string(units) + " units, reinforcements included)");
  } else {
    p.fail(entry.first, "unknown victory condition '" + kind + "' (expected " +
                            kVictoryKindNames.list(", ", " or ") + ")");
  }
  v.text = describe(v, s.teams);
  return v;
}

Result<std::vector<units::UnitType>> parseCatalogue(std::string_view text, const fs::path& file) {
  // A catalogue names no other files.
  const FileReader none = [](const fs::path& f, FileLimit) -> Result<std::string> {
    return Error{f.string(), 0, 0, std::string(kNoSuchFile)};
  };
  const Parser p(file, none);
  try {
    const YAML::Node root = loadYaml(p, text);
    p.checkKeys(root, "the catalogue", {"unit_types"});
    std::vector<units::UnitType> catalogue;
    parseUnitTypes(p, p.need(root, "unit_types", "the catalogue"), catalogue);
    return catalogue;
  } catch (const Error& e) {
    return e;
  } catch (const YAML::Exception& e) {
    return Error{file.string(), e.mark.line + 1, e.mark.column + 1, e.msg};
  }
}

Scenario parse(const Parser& p, std::string_view text) {
  const YAML::Node root = loadYaml(p, text);
  p.checkKeys(
      root, "the scenario",
      {"name", "map", "catalogue", "unit_types", "seed", "tick_rate", "duration", "pathing",
       "stuck", "combat", "teams", "groups", "orders", "triggers", "victory", "expectations"});
  Scenario s;
  s.file = p.file();
  s.name = root["name"] ? p.text(root["name"], "name") : p.file().stem().string();
  s.grid =
      std::make_shared<const AnnotatedGrid>(parseMapNode(p, p.need(root, "map", "the scenario")));
  const GridMap& map = s.grid->map();

  if (const YAML::Node cat = root["catalogue"]) {
    const auto [file, contents] = p.referenced(cat, "catalogue", kYamlFileLimit);
    Result<std::vector<units::UnitType>> loaded = parseCatalogue(contents, file);
    if (!loaded.ok()) throw loaded.error();
    s.catalogue = std::move(loaded).value();
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
        p.fail(pathing["algo"], "unknown algo '" + name + "' (" + kAlgorithmNames.list() + ")");
      s.settings.pathing.algorithm = *algo;
    }
    if (pathing["cluster_size"])
      s.settings.pathing.clusterSize =
          p.integer(pathing["cluster_size"], "cluster_size", 2, kMaxClusterSize);
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

  if (const YAML::Node combat = root["combat"]) {
    p.checkKeys(combat, "combat",
                {"enabled", "wreck_seconds", "sight_through_trees", "scan_every", "armour"});
    CombatSettings& c = s.settings.combat;
    if (combat["enabled"]) c.enabled = p.boolean(combat["enabled"], "combat enabled");
    if (combat["wreck_seconds"])
      c.wreckSeconds = p.number(combat["wreck_seconds"], "wreck_seconds", 0.0, 1e6);
    if (combat["sight_through_trees"])
      c.sight.maxTreeCells =
          p.integer(combat["sight_through_trees"], "sight_through_trees", -1, 1000000);
    if (combat["scan_every"])
      c.scanEveryTicks = p.integer(combat["scan_every"], "scan_every", 1, 1000000);
    if (const YAML::Node armour = combat["armour"]) {
      p.expectMap(armour, "combat armour");
      for (const auto& row : armour) {
        const units::DamageKind kind = parseDamageKind(p, row.first, "combat armour");
        const std::string kindName(units::damageKindName(kind));
        p.expectMap(row.second, "combat armour " + kindName);
        for (const auto& cell : row.second) {
          const units::ArmourClass a = parseArmourClass(p, cell.first, "combat armour");
          c.armour[static_cast<std::size_t>(kind)][static_cast<std::size_t>(a)] = p.integer(
              cell.second,
              "armour percent " + kindName + " vs " + std::string(units::armourClassName(a)), 0,
              1000);
        }
      }
    }
  }

  const YAML::Node teams = p.need(root, "teams", "the scenario");
  if (!teams.IsSequence() || teams.size() == 0) p.fail(teams, "teams must be a non-empty list");
  for (const auto& team : teams) {
    s.teams.push_back(p.text(team, "team"));
    if (s.teams.back() == "none")
      p.fail(team, "'none' cannot name a team (it means no team in winner and end_battle)");
    for (std::size_t i = 0; i + 1 < s.teams.size(); ++i) {
      if (s.teams[i] == s.teams.back()) p.fail(team, "team '" + s.teams.back() + "' given twice");
    }
  }

  const YAML::Node groups = p.need(root, "groups", "the scenario");
  if (!groups.IsSequence()) p.fail(groups, "groups must be a list");
  checkUnitTotal(p, groups);
  std::vector<std::uint8_t> occupied(map.cellCount(), 0);
  std::vector<std::string> groupNames;
  std::vector<YAML::Node> goalNodes;
  for (const auto& node : groups) {
    p.checkKeys(node, "a group",
                {"name", "team", "type", "count", "spawn", "goal", "reinforcement"});
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
    if (node["reinforcement"]) g.reinforcement = p.boolean(node["reinforcement"], "reinforcement");
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
      p.checkKeys(node, "an order", {"at", "when", "group", "order", "move_to", "target"});
      TriggerSpec o;
      o.name = "order " + std::to_string(s.triggers.size() + 1);
      if (node["at"] && node["when"]) p.fail(node, "an order has either 'at' or 'when', not both");
      if (node["at"]) {
        o.kind = TriggerKind::At;
        o.at = p.number(node["at"], "at", 0.0, 1e6);
      } else {
        const YAML::Node when = p.need(node, "when", "an order (or 'at')");
        p.checkKeys(when, "when", {"arrived", "fraction"});
        o.kind = TriggerKind::Arrived;
        o.group = indexOf(p, p.need(when, "arrived", "when"), groupNames, "group");
        if (when["fraction"]) o.fraction = p.number(when["fraction"], "fraction", 0.0, 1.0);
      }
      o.actions.push_back(parseOrderAction(p, node, s, "an order"));
      s.triggers.push_back(std::move(o));
    }
  }

  if (const YAML::Node triggers = root["triggers"]) {
    if (!triggers.IsSequence()) p.fail(triggers, "triggers must be a list");
    std::vector<std::string> reinforcedBy(s.groups.size());
    int number = 0;
    for (const auto& node : triggers) {
      ++number;
      p.checkKeys(node, "a trigger", {"name", "when", "do"});
      TriggerSpec t;
      t.name =
          node["name"] ? p.text(node["name"], "trigger name") : "trigger " + std::to_string(number);
      for (const TriggerSpec& other : s.triggers) {
        if (other.name == t.name)
          p.fail(node["name"] ? node["name"] : node, "trigger name '" + t.name + "' used twice");
      }
      parseCondition(p, p.need(node, "when", "a trigger"), s, t);
      const YAML::Node actions = p.need(node, "do", "a trigger");
      if (!actions.IsSequence() || actions.size() == 0)
        p.fail(actions, "a trigger's 'do' must be a non-empty list of actions");
      for (const auto& action : actions)
        t.actions.push_back(parseAction(p, action, s, t.name, reinforcedBy));
      s.triggers.push_back(std::move(t));
    }
  }

  if (const YAML::Node victory = root["victory"]) {
    if (!victory.IsSequence()) p.fail(victory, "victory must be a list");
    for (const auto& node : victory)
      s.victory.push_back(parseVictory(p, node, s));
  }

  if (const YAML::Node expectations = root["expectations"]) {
    if (!expectations.IsSequence()) p.fail(expectations, "expectations must be a list");
    for (const auto& node : expectations)
      s.expectations.push_back(parseExpectation(p, node, s));
  }
  return s;
}

}  // namespace

std::string_view toString(StatKind kind) {
  return kStatKindNames.name(kind);
}

std::string describe(const VictorySpec& v, const std::vector<std::string>& teams) {
  const std::string& team = teams[static_cast<std::size_t>(v.team)];
  switch (v.kind) {
    case VictoryKind::Eliminate:
      return team + " eliminates the others";
    case VictoryKind::HoldArea:
      return team + " holds " + describeRect(v.area) + " for " + Parser::fmtNumber(v.seconds) + "s";
    case VictoryKind::Exit:
      return std::to_string(v.count) + " of " + team + " exit at " + describeRect(v.area);
  }
  return team + " wins";
}

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

Result<std::string> readDiskFile(const fs::path& file, FileLimit limit) {
  return readFileCapped(file, limit);
}

Result<Scenario> parseScenario(std::string_view text, const fs::path& file) {
  return parseScenario(text, file, readDiskFile);
}

Result<Scenario> parseScenario(std::string_view text, const fs::path& file,
                               const FileReader& files) {
  try {
    return parse(Parser(file, files), text);
  } catch (const Error& e) {
    return e;
  } catch (const YAML::Exception& e) {
    return Error{file.string(), e.mark.line + 1, e.mark.column + 1, e.msg};
  }
}

Result<Scenario> loadScenario(const fs::path& file) {
  const Result<std::string> text = readDiskFile(file, kYamlFileLimit);
  if (!text) return text.error();
  return parseScenario(text.value(), file);
}

Result<std::int64_t> scenarioDurationTicks(std::string_view text, const fs::path& file) {
  const FileReader none = [](const fs::path& f, FileLimit) -> Result<std::string> {
    return Error{f.string(), 0, 0, std::string(kNoSuchFile)};
  };
  const Parser p(file, none);
  try {
    // The same keys and ranges as parse(); only the root's two scalars are looked at.
    const YAML::Node root = loadYaml(p, text);
    p.expectMap(root, "the scenario");
    Scenario s;
    if (root["tick_rate"])
      s.settings.tickRate = p.number(root["tick_rate"], "tick_rate", 1.0, 1000.0);
    s.duration = p.number(p.need(root, "duration", "the scenario"), "duration", 0.0, 1e6);
    return s.durationTicks();
  } catch (const Error& e) {
    return e;
  } catch (const YAML::Exception& e) {
    return Error{file.string(), e.mark.line + 1, e.mark.column + 1, e.msg};
  }
}

Result<std::vector<units::UnitType>> loadCatalogue(const fs::path& file) {
  const Result<std::string> text = readDiskFile(file, kYamlFileLimit);
  if (!text) return text.error();
  return parseCatalogue(text.value(), file);
}

}  // namespace warpath::engine
