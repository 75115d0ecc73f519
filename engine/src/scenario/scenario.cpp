// Scenario and catalogue files in two steps: decoding (engine/src/scenario/decode.cpp) reads
// the YAML into raw structs; the checks here give the values their meaning — ranges, the names
// of teams, types and groups, the map and where units fit on it, the settings' limits — and
// build the Scenario. Both throw Error at the place concerned; the public functions turn it
// into a result.
#include "engine/scenario.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>

#include "engine/src/scenario/decode.h"
#include "engine/src/scenario/raw.h"
#include "pathing/map_io.h"
#include "pathing/planner.h"

namespace warpath::engine {

using namespace pathing;
namespace fs = std::filesystem;

std::int64_t Scenario::durationTicks() const {
  return static_cast<std::int64_t>(std::llround(duration * settings.tickRate));
}

namespace {

std::string fmtNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string describeRect(const CellRect& r) {
  return std::to_string(r.x) + "," + std::to_string(r.y) + " " + std::to_string(r.width) + "x" +
         std::to_string(r.height);
}

// Fails at a raw value's mark; ranges and names.
class Checker {
 public:
  explicit Checker(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(raw::Mark at, const std::string& message) const {
    throw Error{file_, at.line, at.column, message};
  }
  double range(const raw::Field<double>& v, const std::string& what, double lo, double hi) const {
    if (!(v.value >= lo && v.value <= hi))
      fail(v.mark, what + " must be between " + fmtNumber(lo) + " and " + fmtNumber(hi));
    return v.value;
  }
  int range(const raw::Field<int>& v, const std::string& what, int lo, int hi) const {
    if (v.value < lo || v.value > hi)
      fail(v.mark, what + " must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return v.value;
  }
  // The index of `name` in `names`, else "unknown <what> 'x' (known: …)".
  int indexOf(const raw::Field<std::string>& name, const std::vector<std::string>& names,
              const std::string& what) const {
    const auto it = std::find(names.begin(), names.end(), name.value);
    if (it != names.end()) return static_cast<int>(it - names.begin());
    fail(name.mark, "unknown " + what + " '" + name.value + "' (known: " + joined(names) + ")");
  }
  // An area inside the map.
  CellRect area(const raw::Area& a, const GridMap& map, const std::string& what) const {
    CellRect r;
    r.x = range(a.x, what + " x", 0, map.width() - 1);
    r.y = range(a.y, what + " y", 0, map.height() - 1);
    r.width = range(a.w, what + " w", 1, map.width() - r.x);
    r.height = range(a.h, what + " h", 1, map.height() - r.y);
    return r;
  }

  static std::string joined(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& n : names)
      list += (list.empty() ? "" : ", ") + n;
    return list;
  }

 private:
  std::string file_;
};

// ---- a library's limits, reported at the key that set the field -----------------------------

// A field a problemWith function may name (its messages begin with the field's name), the
// scenario key that sets it and where that is written (none: the file leaves the default).
struct Setter {
  std::string field;
  std::string key;
  std::optional<raw::Mark> mark;
};

template <class T>
std::optional<raw::Mark> markOf(const raw::Maybe<T>& v) {
  return v ? std::optional(v->mark) : std::nullopt;
}

// Fails with `problem` (from a problemWith, not empty) at the key that set the field it names,
// the key's name in place of the field's, after `prefix`; at `fallback` when the file did not set
// that field (the problem then lies in a default or a value the file did not give here).
[[noreturn]] void failAtSetter(const Checker& c, std::string_view problem,
                               const std::vector<Setter>& setters, raw::Mark fallback,
                               const std::string& prefix) {
  const Setter* best = nullptr;
  for (const Setter& s : setters) {
    const bool names = problem.starts_with(s.field) &&
                       (problem.size() == s.field.size() || problem[s.field.size()] == ' ' ||
                        problem[s.field.size()] == ':');
    if (names && (best == nullptr || s.field.size() > best->field.size())) best = &s;
  }
  if (best == nullptr || !best->mark) c.fail(fallback, prefix + std::string(problem));
  c.fail(*best->mark, prefix + best->key + std::string(problem.substr(best->field.size())));
}

// ---- unit types ------------------------------------------------------------------------------

// Sets the fields of a weapon that `in` gives. A type that already has a weapon keeps the fields
// not given; a new weapon needs kind, damage, range and cooldown.
void applyWeapon(const Checker& c, const raw::Weapon& in, units::UnitType& type,
                 const std::string& what) {
  if (in.none) {
    type.weapon.reset();
    return;
  }
  units::Weapon w;
  if (type.weapon) {
    w = *type.weapon;
  } else {
    const std::pair<const char*, bool> required[] = {{"kind", in.kind.has_value()},
                                                     {"damage", in.damage.has_value()},
                                                     {"range", in.range.has_value()},
                                                     {"cooldown", in.cooldown.has_value()}};
    for (const auto& [key, given] : required) {
      if (!given) c.fail(in.mark, "a new " + what + " needs '" + key + "'");
    }
  }
  if (in.kind) {
    w.kind = in.kind->value;
    if (!type.weapon && !in.name) w.name = std::string(units::damageKindName(w.kind));
  }
  if (in.name) w.name = in.name->value;
  if (in.damage) w.damage = c.range(*in.damage, what + " damage", 0, 1000000);
  const auto positive = [&](const raw::Field<double>& v, const char* key, double hi) {
    const double x = c.range(v, what + " " + key, 0.0, hi);
    if (!(x > 0.0)) c.fail(v.mark, what + " " + key + " must be greater than 0");
    return x;
  };
  if (in.range) w.range = positive(*in.range, "range", 4096.0);
  if (in.cooldown) w.cooldown = positive(*in.cooldown, "cooldown", 3600.0);
  if (in.projectileSpeed)
    w.projectileSpeed = c.range(*in.projectileSpeed, what + " projectile_speed", 0.0, 1e6);
  if (in.targets) {
    if (in.targets->value.bits == 0)
      c.fail(in.targets->mark, what + " targets must name at least one armour class");
    w.targets = in.targets->value;
  }
  for (const auto& [armour, rank] : in.priority)
    w.priority[static_cast<std::size_t>(armour.value)] =
        static_cast<std::uint8_t>(c.range(rank, what + " priority rank", 0, 255));
  if (const std::string problem = units::problemWith(w); !problem.empty()) {
    failAtSetter(c, problem,
                 {{"damage", "damage", markOf(in.damage)},
                  {"range", "range", markOf(in.range)},
                  {"cooldown", "cooldown", markOf(in.cooldown)},
                  {"projectile_speed", "projectile_speed", markOf(in.projectileSpeed)},
                  {"targets", "targets", markOf(in.targets)}},
                 in.mark, what + ": ");
  }
  type.weapon = std::move(w);
}

// Sets the fields of `type` that `in` gives.
void applyUnitFields(const Checker& c, const raw::UnitType& in, units::UnitType& type) {
  const std::string what = "unit type '" + type.name + "'";
  if (in.size) type.size = c.range(*in.size, what + " size", 1, 255);
  if (in.capability) type.capability = in.capability->value;
  if (in.speed) {
    if (in.speed->all) type.setSpeed(c.range(*in.speed->all, what + " speed", 0.0, 50.0));
    for (const auto& [terrain, speed] : in.speed->perTerrain)
      type.speed[static_cast<std::size_t>(terrain.value)] =
          c.range(speed, what + " speed", 0.0, 50.0);
  }
  if (in.acceleration)
    type.acceleration = c.range(*in.acceleration, what + " acceleration", 0.0, 1000.0);
  if (in.turnRate)  // degrees per second in files, radians inside
    type.turnRate =
        c.range(*in.turnRate, what + " turn_rate", 0.0, 36000.0) * std::numbers::pi / 180.0;
  if (in.radius) type.radius = c.range(*in.radius, what + " radius", 0.0, 128.0);
  if (in.hp) type.hp = c.range(*in.hp, what + " hp", 1, 1000000);
  if (in.armour) type.armour = in.armour->value;
  if (in.weapon) applyWeapon(c, *in.weapon, type, what + " weapon");
}

// units::problemWith(type), reported at the key that set the field it names.
void checkUnitType(const Checker& c, const raw::UnitType& in, const units::UnitType& type) {
  const std::string problem = units::problemWith(type);
  if (problem.empty()) return;
  std::vector<Setter> setters = {
      {"size", "size", markOf(in.size)},
      {"capability", "capability", markOf(in.capability)},
      {"speed", "speed", in.speed ? std::optional(in.speed->mark) : std::nullopt},
      {"acceleration", "acceleration", markOf(in.acceleration)},
      {"turn_rate", "turn_rate", markOf(in.turnRate)},
      {"radius", "radius", markOf(in.radius)},
      {"hp", "hp", markOf(in.hp)},
      {"weapon", "weapon", in.weapon ? std::optional(in.weapon->mark) : std::nullopt}};
  if (in.speed) {
    for (const auto& [terrain, speed] : in.speed->perTerrain) {
      const std::string field = "speed on " + std::string(terrainName(terrain.value));
      setters.push_back({field, field, speed.mark});
    }
  }
  failAtSetter(c, problem, setters, in.mark, "unit type '" + type.name + "': ");
}

// Applies `unit_types:` to `catalogue`: known names are overridden field by field, new ones need
// size, capability and speed (armour defaults by name, see units::defaultArmourFor, else
// infantry; no weapon unless given).
void applyUnitTypes(const Checker& c, const std::vector<raw::UnitType>& types,
                    std::vector<units::UnitType>& catalogue) {
  for (const raw::UnitType& in : types) {
    const std::string& name = in.name.value;
    auto type = std::find_if(catalogue.begin(), catalogue.end(),
                             [&](const units::UnitType& t) { return t.name == name; });
    if (type == catalogue.end()) {
      const std::pair<const char*, bool> required[] = {{"size", in.size.has_value()},
                                                       {"capability", in.capability.has_value()},
                                                       {"speed", in.speed.has_value()}};
      for (const auto& [key, given] : required) {
        if (!given) c.fail(in.mark, "new unit type '" + name + "' needs '" + key + "'");
      }
      units::UnitType fresh;
      fresh.name = name;
      fresh.armour = units::defaultArmourFor(name).value_or(units::ArmourClass::Infantry);
      catalogue.push_back(std::move(fresh));
      type = catalogue.end() - 1;
    }
    applyUnitFields(c, in, *type);
    checkUnitType(c, in, *type);
  }
}

Result<std::vector<units::UnitType>> parseCatalogue(std::string_view text, const fs::path& file) {
  try {
    std::vector<units::UnitType> catalogue;
    applyUnitTypes(Checker(file.string()), decode::catalogue(text, file.string()), catalogue);
    return catalogue;
  } catch (const Error& e) {
    return e;
  }
}

// ---- settings --------------------------------------------------------------------------------

// `tick_rate` and `duration`: what a scenario's length in ticks follows from.
void applyTiming(const Checker& c, const raw::Timing& in, Scenario& s) {
  if (in.tickRate) s.settings.tickRate = c.range(*in.tickRate, "tick_rate", 1.0, 1000.0);
  s.duration = c.range(in.duration, "duration", 0.0, 1e6);
}

void applyPathing(const Checker& c, const raw::Pathing& in, PathServiceSettings& out) {
  if (in.algorithm) out.algorithm = in.algorithm->value;
  if (in.clusterSize)
    out.clusterSize = c.range(*in.clusterSize, "cluster_size", 2, kMaxClusterSize);
  if (in.levels) out.levels = c.range(*in.levels, "levels", 1, 2);
  if (in.levelTwoSize) out.levelTwoSize = c.range(*in.levelTwoSize, "level_two_size", 2, 256);
  if (in.budget)
    out.expansionBudget = static_cast<std::uint64_t>(c.range(*in.budget, "budget", 1, 1000000000));
  if (in.cache)
    out.cacheCapacity = static_cast<std::size_t>(c.range(*in.cache, "cache", 0, 100000000));
  if (in.cooperative) out.cooperative = in.cooperative->value;
  if (in.window) out.window = c.range(*in.window, "window", 1, kMaxCooperativeWindow);
  if (in.corridorSearch) out.corridorSearch = in.corridorSearch->value;
  if (in.corridor) out.corridor = c.range(*in.corridor, "corridor", 1, 64);
  if (in.congestion) out.congestion = in.congestion->value;
  if (in.terrainCosts) out.terrainCosts = in.terrainCosts->value;
  if (in.sliced) out.sliced = in.sliced->value;
  if (in.insertion) out.insertion = in.insertion->value;
}

void applyStuck(const Checker& c, const raw::Stuck& in, units::StuckRule& out) {
  if (in.seconds) out.windowSeconds = c.range(*in.seconds, "stuck seconds", 0.01, 1e6);
  if (in.minProgress) out.minProgress = c.range(*in.minProgress, "min_progress", 0.0, 1e6);
  if (in.flagAfter) out.flagAfter = c.range(*in.flagAfter, "flag_after", 1, 1000000);
}

void applyCombat(const Checker& c, const raw::Combat& in, CombatSettings& out) {
  if (in.enabled) out.enabled = in.enabled->value;
  if (in.wreckSeconds) out.wreckSeconds = c.range(*in.wreckSeconds, "wreck_seconds", 0.0, 1e6);
  if (in.wrecksBlock) out.wrecksBlock = in.wrecksBlock->value;
  if (in.sightThroughTrees)
    out.sight.maxTreeCells = c.range(*in.sightThroughTrees, "sight_through_trees", -1, 1000000);
  if (in.scanEvery) out.scanEveryTicks = c.range(*in.scanEvery, "scan_every", 1, 1000000);
  for (const raw::ArmourPercent& p : in.armour) {
    out.armour[static_cast<std::size_t>(p.kind.value)][static_cast<std::size_t>(p.armour.value)] =
        c.range(p.percent,
                "armour percent " + std::string(units::damageKindName(p.kind.value)) + " vs " +
                    std::string(units::armourClassName(p.armour.value)),
                0, 1000);
  }
}

// The world settings the file gives, each in its range, then problemWith(WorldSettings) (what
// World's constructor would throw on) reported at the key that set the field it names.
void applySettings(const Checker& c, const raw::Settings& in, Scenario& s) {
  WorldSettings& out = s.settings;
  if (in.seed) out.seed = in.seed->value;
  applyTiming(c, in.timing, s);
  if (in.pathing) applyPathing(c, *in.pathing, out.pathing);
  if (in.stuck) applyStuck(c, *in.stuck, out.stuck);
  if (in.combat) applyCombat(c, *in.combat, out.combat);
  if (const std::string problem = problemWith(out); !problem.empty()) {
    const auto section = [](const auto& part, auto field) {
      return part ? markOf((*part).*field) : std::nullopt;
    };
    failAtSetter(
        c, problem,
        {{"tickRate", "tick_rate", markOf(in.timing.tickRate)},
         {"stuck.windowSeconds", "stuck seconds", section(in.stuck, &raw::Stuck::seconds)},
         {"stuck.minProgress", "min_progress", section(in.stuck, &raw::Stuck::minProgress)},
         {"stuck.flagAfter", "flag_after", section(in.stuck, &raw::Stuck::flagAfter)},
         {"pathing: clusterSize", "cluster_size", section(in.pathing, &raw::Pathing::clusterSize)},
         {"pathing: expansionBudget", "budget", section(in.pathing, &raw::Pathing::budget)},
         {"combat.wreckSeconds", "wreck_seconds", section(in.combat, &raw::Combat::wreckSeconds)},
         {"combat.scanEveryTicks", "scan_every", section(in.combat, &raw::Combat::scanEvery)}},
        in.root, "");
  }
}

// ---- the scenario ----------------------------------------------------------------------------

// Builds a Scenario from a decoded file, checking each part against what came before it.
class Builder {
 public:
  Builder(const fs::path& file, const FileReader& files, const WorldSettings& defaults)
      : c_(file.string()), file_(file), files_(files) {
    s_.settings = defaults;
  }

