#pragma once
// Combat rules as plain data and pure functions: weapons, armour, damage arithmetic, line of
// sight over the grid and target choice. The engine owns the units, the clock and the shots in
// flight; nothing here keeps state between calls. docs/combat.md states the rules.
//
// Determinism: damage is integer arithmetic (percent multipliers, floor division); distances
// are compared squared, computed in one fixed expression order; ties are broken by unit id;
// candidates are scanned in the order given and no unordered container is used.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "pathing/enum_names.h"
#include "pathing/grid_map.h"
#include "units/steering.h"

namespace warpath::units {

// How a unit is protected. [Limit: < kArmourClasses]
enum class ArmourClass : std::uint8_t {
  Infantry = 0,    // soldiers
  Light = 1,       // soft-skinned vehicles (jeeps)
  Heavy = 2,       // tanks
  Amphibious = 3,  // light hulls that must float
};
inline constexpr int kArmourClasses = 4;

// What a weapon throws; the armour table is indexed by (DamageKind, ArmourClass).
enum class DamageKind : std::uint8_t {
  Rifle = 0,       // infantry small arms
  MachineGun = 1,  // vehicle-mounted automatic fire
  Cannon = 2,      // tank gun: armour-piercing shell
  LightGun = 3,    // amphibious pintle gun
};
inline constexpr int kDamageKinds = 4;

// Lower-case names for catalogues and reports, one table per enum (list() for "choose one of"
// messages); the functions below read them ("?" for a value not in the table).
inline constexpr EnumNames<ArmourClass, kArmourClasses> kArmourClassNames{{{
    {ArmourClass::Infantry, "infantry"},
    {ArmourClass::Light, "light"},
    {ArmourClass::Heavy, "heavy"},
    {ArmourClass::Amphibious, "amphibious"},
}}};
inline constexpr EnumNames<DamageKind, kDamageKinds> kDamageKindNames{{{
    {DamageKind::Rifle, "rifle"},
    {DamageKind::MachineGun, "machine_gun"},
    {DamageKind::Cannon, "cannon"},
    {DamageKind::LightGun, "light_gun"},
}}};
std::string_view armourClassName(ArmourClass a);
std::optional<ArmourClass> armourClassFromName(std::string_view name);
std::string_view damageKindName(DamageKind k);
std::optional<DamageKind> damageKindFromName(std::string_view name);

// A set of armour classes (what a weapon may target), one bit per class.
struct TargetMask {
  std::uint8_t bits = 0;
  static constexpr TargetMask all() { return {(1u << kArmourClasses) - 1u}; }
  static constexpr TargetMask of(std::initializer_list<ArmourClass> classes) {
    std::uint8_t b = 0;
    for (ArmourClass a : classes)
      b = static_cast<std::uint8_t>(b | (1u << static_cast<int>(a)));
    return {b};
  }
  constexpr bool has(ArmourClass a) const { return (bits >> static_cast<int>(a)) & 1u; }
  constexpr bool operator==(const TargetMask&) const = default;
};

// [Unit: percent] damage multiplier per (DamageKind, ArmourClass); 100 = full damage, 0 = none.
using ArmourTable = std::array<std::array<int, kArmourClasses>, kDamageKinds>;

// The default multipliers: rifles hurt infantry and barely scratch tanks; machine guns are best
// against infantry; the tank gun is deadly to vehicles and poor against scattered soldiers;
// the amphibious gun is weak against everything but infantry.
ArmourTable defaultArmourTable();

struct Weapon {
  std::string name;
  DamageKind kind = DamageKind::Rifle;
  int damage = 10;               // [Limit: >= 0] per shot, before the armour multiplier
  double range = 5.0;            // [Unit: cells] [Limit: > 0] edge-to-edge gap it reaches
  double cooldown = 1.0;         // [Unit: s] [Limit: > 0] time between shots
  double projectileSpeed = 0.0;  // [Unit: cells/s] [Limit: >= 0] 0 = instant hit
  TargetMask targets = TargetMask::all();
  // Rank per armour class, lower preferred; within a rank the nearest wins. All equal (the
  // default) means plain nearest-enemy.
  std::array<std::uint8_t, kArmourClasses> priority{};

