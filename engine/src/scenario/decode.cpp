// The only user of yaml-cpp: YAML nodes into raw structs, failing at the node concerned.
#include "engine/src/scenario/decode.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <initializer_list>
#include <type_traits>
#include <unordered_map>

namespace warpath::engine::decode {
namespace {

using raw::Field;
using raw::Maybe;

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  static raw::Mark mark(const YAML::Mark& m) { return {m.line + 1, m.column + 1}; }
  static raw::Mark mark(const YAML::Node& node) { return mark(node.Mark()); }

  [[noreturn]] void fail(raw::Mark at, const std::string& message) const {
    throw Error{file_, at.line, at.column, message};
  }
  [[noreturn]] void fail(const YAML::Mark& at, const std::string& message) const {
    fail(mark(at), message);
  }
  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    fail(node.Mark(), message);
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
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string list;
      for (std::string_view a : allowed)
        list += (list.empty() ? "" : ", ") + std::string(a);
      fail(entry.first,
           "unknown key '" + key + "' in " + what + " (expected one of: " + list + ")");
    }
  }
  YAML::Node need(const YAML::Node& node, const char* key, const std::string& what) const {
    const YAML::Node value = node[key];
    if (!value) fail(node, what + " needs '" + key + "'");
    return value;
  }

  template <class T>
  Field<T> as(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a single value");
    try {
      return {node.as<T>(), mark(node)};
    } catch (const YAML::Exception&) {
      fail(node, what + ": cannot read '" + node.Scalar() + "' as " +
                     (std::is_integral_v<T> ? "an integer" : "a number"));
    }
  }
  Field<double> number(const YAML::Node& node, const std::string& what) const {
    return as<double>(node, what);
  }
  Field<int> integer(const YAML::Node& node, const std::string& what) const {
    return as<int>(node, what);
  }
  Field<bool> boolean(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a single value");
    bool v = false;
    if (!YAML::convert<bool>::decode(node, v))
      fail(node, what + " must be true or false, not '" + node.Scalar() + "'");
    return {v, mark(node)};
  }
  Field<std::string> text(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a single value");
    return {node.Scalar(), mark(node)};
  }
  // A name from one of the schema's EnumNames tables, else "unknown <kind> 'x' (<list>)".
  template <class Table>
  auto named(const YAML::Node& node, const std::string& what, const Table& table,
             const std::string& kind, const std::string& list) const
      -> Field<typename std::remove_cvref_t<decltype(table.rows()[0].value)>> {
    const Field<std::string> name = text(node, what);
    const auto value = table.parse(name.value);
    if (!value) fail(node, "unknown " + kind + " '" + name.value + "' (" + list + ")");
    return {*value, name.mark};
  }

  // The optional key `key` of `node` read by `read`, or nothing when it is absent.
  template <class Read>
  auto maybe(const YAML::Node& node, const char* key, Read read) const
      -> std::optional<decltype(read(node))> {
    if (const YAML::Node value = node[key]) return read(value);
    return std::nullopt;
  }
  Maybe<double> maybeNumber(const YAML::Node& node, const char* key,
                            const std::string& what) const {
    return maybe(node, key, [&](const YAML::Node& v) { return number(v, what); });
  }
  Maybe<int> maybeInteger(const YAML::Node& node, const char* key, const std::string& what) const {
    return maybe(node, key, [&](const YAML::Node& v) { return integer(v, what); });
  }
  Maybe<bool> maybeBoolean(const YAML::Node& node, const char* key, const std::string& what) const {
    return maybe(node, key, [&](const YAML::Node& v) { return boolean(v, what); });
  }
  Maybe<std::string> maybeText(const YAML::Node& node, const char* key,
                               const std::string& what) const {
    return maybe(node, key, [&](const YAML::Node& v) { return text(v, what); });
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

// ---- bounds on what the file expands to -------------------------------------------------------

// yaml-cpp keeps one node for an anchor and every alias of it, but reading walks each alias in
// full: an 80 KB file can stand for an 8192x8192 map or millions of groups. The limits are
// checked before anything is built from the file (docs/scenarios.md, "Limits").
constexpr int kMaxNesting = 64;                 // levels of mappings and lists
constexpr std::size_t kMaxYamlNodes = 250'000;  // nodes, every alias counted in full
constexpr std::size_t kMaxListEntries = 1'000;  // entries of one list or mapping (map rows: cells)
constexpr std::size_t kMaxInlineMapCells = std::size_t{1} << 20;  // 1024x1024
constexpr long long kMaxUnits = 20'000;  // the sum of every group's count, reinforcements included

// Walks the document as it will be read, aliases expanded, and fails at the first node past a
// limit. `key` is the mapping key the node sits under (empty at the root), to name the list in
// messages.
void checkExpansion(const Reader& r, const YAML::Node& node, const std::string& key, int depth,
                    std::size_t& nodes) {
  if (++nodes > kMaxYamlNodes)
    r.fail(node, "the file expands to more than " + std::to_string(kMaxYamlNodes) +
                     " YAML nodes (anchors and aliases repeat what they name)");
  if (depth > kMaxNesting)
    r.fail(node, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
  if (!node.IsSequence() && !node.IsMap()) return;
  if (key != "rows" && node.size() > kMaxListEntries)
    r.fail(node, (key.empty() ? "the file" : "'" + key + "'") + " has " +
                     std::to_string(node.size()) + " entries, more than the " +
                     std::to_string(kMaxListEntries) + " allowed");
  if (node.IsSequence()) {
    for (const auto& item : node)
      checkExpansion(r, item, key, depth + 1, nodes);
    return;
  }
  // YAML forbids a key twice in one mapping; yaml-cpp keeps the first and drops the rest
  // unread, so a setting added at the end of a file would silently not apply.
  std::unordered_map<std::string, int> lineOf;
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) continue;
    const auto [at, added] = lineOf.try_emplace(entry.first.Scalar(), entry.first.Mark().line + 1);
    if (!added)
      r.fail(entry.first, "duplicate key '" + at->first + "' (first at line " +
                              std::to_string(at->second) + ")");
  }
  for (const auto& entry : node) {
    checkExpansion(r, entry.first, key, depth + 1, nodes);
    const std::string inner = entry.first.IsScalar() ? entry.first.Scalar() : key;
    checkExpansion(r, entry.second, inner, depth + 1, nodes);
  }
}