  // Takes the file's sections in the schema's order: the map, the unit types, the settings,
  // teams, groups, then what refers to them.
  Scenario build(const decode::ScenarioFile& in) {
    const raw::Maybe<std::string> name = in.name();
    s_.file = file_;
    s_.name = name ? name->value : file_.stem().string();
    s_.grid = std::make_shared<const AnnotatedGrid>(map(in.map()));
    catalogue(in);
    applySettings(c_, in.settings(), s_);
    teams(in.teams());
    groups(in.groups());
    for (const raw::Order& o : in.orders())
      s_.triggers.push_back(order(o));
    const std::vector<raw::Trigger> triggers = in.triggers();
    std::vector<std::string> reinforcedBy(s_.groups.size());
    for (std::size_t i = 0; i < triggers.size(); ++i)
      s_.triggers.push_back(trigger(triggers[i], static_cast<int>(i) + 1, reinforcedBy));
    for (const raw::Victory& v : in.victory())
      s_.victory.push_back(victory(v));
    for (const raw::Expectation& e : in.expectations())
      s_.expectations.push_back(expectation(e));
    return std::move(s_);
  }

 private:
  const GridMap& gridMap() const { return s_.grid->map(); }

  // The contents of the file `name` names (resolved against the scenario's folder) through the
  // file reader; fails at `name` when it has none or cannot read it ("map: FILE: is a
  // directory"). `what` is "map" or "catalogue".
  std::pair<fs::path, std::string> referenced(const raw::Field<std::string>& name,
                                              const std::string& what, FileLimit limit) const {
    const fs::path file = file_.parent_path() / name.value;
    Result<std::string> contents = files_(file, limit);
    if (!contents) {
      if (contents.error().message == kNoSuchFile)
        c_.fail(name.mark, what + " file '" + file.string() + "' not found");
      c_.fail(name.mark, what + ": " + contents.error().describe());
    }
    return {file, std::move(contents).value()};
  }

