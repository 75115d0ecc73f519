#include "units/combat.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace warpath::units {

using pathing::Cell;
using pathing::GridMap;
using pathing::Terrain;

namespace {

// Sight cost of one cell: trees thin sight, walls (and the map's outside) stop it.
constexpr int kWall = std::numeric_limits<int>::max() / 4;
int sightCost(const GridMap& map, Cell c) {
  const Terrain t = map.at(c);
  if (t == Terrain::Blocked) return kWall;
  return t == Terrain::Trees ? 1 : 0;
}

Cell cellOf(Vec2 centre) {
  return {static_cast<int>(std::floor(centre.x)), static_cast<int>(std::floor(centre.y))};
}

const Combatant* findById(std::span<const Combatant> units, std::uint32_t id) {
  for (const Combatant& u : units)
    if (u.id == id) return &u;
  return nullptr;
}

}  // namespace

std::string_view armourClassName(ArmourClass a) {
  return kArmourClassNames.name(a);
}

std::optional<ArmourClass> armourClassFromName(std::string_view name) {
  return kArmourClassNames.parse(name);
}

std::string_view damageKindName(DamageKind k) {
  return kDamageKindNames.name(k);
}

std::optional<DamageKind> damageKindFromName(std::string_view name) {
  return kDamageKindNames.parse(name);
}

ArmourTable defaultArmourTable() {
  // Columns: infantry, light, heavy, amphibious.
  ArmourTable t{};
  t[static_cast<std::size_t>(DamageKind::Rifle)] = {100, 40, 5, 25};
  t[static_cast<std::size_t>(DamageKind::MachineGun)] = {125, 60, 10, 35};
  t[static_cast<std::size_t>(DamageKind::Cannon)] = {40, 150, 100, 125};
  t[static_cast<std::size_t>(DamageKind::LightGun)] = {100, 50, 10, 40};
  return t;
}

std::string problemWith(const Weapon& w) {
  if (static_cast<int>(w.kind) >= kDamageKinds) return "unknown damage kind";
  if (w.damage < 0) return "damage must not be negative";
  if (!(w.range > 0.0) || !std::isfinite(w.range)) return "range must be positive";
  if (!(w.cooldown > 0.0) || !std::isfinite(w.cooldown)) return "cooldown must be positive";
  if (!(w.projectileSpeed >= 0.0) || !std::isfinite(w.projectileSpeed))
    return "projectile_speed must be 0 (instant) or positive";
  if (w.targets.bits == 0) return "targets must name at least one armour class";
  if (w.targets.bits >= (1u << kArmourClasses)) return "targets names an unknown armour class";
  return {};
}

std::optional<ArmourClass> defaultArmourFor(std::string_view unitType) {
  if (unitType == "infantry") return ArmourClass::Infantry;
  if (unitType == "jeep") return ArmourClass::Light;
  if (unitType == "tank") return ArmourClass::Heavy;
  if (unitType == "amphibious") return ArmourClass::Amphibious;
  return std::nullopt;
}

std::optional<Weapon> defaultWeaponFor(std::string_view unitType) {
  // priority order: infantry, light, heavy, amphibious (lower rank first).
  Weapon w;
  if (unitType == "infantry") {
    w = {"rifle", DamageKind::Rifle, 10, 5.0, 1.0, 0.0, TargetMask::all(), {0, 1, 2, 1}};
  } else if (unitType == "jeep") {
    w = {"machine_gun", DamageKind::MachineGun, 8, 6.0, 0.3, 0.0, TargetMask::all(), {0, 1, 2, 1}};
  } else if (unitType == "tank") {
    // Slow shells that lead vehicles first; infantry only when nothing bigger is in reach.
    w = {"tank_gun", DamageKind::Cannon, 150, 8.0, 3.0, 15.0, TargetMask::all(), {1, 0, 0, 0}};
  } else if (unitType == "amphibious") {
    w = {"light_gun", DamageKind::LightGun, 12, 4.0, 1.5, 0.0, TargetMask::all(), {0, 1, 1, 1}};
  } else {
    return std::nullopt;
  }
  return w;
}

int damageDealt(int damage, int percent) {
  if (damage <= 0 || percent <= 0) return 0;
  const std::int64_t d = static_cast<std::int64_t>(damage) * percent / 100;
  return static_cast<int>(std::clamp<std::int64_t>(d, 1, std::numeric_limits<int>::max()));
}

int damageDealt(const Weapon& weapon, ArmourClass target, const ArmourTable& table) {
  return damageDealt(
      weapon.damage,
      table[static_cast<std::size_t>(weapon.kind)][static_cast<std::size_t>(target)]);
}

std::int64_t cooldownTicks(const Weapon& weapon, double ticksPerSecond) {
  return std::max<std::int64_t>(1, std::llround(weapon.cooldown * ticksPerSecond));
}