YAML::Node load(const Reader& r, std::string_view text) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::DeepRecursion& e) {
    r.fail(e.mark, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
  } catch (const YAML::ParserException& e) {
    r.fail(e.mark, e.msg);
  }
  std::size_t nodes = 0;
  checkExpansion(r, root, "", 0, nodes);
  return root;
}

// Runs `decode` with yaml-cpp's own exceptions (a conversion deep inside, say) as Errors.
template <class Decode>
auto guarded(const std::string& file, Decode decode) -> decltype(decode()) {
  try {
    return decode();
  } catch (const YAML::Exception& e) {
    throw Error{file, e.mark.line + 1, e.mark.column + 1, e.msg};
  }
}

// ---- the schema's names --------------------------------------------------------------------

Field<units::ArmourClass> armourClass(const Reader& r, const YAML::Node& node,
                                      const std::string& what) {
  return r.named(node, what, units::kArmourClassNames, "armour class",
                 units::kArmourClassNames.list());
}

Field<units::DamageKind> damageKind(const Reader& r, const YAML::Node& node,
                                    const std::string& what) {
  return r.named(node, what, units::kDamageKindNames, "damage kind",
                 units::kDamageKindNames.list());
}

// `ground` or `[ground, swamp]` (or "ground,swamp").
Field<pathing::Capability> capability(const Reader& r, const YAML::Node& node) {
  std::string joined;
  if (node.IsSequence()) {
    for (const auto& item : node)
      joined += (joined.empty() ? "" : ",") + r.text(item, "capability").value;
  } else {
    joined = r.text(node, "capability").value;
  }
  const Result<pathing::Capability> c = pathing::parseCapability(joined);
  if (!c) r.fail(node, "capability: " + c.error().describe());
  return {c.value(), Reader::mark(node)};
}

// ---- pieces used in several places -----------------------------------------------------------

template <class Decode>
auto list(const Reader& r, const YAML::Node& node, const std::string& what, Decode decode)
    -> std::vector<decltype(decode(node))> {
  if (!node.IsSequence()) r.fail(node, what + " must be a list");
  std::vector<decltype(decode(node))> out;
  for (const auto& item : node)
    out.push_back(decode(item));
  return out;
}

raw::Area area(const Reader& r, const YAML::Node& node, const std::string& what) {
  r.checkKeys(node, what, {"x", "y", "w", "h"});
  return {Reader::mark(node), r.integer(r.need(node, "x", what), what + " x"),
          r.integer(r.need(node, "y", what), what + " y"),
          r.integer(r.need(node, "w", what), what + " w"),
          r.integer(r.need(node, "h", what), what + " h")};
}