  GridMap map(const raw::Map& in) const {
    if (in.file) {
      const auto [file, contents] = referenced(*in.file, "map", kMapFileLimit);
      Result<GridMap> map = parseMap(std::string_view(contents), file.string());
      if (!map) c_.fail(in.file->mark, "map: " + map.error().describe());
      return std::move(map).value();
    }
    // Inline rows use the .map glyphs; reading them through the .map parser keeps one reader.
    std::string text = "type octile\nheight " + std::to_string(in.rows.size()) + "\nwidth " +
                       std::to_string(in.rows[0].value.size()) + "\nmap\n";
    for (const raw::Field<std::string>& row : in.rows)
      text += row.value + "\n";
    Result<GridMap> map = parseMap(std::string_view(text), "inline map");
    if (!map) {
      constexpr int kHeaderLines = 4;
      const int row = map.error().line - kHeaderLines - 1;
      if (row >= 0 && row < static_cast<int>(in.rows.size()))
        c_.fail(in.rows[static_cast<std::size_t>(row)].mark, "map row: " + map.error().message);
      c_.fail(in.rowsMark, "map: " + map.error().message);
    }
    return std::move(map).value();
  }

  // The catalogue file, then `unit_types`.
  void catalogue(const decode::ScenarioFile& in) {
    if (const raw::Maybe<std::string> named = in.catalogue()) {
      const auto [file, contents] = referenced(*named, "catalogue", kYamlFileLimit);
      Result<std::vector<units::UnitType>> loaded = parseCatalogue(contents, file);
      if (!loaded.ok()) throw loaded.error();
      s_.catalogue = std::move(loaded).value();
    }
    applyUnitTypes(c_, in.unitTypes(), s_.catalogue);
    if (s_.catalogue.empty()) c_.fail(in.root(), "no unit types: give 'catalogue' or 'unit_types'");
    for (const units::UnitType& t : s_.catalogue)
      typeNames_.push_back(t.name);
  }