  bool canTarget(ArmourClass a) const { return targets.has(a); }
  std::uint8_t rankOf(ArmourClass a) const { return priority[static_cast<std::size_t>(a)]; }
};

// Empty when the weapon is usable, else what is wrong with it (for error messages), beginning
// with the field as scenario files spell it ("cooldown must be positive").
std::string problemWith(const Weapon& weapon);

// A unit's default armour and weapon by catalogue type name ("infantry", "jeep", "tank",
// "amphibious"); nullopt for other names.
std::optional<ArmourClass> defaultArmourFor(std::string_view unitType);
std::optional<Weapon> defaultWeaponFor(std::string_view unitType);

// Damage one shot deals: floor(damage · percent / 100), at least 1 whenever percent > 0 so that
// a hit that is meant to scratch does scratch; 0 when percent is 0 (immune).
int damageDealt(int damage, int percent);
int damageDealt(const Weapon& weapon, ArmourClass target, const ArmourTable& table);
// Hit points left after `damage`, never below 0.
constexpr int applyDamage(int hp, int damage) {
  return hp > damage ? hp - damage : 0;
}

// [Unit: ticks] Seconds rounded to the nearest tick, at least 1: a weapon never fires twice
// in one tick and 0.3 s at 30 Hz is 9 ticks, not 10 through a rounding error upwards.
std::int64_t cooldownTicks(const Weapon& weapon, double ticksPerSecond);
// [Unit: ticks] Flight time of a shot over `gap` cells: 0 for instant weapons, else the travel
// time rounded to the nearest tick and at least 1 (the shell lands on a later tick).
std::int64_t travelTicks(const Weapon& weapon, double gap, double ticksPerSecond);

// What the rules need to know about a unit; the engine builds these from its storage.
struct Combatant {
  std::uint32_t id = 0;  // creation order; the final tie-break
  int team = 0;
  ArmourClass armour = ArmourClass::Infantry;
  int size = 1;  // [Unit: cells] side of the footprint
  Vec2 centre;   // [Unit: cells] body centre
  int hp = 1;    // <= 0 is dead
  bool alive() const { return hp > 0; }
};

// [Unit: cells²] Squared gap between two footprints (axis-aligned squares of side `size`
// around their centres): 0 when they touch or overlap. Range is measured edge to edge so that
// a big target is not out of reach because its centre is far.
double gapSquared(const Combatant& a, const Combatant& b);
inline bool inRange(const Weapon& w, const Combatant& shooter, const Combatant& target) {
  return gapSquared(shooter, target) <= w.range * w.range;
}

// What stops sight. Blocked cells (and cells off the map) always do. Trees thin it: sight
// passes through at most `maxTreeCells` tree cells between the two ends, so units see into the
// edge of a forest but not across it. A negative value lets sight through any number of trees.
struct SightRules {
  int maxTreeCells = 2;  // [Unit: cells]
};

// Line of sight between two cells: a supercover walk (every cell the segment between the two
// cell centres passes through). The end cells themselves never block (a unit may stand in a
// forest and shoot out of it). Where the segment passes exactly through a cell corner the less
// obstructed of the two side cells counts, so a single corner never hides anything; two blocked
// diagonal neighbours do. Symmetric: los(a, b) == los(b, a).
bool lineOfSight(const pathing::GridMap& map, pathing::Cell from, pathing::Cell to,
                 const SightRules& rules = {});
// Between units: from the cell holding one centre to the cell holding the other.
bool lineOfSight(const pathing::GridMap& map, const Combatant& from, const Combatant& to,
                 const SightRules& rules = {});

// True when `shooter` may fire `weapon` at `target` now: both alive, other teams, a class the
// weapon targets, in range and in sight.
bool canEngage(const Weapon& weapon, const Combatant& shooter, const Combatant& target,
               const pathing::GridMap& map, const SightRules& rules = {});

// The best target among `candidates` (any order; the shooter itself may be among them): the
// lowest priority rank, then the smallest gap, then the smallest id. nullopt when none may be
// engaged.
std::optional<std::uint32_t> acquireTarget(const Weapon& weapon, const Combatant& shooter,
                                           std::span<const Combatant> candidates,
                                           const pathing::GridMap& map,
                                           const SightRules& rules = {});

// Sticky targeting, the rule the world runs for every armed unit each tick (orders other than
// Attack): keeps `current` (null when the unit has no target, or its target left the world)
// while it may still be engaged, so a nearer enemy walking up does not make a gunner swap
// mid-fight. Otherwise it looks for the best target with acquireTarget among `candidates()`,
// but only when `mayScan`: a unit that lost its target scans at once, one that had none scans
// every few ticks (staggered by id) to spread the cost. `candidates` (a callable returning a
// range of Combatant) is called only when a scan runs. nullopt: no target.
template <class CandidatesFn>
std::optional<std::uint32_t> chooseTarget(const Weapon& weapon, const Combatant& shooter,
                                          const Combatant* current, bool mayScan,
                                          CandidatesFn&& candidates, const pathing::GridMap& map,
                                          const SightRules& rules = {}) {
  if (current != nullptr && canEngage(weapon, shooter, *current, map, rules)) return current->id;
  if (!mayScan) return std::nullopt;
  return acquireTarget(weapon, shooter, candidates(), map, rules);
}

// The same rule when the current target is known by id among `candidates` and a scan may
// always run: keeps `current` while it may be engaged, else acquireTarget.
std::optional<std::uint32_t> chooseTarget(const Weapon& weapon, const Combatant& shooter,
                                          std::optional<std::uint32_t> current,
                                          std::span<const Combatant> candidates,
                                          const pathing::GridMap& map,
                                          const SightRules& rules = {});

// An Attack order's rule: among the ordered targets (in the order given), the one with the
// smallest gap that may be engaged now; the earlier one on equal gaps. nullopt when none may.
std::optional<std::uint32_t> nearestEngageable(const Weapon& weapon, const Combatant& shooter,
                                               std::span<const Combatant> ordered,
                                               const pathing::GridMap& map,
                                               const SightRules& rules = {});

}  // namespace warpath::units