// `GROUP` or `[GROUP, ...]`.
raw::Names groupNames(const Reader& r, const YAML::Node& node, const std::string& what) {
  raw::Names names;
  if (node.IsSequence()) {
    if (node.size() == 0) r.fail(node, what + " needs at least one group");
    for (const auto& item : node)
      names.items.push_back(r.text(item, "group"));
  } else {
    names.items.push_back(r.text(node, "group"));
  }
  return names;
}

// ---- unit types ----------------------------------------------------------------------------

raw::Weapon weapon(const Reader& r, const YAML::Node& node, const std::string& what) {
  raw::Weapon w;
  w.mark = Reader::mark(node);
  if (node.IsScalar()) {
    if (node.Scalar() != "none")
      r.fail(node, what +
                       " must be 'none' or a mapping {name, kind, damage, range, cooldown, "
                       "projectile_speed, targets, priority}");
    w.none = true;
    return w;
  }
  r.checkKeys(
      node, what,
      {"name", "kind", "damage", "range", "cooldown", "projectile_speed", "targets", "priority"});
  w.name = r.maybeText(node, "name", what + " name");
  w.kind =
      r.maybe(node, "kind", [&](const YAML::Node& v) { return damageKind(r, v, what + " kind"); });
  w.damage = r.maybeInteger(node, "damage", what + " damage");
  w.range = r.maybeNumber(node, "range", what + " range");
  w.cooldown = r.maybeNumber(node, "cooldown", what + " cooldown");
  w.projectileSpeed = r.maybeNumber(node, "projectile_speed", what + " projectile_speed");
  if (const YAML::Node targets = node["targets"]) {
    units::TargetMask mask;
    const auto add = [&](const YAML::Node& item) {
      mask.bits = static_cast<std::uint8_t>(
          mask.bits | units::TargetMask::of({armourClass(r, item, what + " targets").value}).bits);
    };
    if (targets.IsSequence()) {
      for (const auto& item : targets)
        add(item);
    } else {
      add(targets);
    }
    w.targets = Field<units::TargetMask>{mask, Reader::mark(targets)};
  }
  if (const YAML::Node priority = node["priority"]) {
    r.expectMap(priority, what + " priority");
    for (const auto& entry : priority)
      w.priority.emplace_back(armourClass(r, entry.first, what + " priority"),
                              r.integer(entry.second, what + " priority rank"));
  }
  return w;
}

raw::Speed speed(const Reader& r, const YAML::Node& node, const std::string& what) {
  raw::Speed s;
  s.mark = Reader::mark(node);
  if (!node.IsMap()) {
    s.all = r.number(node, what + " speed");
    return s;
  }
  for (const auto& entry : node) {
    const Field<std::string> name = r.text(entry.first, "terrain");
    const std::optional<pathing::Terrain> t = pathing::terrainFromName(name.value);
    if (!t || !pathing::isTraversable(*t))
      r.fail(entry.first, "unknown terrain '" + name.value + "'");
    s.perTerrain.emplace_back(Field<pathing::Terrain>{*t, name.mark},
                              r.number(entry.second, what + " speed"));
  }
  return s;
}

raw::UnitType unitType(const Reader& r, const YAML::Node& key, const YAML::Node& node) {
  raw::UnitType t;
  t.name = r.text(key, "unit type name");
  t.mark = Reader::mark(node);
  const std::string what = "unit type '" + t.name.value + "'";
  r.checkKeys(node, what,
              {"size", "capability", "speed", "acceleration", "turn_rate", "radius", "hp", "armour",
               "weapon"});
  t.size = r.maybeInteger(node, "size", what + " size");
  t.capability = r.maybe(node, "capability", [&](const YAML::Node& v) { return capability(r, v); });
  t.speed = r.maybe(node, "speed", [&](const YAML::Node& v) { return speed(r, v, what); });
  t.acceleration = r.maybeNumber(node, "acceleration", what + " acceleration");
  t.turnRate = r.maybeNumber(node, "turn_rate", what + " turn_rate");
  t.radius = r.maybeNumber(node, "radius", what + " radius");
  t.hp = r.maybeInteger(node, "hp", what + " hp");
  t.armour = r.maybe(node, "armour",
                     [&](const YAML::Node& v) { return armourClass(r, v, what + " armour"); });
  t.weapon =
      r.maybe(node, "weapon", [&](const YAML::Node& v) { return weapon(r, v, what + " weapon"); });
  return t;
}

std::vector<raw::UnitType> unitTypes(const Reader& r, const YAML::Node& node) {
  r.expectMap(node, "unit_types");
  std::vector<raw::UnitType> types;
  for (const auto& entry : node)
    types.push_back(unitType(r, entry.first, entry.second));
  return types;
}