  void teams(const std::vector<raw::Field<std::string>>& in) {
    for (const raw::Field<std::string>& team : in) {
      if (team.value == "none")
        c_.fail(team.mark, "'none' cannot name a team (it means no team in winner and end_battle)");
      if (std::find(s_.teams.begin(), s_.teams.end(), team.value) != s_.teams.end())
        c_.fail(team.mark, "team '" + team.value + "' given twice");
      s_.teams.push_back(team.value);
    }
  }

  // A team name, or `none` (-1): the winner expectation and the end_battle action.
  int teamOrNone(const raw::Field<std::string>& name, const std::string& what) const {
    if (name.value == "none") return -1;
    const auto it = std::find(s_.teams.begin(), s_.teams.end(), name.value);
    if (it != s_.teams.end()) return static_cast<int>(it - s_.teams.begin());
    c_.fail(name.mark, "unknown team '" + name.value + "' in " + what +
                           " (known: " + Checker::joined(s_.teams) + "; or none)");
  }

  // Each group placed in its spawn area (footprints apart from the groups before it), its goal
  // checked reachable.
  void groups(const std::vector<raw::Group>& in) {
    std::vector<std::uint8_t> occupied(gridMap().cellCount(), 0);
    for (const raw::Group& node : in) {
      GroupSpec g;
      g.name = node.name ? node.name->value : "group" + std::to_string(s_.groups.size() + 1);
      if (std::find(groupNames_.begin(), groupNames_.end(), g.name) != groupNames_.end())
        c_.fail(node.name ? node.name->mark : node.mark, "group '" + g.name + "' given twice");
      g.team = c_.indexOf(node.team, s_.teams, "team");
      g.type = c_.indexOf(node.type, typeNames_, "unit type");
      g.count = c_.range(node.count, "count", 1, 1000000);
      g.spawn = c_.area(node.spawn, gridMap(), "spawn");
      const units::UnitType& type = s_.catalogue[static_cast<std::size_t>(g.type)];
      g.anchors = placeUnits(*s_.grid, type.agent(), g.spawn, g.count, occupied);
      if (static_cast<int>(g.anchors.size()) < g.count)
        c_.fail(node.spawn.mark, "spawn area " + describeRect(g.spawn) + " has room for only " +
                                     std::to_string(g.anchors.size()) + " of " +
                                     std::to_string(g.count) + " " + type.name + " (size " +
                                     std::to_string(type.size) + ", " + type.capability.toString() +
                                     ") on terrain it can stand on");
      if (node.reinforcement) g.reinforcement = node.reinforcement->value;
      if (node.goal) {
        g.goal = c_.area(*node.goal, gridMap(), "goal");
        checkReachable(node.goal->mark, g, *g.goal);
      }
      groupNames_.push_back(g.name);
      s_.groups.push_back(std::move(g));
    }
  }