std::int64_t travelTicks(const Weapon& weapon, double gap, double ticksPerSecond) {
  if (!(weapon.projectileSpeed > 0.0)) return 0;
  return std::max<std::int64_t>(1, std::llround(gap / weapon.projectileSpeed * ticksPerSecond));
}

double gapSquared(const Combatant& a, const Combatant& b) {
  const double half = 0.5 * (a.size + b.size);
  const double dx = std::max(0.0, std::abs(a.centre.x - b.centre.x) - half);
  const double dy = std::max(0.0, std::abs(a.centre.y - b.centre.y) - half);
  return dx * dx + dy * dy;
}

bool lineOfSight(const GridMap& map, Cell from, Cell to, const SightRules& rules) {
  // Integer supercover walk between cell centres (no floating point, so both directions agree):
  // at each step compare where the segment crosses the next vertical and horizontal cell edge.
  const int nx = std::abs(to.x - from.x);
  const int ny = std::abs(to.y - from.y);
  const int sx = to.x > from.x ? 1 : -1;
  const int sy = to.y > from.y ? 1 : -1;
  const std::int64_t budget = rules.maxTreeCells < 0 ? kWall - 1 : rules.maxTreeCells;
  std::int64_t cost = 0;
  Cell c = from;
  for (int ix = 0, iy = 0; ix < nx || iy < ny;) {
    const std::int64_t decision =
        static_cast<std::int64_t>(1 + 2 * ix) * ny - static_cast<std::int64_t>(1 + 2 * iy) * nx;
    if (decision == 0) {
      // Exactly through a corner: the segment grazes both side cells; the clearer one counts.
      cost += std::min(sightCost(map, {c.x + sx, c.y}), sightCost(map, {c.x, c.y + sy}));
      c.x += sx;
      c.y += sy;
      ++ix;
      ++iy;
    } else if (decision < 0) {
      c.x += sx;
      ++ix;
    } else {
      c.y += sy;
      ++iy;
    }
    if (c == to) break;
    cost += sightCost(map, c);
    if (cost > budget) return false;
  }
  return cost <= budget;
}

bool lineOfSight(const GridMap& map, const Combatant& from, const Combatant& to,
                 const SightRules& rules) {
  return lineOfSight(map, cellOf(from.centre), cellOf(to.centre), rules);
}

bool canEngage(const Weapon& weapon, const Combatant& shooter, const Combatant& target,
               const GridMap& map, const SightRules& rules) {
  return shooter.alive() && target.alive() && shooter.team != target.team &&
         weapon.canTarget(target.armour) && inRange(weapon, shooter, target) &&
         lineOfSight(map, shooter, target, rules);
}

std::optional<std::uint32_t> acquireTarget(const Weapon& weapon, const Combatant& shooter,
                                           std::span<const Combatant> candidates,
                                           const GridMap& map, const SightRules& rules) {
  if (!shooter.alive()) return std::nullopt;
  const Combatant* best = nullptr;
  double bestGap = 0.0;
  for (const Combatant& c : candidates) {
    // Cheap tests first; sight (a grid walk) only for a candidate that would win.
    if (!c.alive() || c.team == shooter.team || !weapon.canTarget(c.armour)) continue;
    const double gap = gapSquared(shooter, c);
    if (gap > weapon.range * weapon.range) continue;
    if (best) {
      const auto rank = weapon.rankOf(c.armour);
      const auto bestRank = weapon.rankOf(best->armour);
      const bool better = rank != bestRank ? rank < bestRank
                          : gap != bestGap ? gap < bestGap
                                           : c.id < best->id;
      if (!better) continue;
    }
    if (!lineOfSight(map, shooter, c, rules)) continue;
    best = &c;
    bestGap = gap;
  }
  if (!best) return std::nullopt;
  return best->id;
}

std::optional<std::uint32_t> chooseTarget(const Weapon& weapon, const Combatant& shooter,
                                          std::optional<std::uint32_t> current,
                                          std::span<const Combatant> candidates, const GridMap& map,
                                          const SightRules& rules) {
  const Combatant* held = current ? findById(candidates, *current) : nullptr;
  return chooseTarget(
      weapon, shooter, held, true, [&] { return candidates; }, map, rules);
}

std::optional<std::uint32_t> nearestEngageable(const Weapon& weapon, const Combatant& shooter,
                                               std::span<const Combatant> ordered,
                                               const GridMap& map, const SightRules& rules) {
  std::optional<std::uint32_t> best;
  double bestGap = INFINITY;
  for (const Combatant& target : ordered) {
    const double gap = gapSquared(shooter, target);
    if (gap < bestGap && canEngage(weapon, shooter, target, map, rules)) {
      bestGap = gap;
      best = target.id;
    }
  }
  return best;
}

}  // namespace warpath::units