// ---- settings ------------------------------------------------------------------------------

raw::Timing timing(const Reader& r, const YAML::Node& root) {
  raw::Timing t;
  t.tickRate = r.maybeNumber(root, "tick_rate", "tick_rate");
  t.duration = r.number(r.need(root, "duration", "the scenario"), "duration");
  return t;
}

// `cooperative_search`: whether windows are searched inside the CPRA* corridor.
inline constexpr EnumNames<bool, 2> kCooperativeSearchNames{{{{true, "cpra"}, {false, "whca"}}}};

raw::Pathing pathing(const Reader& r, const YAML::Node& node) {
  r.checkKeys(node, "pathing",
              {"algo", "cluster_size", "levels", "level_two_size", "budget", "cache", "cooperative",
               "window", "cooperative_search", "corridor", "congestion", "terrain_costs", "sliced",
               "insertion"});
  raw::Pathing p;
  p.algorithm = r.maybe(node, "algo", [&](const YAML::Node& v) {
    return r.named(v, "algo", pathing::kAlgorithmNames, "algo", pathing::kAlgorithmNames.list());
  });
  p.clusterSize = r.maybeInteger(node, "cluster_size", "cluster_size");
  p.levels = r.maybeInteger(node, "levels", "levels");
  p.levelTwoSize = r.maybeInteger(node, "level_two_size", "level_two_size");
  p.budget = r.maybeInteger(node, "budget", "budget");
  p.cache = r.maybeInteger(node, "cache", "cache");
  p.cooperative = r.maybeBoolean(node, "cooperative", "cooperative");
  p.window = r.maybeInteger(node, "window", "window");
  p.corridorSearch = r.maybe(node, "cooperative_search", [&](const YAML::Node& v) {
    return r.named(v, "cooperative_search", kCooperativeSearchNames, "cooperative_search",
                   kCooperativeSearchNames.list());
  });
  p.corridor = r.maybeInteger(node, "corridor", "corridor");
  p.congestion = r.maybeBoolean(node, "congestion", "congestion");
  p.terrainCosts = r.maybeBoolean(node, "terrain_costs", "terrain_costs");
  p.sliced = r.maybeBoolean(node, "sliced", "sliced");
  p.insertion = r.maybe(node, "insertion", [&](const YAML::Node& v) {
    return r.named(v, "insertion", pathing::kInsertionModeNames, "insertion",
                   pathing::kInsertionModeNames.list());
  });
  return p;
}

raw::Stuck stuck(const Reader& r, const YAML::Node& node) {
  r.checkKeys(node, "stuck", {"seconds", "min_progress", "flag_after"});
  raw::Stuck s;
  s.seconds = r.maybeNumber(node, "seconds", "stuck seconds");
  s.minProgress = r.maybeNumber(node, "min_progress", "min_progress");
  s.flagAfter = r.maybeInteger(node, "flag_after", "flag_after");
  return s;
}

raw::Combat combat(const Reader& r, const YAML::Node& node) {
  r.checkKeys(
      node, "combat",
      {"enabled", "wreck_seconds", "wrecks_block", "sight_through_trees", "scan_every", "armour"});
  raw::Combat c;
  c.enabled = r.maybeBoolean(node, "enabled", "combat enabled");
  c.wreckSeconds = r.maybeNumber(node, "wreck_seconds", "wreck_seconds");
  c.wrecksBlock = r.maybeBoolean(node, "wrecks_block", "wrecks_block");
  c.sightThroughTrees = r.maybeInteger(node, "sight_through_trees", "sight_through_trees");
  c.scanEvery = r.maybeInteger(node, "scan_every", "scan_every");
  if (const YAML::Node armour = node["armour"]) {
    r.expectMap(armour, "combat armour");
    for (const auto& row : armour) {
      const Field<units::DamageKind> kind = damageKind(r, row.first, "combat armour");
      const std::string kindName(units::damageKindName(kind.value));
      r.expectMap(row.second, "combat armour " + kindName);
      for (const auto& cell : row.second) {
        const Field<units::ArmourClass> a = armourClass(r, cell.first, "combat armour");
        c.armour.push_back(
            {kind, a,
             r.integer(cell.second, "armour percent " + kindName + " vs " +
                                        std::string(units::armourClassName(a.value)))});
      }
    }
  }
  return c;
}

// ---- the map -------------------------------------------------------------------------------