  // Every spawn cell of `group` must reach some cell of `area` where its type can stand.
  void checkReachable(raw::Mark where, const GroupSpec& group, const CellRect& area) {
    const AreaKey key{group.type, area.x, area.y, area.width, area.height};
    if (reachableGroups_.contains({group.name, key})) return;
    const units::UnitType& type = s_.catalogue[static_cast<std::size_t>(group.type)];
    const auto& components = s_.grid->layer(type.agent()).components();
    auto [found, isNew] = reachableComponents_.try_emplace(key);
    std::set<std::uint32_t>& reachable = found->second;
    if (isNew) {
      for (int y = area.y; y < area.y + area.height; ++y) {
        for (int x = area.x; x < area.x + area.width; ++x) {
          if (s_.grid->canStand(type.agent(), {x, y}))
            reachable.insert(components[gridMap().indexOf({x, y})]);
        }
      }
    }
    if (reachable.empty())
      c_.fail(where, "goal area " + describeRect(area) + " has no cell where a " + type.name +
                         " (size " + std::to_string(type.size) + ", " + type.capability.toString() +
                         ") can stand");
    for (Cell cell : group.anchors) {
      if (!reachable.contains(components[gridMap().indexOf(cell)]))
        c_.fail(where, "goal area " + describeRect(area) + " is unreachable for " + type.name +
                           " of group '" + group.name + "' spawned at " + std::to_string(cell.x) +
                           "," + std::to_string(cell.y));
    }
    reachableGroups_.insert({group.name, key});
  }