raw::Map map(const Reader& r, const YAML::Node& node) {
  raw::Map m;
  if (node.IsScalar()) {
    m.file = r.text(node, "map");
    return m;
  }
  r.checkKeys(node, "map", {"rows"});
  const YAML::Node rows = r.need(node, "rows", "map");
  if (!rows.IsSequence() || rows.size() == 0) r.fail(rows, "map rows must be a non-empty list");
  m.rowsMark = Reader::mark(rows);
  // Aliases may repeat a row: the cells are counted before they are copied.
  const std::size_t width = r.text(rows[0], "map row").value.size();
  const auto tooMany = [&] {
    r.fail(rows, "the inline map has " + std::to_string(rows.size()) + " rows of " +
                     std::to_string(width) + " cells, more than the " +
                     std::to_string(kMaxInlineMapCells) + " cells allowed: give a .map file");
  };
  if (rows.size() > kMaxInlineMapCells / std::max<std::size_t>(width, 1)) tooMany();
  std::size_t cells = 0;
  for (const auto& row : rows) {
    m.rows.push_back(r.text(row, "map row"));
    cells += m.rows.back().value.size();
    if (cells > kMaxInlineMapCells) tooMany();
  }
  return m;
}

// ---- groups, orders, triggers, victory, expectations -----------------------------------------

raw::Group group(const Reader& r, const YAML::Node& node) {
  r.checkKeys(node, "a group", {"name", "team", "type", "count", "spawn", "goal", "reinforcement"});
  raw::Group g;
  g.mark = Reader::mark(node);
  g.name = r.maybeText(node, "name", "group name");
  g.team = r.text(r.need(node, "team", "a group"), "team");
  g.type = r.text(r.need(node, "type", "a group"), "unit type");
  g.count = r.integer(r.need(node, "count", "a group"), "count");
  g.spawn = area(r, r.need(node, "spawn", "a group"), "spawn");
  g.reinforcement = r.maybeBoolean(node, "reinforcement", "reinforcement");
  g.goal = r.maybe(node, "goal", [&](const YAML::Node& v) { return area(r, v, "goal"); });
  return g;
}

// The groups' counts add up to at most kMaxUnits, checked before any unit is placed.
void checkUnitTotal(const Reader& r, const std::vector<raw::Group>& groups) {
  long long total = 0;
  for (const raw::Group& g : groups) {
    if (g.count.value < 1) continue;  // out of range: the checks say so
    total += std::min<long long>(g.count.value, kMaxUnits + 1);
    if (total > kMaxUnits)
      r.fail(g.count.mark, "the groups have more than " + std::to_string(kMaxUnits) +
                               " units in all (the limit for one scenario)");
  }
}

// The keys `order` (default move), `group`, `move_to` and `target` of `node`; the caller has
// checked that no other key is there. `what` names the entry for "needs" messages.
raw::OrderAction orderAction(const Reader& r, const YAML::Node& node, const std::string& what) {
  raw::OrderAction a;
  a.order = {OrderKind::Move, Reader::mark(node)};
  if (const YAML::Node order = node["order"])
    a.order = r.named(order, "order", kOrderKindNames, "order",
                      "expected " + kOrderKindNames.list(", ", " or "));
  a.groups = groupNames(r, r.need(node, "group", what), "'group'");
  const std::string kindText = "order '" + std::string(kOrderKindNames.name(a.order.value)) + "'";
  switch (a.order.value) {
    case OrderKind::Move:
    case OrderKind::AttackMove:
      if (node["target"]) r.fail(node["target"], kindText + " takes 'move_to', not 'target'");
      a.moveTo = area(r, r.need(node, "move_to", kindText), "move_to");
      break;
    case OrderKind::Attack:
      if (node["move_to"]) r.fail(node["move_to"], kindText + " takes 'target', not 'move_to'");
      a.target = groupNames(r, r.need(node, "target", kindText), "'target'");
      break;
    case OrderKind::Hold:
    case OrderKind::Stop:
      for (const char* key : {"move_to", "target"}) {
        if (node[key]) r.fail(node[key], kindText + " takes neither 'move_to' nor 'target'");
      }
      break;
  }
  return a;
}

raw::Order order(const Reader& r, const YAML::Node& node) {
  r.checkKeys(node, "an order", {"at", "when", "group", "order", "move_to", "target"});
  raw::Order o;
  if (node["at"] && node["when"]) r.fail(node, "an order has either 'at' or 'when', not both");
  if (node["at"]) {
    o.at = r.number(node["at"], "at");
  } else {
    const YAML::Node when = r.need(node, "when", "an order (or 'at')");
    r.checkKeys(when, "when", {"arrived", "fraction"});
    o.arrived = r.text(r.need(when, "arrived", "when"), "group");
    o.fraction = r.maybeNumber(when, "fraction", "fraction");
  }
  o.action = orderAction(r, node, "an order");
  return o;
}

// A trigger's `when:`: exactly one condition.
raw::Condition condition(const Reader& r, const YAML::Node& when) {
  const std::string one =
      "exactly one of: at: SECONDS, arrived: {group, fraction}, team_below: {team, count}, "
      "enters: {group, area, count}, dies: {group, count}";
  if (!when.IsMap() || when.size() == 0) r.fail(when, "a trigger's 'when' is " + one);
  if (when.size() > 1)
    r.fail(when, "a trigger's 'when' has " + std::to_string(when.size()) + " conditions; give " +
                     one + " (use two triggers for either of two)");
  const auto entry = *when.begin();
  const YAML::Node body = entry.second;
  raw::Condition c;
  c.kind = r.named(entry.first, "condition", kTriggerKindNames, "trigger condition",
                   "expected " + kTriggerKindNames.list(", ", " or "));
  const auto count = [&](const std::string& what) { return r.maybeInteger(body, "count", what); };
  const auto group = [&](const char* what) { return r.text(r.need(body, "group", what), "group"); };
  switch (c.kind.value) {
    case TriggerKind::At:
      c.at = r.number(body, "at");
      break;
    case TriggerKind::Arrived:
      r.checkKeys(body, "arrived", {"group", "fraction"});
      c.group = group("arrived");
      c.fraction = r.maybeNumber(body, "fraction", "fraction");
      break;
    case TriggerKind::TeamBelow:
      r.checkKeys(body, "team_below", {"team", "count"});
      c.team = r.text(r.need(body, "team", "team_below"), "team");
      c.count = r.integer(r.need(body, "count", "team_below"), "team_below count");
      break;
    case TriggerKind::Enters:
      r.checkKeys(body, "enters", {"group", "area", "count"});
      c.group = group("enters");
      c.area = area(r, r.need(body, "area", "enters"), "enters area");
      c.count = count("enters count");
      break;
    case TriggerKind::Dies:
      r.checkKeys(body, "dies", {"group", "count"});
      c.group = group("dies");
      c.count = count("dies count");
      break;
  }
  return c;
}

// One entry of a trigger's `do:`.
raw::Action action(const Reader& r, const YAML::Node& node) {
  const std::string one =
      "an action is exactly one of: {order: KIND, group, move_to or target}, "
      "{reinforce: GROUP}, {end_battle: TEAM or none}, {set_terrain: {area, terrain}}";
  if (!node.IsMap()) r.fail(node, one);
  int kinds = 0;
  raw::Action a;
  for (const auto& row : kActionKindNames.rows()) {
    if (!node[std::string(row.name)]) continue;
    ++kinds;
    a.kind = row.value;
  }
  if (kinds != 1) r.fail(node, one);
  switch (a.kind) {
    case ActionKind::Order:
      r.checkKeys(node, "an order action", {"order", "group", "move_to", "target"});
      a.order = orderAction(r, node, "an order action");
      break;
    case ActionKind::Reinforce:
      r.checkKeys(node, "a reinforce action", {"reinforce"});
      a.name = r.text(node["reinforce"], "group");
      break;
    case ActionKind::EndBattle:
      r.checkKeys(node, "an end_battle action", {"end_battle"});
      a.name = r.text(node["end_battle"], "end_battle");
      break;
    case ActionKind::SetTerrain: {
      r.checkKeys(node, "a set_terrain action", {"set_terrain"});
      const YAML::Node body = node["set_terrain"];
      r.checkKeys(body, "set_terrain", {"area", "terrain"});
      a.area = area(r, r.need(body, "area", "set_terrain"), "set_terrain area");
      a.terrain = r.named(r.need(body, "terrain", "set_terrain"), "set_terrain terrain",
                          pathing::kTerrainNames, "terrain", pathing::kTerrainNames.list());
      break;
    }
  }
  return a;
}

raw::Trigger trigger(const Reader& r, const YAML::Node& node) {
  r.checkKeys(node, "a trigger", {"name", "when", "do"});
  raw::Trigger t;
  t.mark = Reader::mark(node);
  t.name = r.maybeText(node, "name", "trigger name");
  t.when = condition(r, r.need(node, "when", "a trigger"));
  const YAML::Node actions = r.need(node, "do", "a trigger");
  if (!actions.IsSequence() || actions.size() == 0)
    r.fail(actions, "a trigger's 'do' must be a non-empty list of actions");
  for (const auto& item : actions)
    t.actions.push_back(action(r, item));
  return t;
}