  // Group names: at least one, none twice.
  std::vector<int> groupList(const raw::Names& in, const std::string& what) const {
    std::vector<int> out;
    for (const raw::Field<std::string>& item : in.items) {
      const int g = c_.indexOf(item, groupNames_, "group");
      if (std::find(out.begin(), out.end(), g) != out.end())
        c_.fail(item.mark, "group '" + item.value + "' named twice in " + what);
      out.push_back(g);
    }
    return out;
  }

  ActionSpec orderAction(const raw::OrderAction& in) {
    ActionSpec a;
    a.kind = ActionKind::Order;
    a.order = in.order.value;
    a.groups = groupList(in.groups, "'group'");
    if (in.moveTo) {
      a.area = c_.area(*in.moveTo, gridMap(), "move_to");
      for (int g : a.groups)
        checkReachable(in.moveTo->mark, s_.groups[static_cast<std::size_t>(g)], a.area);
    }
    if (in.target) {
      a.targetGroups = groupList(*in.target, "'target'");
      for (std::size_t i = 0; i < a.targetGroups.size(); ++i) {
        const GroupSpec& enemy = s_.groups[static_cast<std::size_t>(a.targetGroups[i])];
        for (int g : a.groups) {
          const GroupSpec& own = s_.groups[static_cast<std::size_t>(g)];
          if (own.team == enemy.team)
            c_.fail(in.target->items[i].mark, "attack target '" + enemy.name + "' is on team '" +
                                                  s_.teams[static_cast<std::size_t>(enemy.team)] +
                                                  "', the team of ordered group '" + own.name +
                                                  "': targets must be enemies");
        }
      }
    }
    return a;
  }

  // An `orders:` entry: a trigger named "order N" with one order action.
  TriggerSpec order(const raw::Order& in) {
    TriggerSpec o;
    o.name = "order " + std::to_string(s_.triggers.size() + 1);
    if (in.at) {
      o.kind = TriggerKind::At;
      o.at = c_.range(*in.at, "at", 0.0, 1e6);
    } else {
      o.kind = TriggerKind::Arrived;
      o.group = c_.indexOf(in.arrived, groupNames_, "group");
      if (in.fraction) o.fraction = c_.range(*in.fraction, "fraction", 0.0, 1.0);
    }
    o.actions.push_back(orderAction(in.action));
    return o;
  }