raw::Victory victory(const Reader& r, const YAML::Node& node) {
  const std::string one =
      "a victory condition is exactly one of: eliminate: TEAM, hold: {team, area, seconds}, "
      "exit: {team, area, count}";
  if (!node.IsMap() || node.size() != 1) r.fail(node, one);
  const auto entry = *node.begin();
  const YAML::Node body = entry.second;
  raw::Victory v;
  v.kind = r.named(entry.first, "victory condition", kVictoryKindNames, "victory condition",
                   "expected " + kVictoryKindNames.list(", ", " or "));
  switch (v.kind.value) {
    case VictoryKind::Eliminate:
      v.team = r.text(body, "team");
      break;
    case VictoryKind::HoldArea:
      r.checkKeys(body, "hold", {"team", "area", "seconds"});
      v.team = r.text(r.need(body, "team", "hold"), "team");
      v.area = area(r, r.need(body, "area", "hold"), "hold area");
      v.seconds = r.number(r.need(body, "seconds", "hold"), "hold seconds");
      break;
    case VictoryKind::Exit:
      r.checkKeys(body, "exit", {"team", "area", "count"});
      v.team = r.text(r.need(body, "team", "exit"), "team");
      v.area = area(r, r.need(body, "area", "exit"), "exit area");
      v.count = r.integer(r.need(body, "count", "exit"), "exit count");
      break;
  }
  return v;
}

raw::Expectation expectation(const Reader& r, const YAML::Node& node) {
  // Every expectation key: the kinds named by their own key, then the statistics.
  const std::string keys = kExpectationKindNames.list() + ", " + kStatKindNames.list(", ", " or ");
  if (!node.IsMap() || node.size() != 1) r.fail(node, "an expectation is one key, one of: " + keys);
  const auto entry = *node.begin();
  const YAML::Node body = entry.second;
  raw::Expectation e;
  e.key = r.text(entry.first, "expectation");
  if (const auto kind = kExpectationKindNames.parse(e.key.value)) {
    e.kind = *kind;
  } else if (const auto stat = kStatKindNames.parse(e.key.value)) {
    e.kind = ExpectationKind::Stat;
    e.stat = *stat;
  } else {
    r.fail(entry.first, "unknown expectation '" + e.key.value + "' (expected " + keys + ")");
  }
  const auto who = [&] {
    e.team = r.maybeText(body, "team", "team");
    e.type = r.maybeText(body, "type", "unit type");
  };
  switch (e.kind) {
    case ExpectationKind::ArrivalRate:
      r.checkKeys(body, "arrival_rate", {"team", "type", "at_least", "by"});
      e.threshold = r.number(r.need(body, "at_least", "arrival_rate"), "at_least");
      e.by = r.number(r.need(body, "by", "arrival_rate"), "by");
      who();
      break;
    case ExpectationKind::MaxStuck:
      e.count = r.integer(body, "max_stuck");
      break;
    case ExpectationKind::ArrivalTime:
    case ExpectationKind::Delay:
      r.checkKeys(body, e.key.value, {"team", "type", "percentile", "at_most"});
      e.percentile = r.number(r.need(body, "percentile", e.key.value), "percentile");
      e.threshold = r.number(r.need(body, "at_most", e.key.value), "at_most");
      who();
      break;
    case ExpectationKind::MaxWait:
      e.threshold = r.number(body, "max_wait");
      break;
    case ExpectationKind::MaxDeadlocks:
      e.count = r.integer(body, "max_deadlocks");
      break;
    case ExpectationKind::Winner:
      e.team = r.text(body, "winner");
      break;
    case ExpectationKind::Stat: {
      r.checkKeys(body, e.key.value, {"team", "type", "at_most", "at_least"});
      if (static_cast<bool>(body["at_most"]) == static_cast<bool>(body["at_least"]))
        r.fail(body, e.key.value + " needs exactly one of 'at_most' and 'at_least'");
      e.atMost = static_cast<bool>(body["at_most"]);
      const char* bound = e.atMost ? "at_most" : "at_least";
      e.threshold = r.number(body[bound], bound);
      who();
      break;
    }
  }
  return e;
}

raw::Settings settings(const Reader& r, const YAML::Node& root) {
  raw::Settings s;
  s.root = Reader::mark(root);
  s.seed =
      r.maybe(root, "seed", [&](const YAML::Node& v) { return r.as<std::uint64_t>(v, "seed"); });
  s.timing = timing(r, root);
  s.pathing = r.maybe(root, "pathing", [&](const YAML::Node& v) { return pathing(r, v); });
  s.stuck = r.maybe(root, "stuck", [&](const YAML::Node& v) { return stuck(r, v); });
  s.combat = r.maybe(root, "combat", [&](const YAML::Node& v) { return combat(r, v); });
  return s;
}