  void condition(const raw::Condition& in, TriggerSpec& t) const {
    t.kind = in.kind.value;
    // `count` of a group's units: 1 by default, at most the group's size.
    const auto groupCount = [&](const std::string& what) {
      if (!in.count) return 1;
      const GroupSpec& g = s_.groups[static_cast<std::size_t>(t.group)];
      return c_.range(*in.count, what + " count (group '" + g.name + "')", 1, g.count);
    };
    switch (in.kind.value) {
      case TriggerKind::At:
        t.at = c_.range(in.at, "at", 0.0, 1e6);
        break;
      case TriggerKind::Arrived:
        t.group = c_.indexOf(in.group, groupNames_, "group");
        if (in.fraction) t.fraction = c_.range(*in.fraction, "fraction", 0.0, 1.0);
        break;
      case TriggerKind::TeamBelow:
        t.team = c_.indexOf(in.team, s_.teams, "team");
        t.count = c_.range(*in.count, "team_below count", 1, 100000000);
        break;
      case TriggerKind::Enters:
        t.group = c_.indexOf(in.group, groupNames_, "group");
        t.area = c_.area(in.area, gridMap(), "enters area");
        t.count = groupCount("enters");
        break;
      case TriggerKind::Dies:
        t.group = c_.indexOf(in.group, groupNames_, "group");
        t.count = groupCount("dies");
        break;
    }
  }

  // `reinforcedBy` holds, per group, the trigger that already brings it in (empty when none).
  ActionSpec action(const raw::Action& in, const std::string& trigger,
                    std::vector<std::string>& reinforcedBy) {
    ActionSpec a;
    switch (in.kind) {
      case ActionKind::Order:
        return orderAction(in.order);
      case ActionKind::Reinforce: {
        a.kind = ActionKind::Reinforce;
        a.group = c_.indexOf(in.name, groupNames_, "group");
        const GroupSpec& g = s_.groups[static_cast<std::size_t>(a.group)];
        if (!g.reinforcement)
          c_.fail(in.name.mark, "group '" + g.name +
                                    "' is not a reinforcement group (it spawns at the start; "
                                    "give it 'reinforcement: true')");
        std::string& by = reinforcedBy[static_cast<std::size_t>(a.group)];
        if (!by.empty())
          c_.fail(in.name.mark,
                  "group '" + g.name + "' is already brought in by trigger '" + by + "'");
        by = trigger;
        return a;
      }
      case ActionKind::EndBattle:
        a.kind = ActionKind::EndBattle;
        a.team = teamOrNone(in.name, "end_battle");
        return a;
      case ActionKind::SetTerrain:
        a.kind = ActionKind::SetTerrain;
        a.area = c_.area(in.area, gridMap(), "set_terrain area");
        a.terrain = in.terrain.value;
        s_.settings.terrainChanges = true;  // the run's world gets a grid of its own
        return a;
    }
    return a;
  }

  // The `number`th entry of `triggers:`.
  TriggerSpec trigger(const raw::Trigger& in, int number, std::vector<std::string>& reinforcedBy) {
    TriggerSpec t;
    t.name = in.name ? in.name->value : "trigger " + std::to_string(number);
    for (const TriggerSpec& other : s_.triggers) {
      if (other.name == t.name)
        c_.fail(in.name ? in.name->mark : in.mark, "trigger name '" + t.name + "' used twice");
    }
    condition(in.when, t);
    for (const raw::Action& action : in.actions)
      t.actions.push_back(this->action(action, t.name, reinforcedBy));
    return t;
  }

  VictorySpec victory(const raw::Victory& in) const {
    VictorySpec v;
    v.kind = in.kind.value;
    v.team = c_.indexOf(in.team, s_.teams, "team");
    switch (in.kind.value) {
      case VictoryKind::Eliminate:
        break;
      case VictoryKind::HoldArea:
        v.area = c_.area(in.area, gridMap(), "hold area");
        v.seconds = c_.range(in.seconds, "hold seconds", 0.0, 1e6);
        break;
      case VictoryKind::Exit: {
        v.area = c_.area(in.area, gridMap(), "exit area");
        int units = 0;
        for (const GroupSpec& g : s_.groups)
          units += g.team == v.team ? g.count : 0;
        v.count = c_.range(in.count, "exit count", 1, 100000000);
        if (v.count > units)
          c_.fail(in.count.mark, "exit count " + std::to_string(v.count) + " is more than team '" +
                                     s_.teams[static_cast<std::size_t>(v.team)] + "' has (" +
                                     std::to_string(units) + " units, reinforcements included)");
        break;
      }
    }
    v.text = describe(v, s_.teams);
    return v;
  }