std::vector<Field<std::string>> teams(const Reader& r, const YAML::Node& root) {
  const YAML::Node teams = r.need(root, "teams", "the scenario");
  if (!teams.IsSequence() || teams.size() == 0) r.fail(teams, "teams must be a non-empty list");
  std::vector<Field<std::string>> names;
  for (const auto& team : teams)
    names.push_back(r.text(team, "team"));
  return names;
}

// The list under the optional key `key` of `root`, each entry read by `decode`.
template <class Decode>
auto optionalList(const Reader& r, const YAML::Node& root, const char* key, Decode decode)
    -> std::vector<decltype(decode(root))> {
  if (const YAML::Node node = root[key]) return list(r, node, key, decode);
  return {};
}

}  // namespace

struct ScenarioFile::Document {
  Reader r;
  YAML::Node root;

  // Runs `decode` on the reader and the root, yaml-cpp's own exceptions turned into Errors.
  template <class Decode>
  auto read(Decode decode) const {
    return guarded(r.file(), [&] { return decode(r, root); });
  }
};

ScenarioFile::ScenarioFile(std::string_view text, const std::string& file)
    : document_(std::make_unique<Document>(Document{Reader(file), {}})) {
  Document& d = *document_;
  d.root = guarded(file, [&] {
    YAML::Node root = load(d.r, text);
    d.r.checkKeys(
        root, "the scenario",
        {"name", "map", "catalogue", "unit_types", "seed", "tick_rate", "duration", "pathing",
         "stuck", "combat", "teams", "groups", "orders", "triggers", "victory", "expectations"});
    return root;
  });
}

ScenarioFile::~ScenarioFile() = default;

raw::Mark ScenarioFile::root() const {
  return Reader::mark(document_->root);
}

raw::Maybe<std::string> ScenarioFile::name() const {
  return document_->read(
      [](const Reader& r, const YAML::Node& root) { return r.maybeText(root, "name", "name"); });
}

raw::Map ScenarioFile::map() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    return decode::map(r, r.need(root, "map", "the scenario"));
  });
}

raw::Maybe<std::string> ScenarioFile::catalogue() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    return r.maybeText(root, "catalogue", "catalogue");
  });
}

std::vector<raw::UnitType> ScenarioFile::unitTypes() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    const YAML::Node types = root["unit_types"];
    return types ? decode::unitTypes(r, types) : std::vector<raw::UnitType>{};
  });
}

raw::Settings ScenarioFile::settings() const {
  return document_->read(decode::settings);
}

std::vector<Field<std::string>> ScenarioFile::teams() const {
  return document_->read(decode::teams);
}

std::vector<raw::Group> ScenarioFile::groups() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    std::vector<raw::Group> groups = list(r, r.need(root, "groups", "the scenario"), "groups",
                                          [&](const YAML::Node& v) { return decode::group(r, v); });
    checkUnitTotal(r, groups);
    return groups;
  });
}

std::vector<raw::Order> ScenarioFile::orders() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    return optionalList(r, root, "orders",
                        [&](const YAML::Node& v) { return decode::order(r, v); });
  });
}

std::vector<raw::Trigger> ScenarioFile::triggers() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    return optionalList(r, root, "triggers",
                        [&](const YAML::Node& v) { return decode::trigger(r, v); });
  });
}

std::vector<raw::Victory> ScenarioFile::victory() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    return optionalList(r, root, "victory",
                        [&](const YAML::Node& v) { return decode::victory(r, v); });
  });
}

std::vector<raw::Expectation> ScenarioFile::expectations() const {
  return document_->read([](const Reader& r, const YAML::Node& root) {
    return optionalList(r, root, "expectations",
                        [&](const YAML::Node& v) { return decode::expectation(r, v); });
  });
}

std::vector<raw::UnitType> catalogue(std::string_view text, const std::string& file) {
  const Reader r(file);
  return guarded(file, [&] {
    const YAML::Node root = load(r, text);
    r.checkKeys(root, "the catalogue", {"unit_types"});
    return unitTypes(r, r.need(root, "unit_types", "the catalogue"));
  });
}

raw::Timing timing(std::string_view text, const std::string& file) {
  const Reader r(file);
  return guarded(file, [&] {
    const YAML::Node root = load(r, text);
    r.expectMap(root, "the scenario");
    return timing(r, root);
  });
}

}  // namespace warpath::engine::decode