  Expectation expectation(const raw::Expectation& in) const {
    Expectation e;
    e.kind = in.kind;
    // "kind(team, type)", the team and type resolved.
    const auto who = [&](const std::string& what) {
      if (in.team) e.team = c_.indexOf(*in.team, s_.teams, "team");
      if (in.type) e.type = c_.indexOf(*in.type, typeNames_, "unit type");
      return what + "(" + (e.team < 0 ? "*" : s_.teams[static_cast<std::size_t>(e.team)]) + ", " +
             (e.type < 0 ? "*" : typeNames_[static_cast<std::size_t>(e.type)]) + ")";
    };
    switch (in.kind) {
      case ExpectationKind::ArrivalRate:
        e.threshold = c_.range(in.threshold, "at_least", 0.0, 1.0);
        e.by = c_.range(in.by, "by", 0.0, 1e6);
        e.text =
            who("arrival_rate") + " >= " + fmtNumber(e.threshold) + " by " + fmtNumber(e.by) + "s";
        break;
      case ExpectationKind::MaxStuck:
        e.threshold = c_.range(in.count, "max_stuck", 0, 1000000);
        e.text = "max_stuck <= " + fmtNumber(e.threshold);
        break;
      case ExpectationKind::ArrivalTime:
        e.percentile = c_.range(in.percentile, "percentile", 0.0, 100.0);
        e.threshold = c_.range(in.threshold, "at_most", 0.0, 1e6);
        e.text = who("arrival_time") + " p" + fmtNumber(e.percentile) +
                 " <= " + fmtNumber(e.threshold) + "s";
        break;
      case ExpectationKind::Delay:
        e.percentile = c_.range(in.percentile, "percentile", 0.0, 100.0);
        e.threshold = c_.range(in.threshold, "at_most", 0.0, 1e6);
        e.text = who("delay") + " p" + fmtNumber(e.percentile) + " <= " + fmtNumber(e.threshold);
        break;
      case ExpectationKind::MaxWait:
        e.threshold = c_.range(in.threshold, "max_wait", 0.0, 1e6);
        e.text = "max_wait <= " + fmtNumber(e.threshold) + "s";
        break;
      case ExpectationKind::MaxDeadlocks:
        e.threshold = c_.range(in.count, "max_deadlocks", 0, 1000000);
        e.text = "max_deadlocks <= " + fmtNumber(e.threshold);
        break;
      case ExpectationKind::Winner:
        e.team = teamOrNone(*in.team, "winner");
        e.text = "winner == " +
                 (e.team < 0 ? std::string("none") : s_.teams[static_cast<std::size_t>(e.team)]);
        break;
      case ExpectationKind::Stat:
        e.stat = in.stat;
        e.atMost = in.atMost;
        e.threshold = c_.range(in.threshold, e.atMost ? "at_most" : "at_least", 0.0, 1e12);
        e.text = who(in.key.value) + (e.atMost ? " <= " : " >= ") + fmtNumber(e.threshold);
        break;
    }
    return e;
  }

  // What checkReachable has worked out already: the map components a unit type can reach in an
  // area, and the (group, area) pairs found reachable. Aliases can repeat one order or goal
  // thousands of times; each is checked once.
  using AreaKey = std::tuple<int, int, int, int, int>;
  std::map<AreaKey, std::set<std::uint32_t>> reachableComponents_;
  std::set<std::pair<std::string, AreaKey>> reachableGroups_;

  Checker c_;
  fs::path file_;
  const FileReader& files_;
  Scenario s_;
  std::vector<std::string> typeNames_;
  std::vector<std::string> groupNames_;
};

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
      return team + " holds " + describeRect(v.area) + " for " + fmtNumber(v.seconds) + "s";
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

Result<Scenario> parseScenario(std::string_view text, const fs::path& file, const FileReader& files,
                               const WorldSettings& defaults) {
  try {
    return Builder(file, files, defaults).build(decode::ScenarioFile(text, file.string()));
  } catch (const Error& e) {
    return e;
  }
}

Result<Scenario> loadScenario(const fs::path& file) {
  const Result<std::string> text = readDiskFile(file, kYamlFileLimit);
  if (!text) return text.error();
  return parseScenario(text.value(), file);
}

Result<std::int64_t> scenarioDurationTicks(std::string_view text, const fs::path& file) {
  try {
    // The same keys and ranges as a whole scenario's; only `tick_rate` and `duration` are read.
    Scenario s;
    applyTiming(Checker(file.string()), decode::timing(text, file.string()), s);
    return s.durationTicks();
  } catch (const Error& e) {
    return e;
  }
}

Result<std::vector<units::UnitType>> loadCatalogue(const fs::path& file) {
  const Result<std::string> text = readDiskFile(file, kYamlFileLimit);
  if (!text) return text.error();
  return parseCatalogue(text.value(), file);
}

}  // namespace warpath::engine
