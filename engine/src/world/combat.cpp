// Combat in the tick: targets chosen by the rules of units/combat.h, then fire and shots
// landing (docs/combat.md gives the order within a tick).

#include <algorithm>
#include <cmath>

#include "engine/src/world/phases.h"

namespace warpath::engine::world {

int maxUnitSize(const std::vector<units::UnitType>& catalogue) {
  int size = 1;
  for (const units::UnitType& type : catalogue)
    size = std::max(size, type.size);
  return size;
}

void TargetIndex::rebuild(const Refs& w) {
  // Counting sort of the living units into buckets of kBucketCells² cells (CSR layout).
  const pathing::GridMap& map = w.map();
  bucketsWide_ = (map.width() + kBucketCells - 1) / kBucketCells;
  bucketsHigh_ = (map.height() + kBucketCells - 1) / kBucketCells;
  const std::size_t buckets = static_cast<std::size_t>(bucketsWide_ * bucketsHigh_);
  start_.assign(buckets + 1, 0);
  combatants_.clear();
  for (const Unit& unit : w.state.units)
    combatants_.push_back(w.combatantOf(unit));
  const auto bucketOf = [&](const Unit& unit) {
    const int bx =
        std::clamp(static_cast<int>(unit.position.x) / kBucketCells, 0, bucketsWide_ - 1);
    const int by =
        std::clamp(static_cast<int>(unit.position.y) / kBucketCells, 0, bucketsHigh_ - 1);
    return static_cast<std::size_t>(by * bucketsWide_ + bx);
  };
  for (const Unit& unit : w.state.units)
    if (unit.alive()) ++start_[bucketOf(unit) + 1];
  for (std::size_t b = 0; b < buckets; ++b)
    start_[b + 1] += start_[b];
  units_.assign(start_[buckets], 0);
  fill_.assign(start_.begin(), start_.end() - 1);
  for (const Unit& unit : w.state.units)
    if (unit.alive()) units_[fill_[bucketOf(unit)]++] = unit.id.index;
}

const std::vector<units::Combatant>& TargetIndex::near(units::Vec2 centre, double reach) {
  const double r = reach;
  const int bx0 = std::max(0, static_cast<int>(std::floor(centre.x - r)) / kBucketCells);
  const int by0 = std::max(0, static_cast<int>(std::floor(centre.y - r)) / kBucketCells);
  const int bx1 =
      std::min(bucketsWide_ - 1, static_cast<int>(std::floor(centre.x + r)) / kBucketCells);
  const int by1 =
      std::min(bucketsHigh_ - 1, static_cast<int>(std::floor(centre.y + r)) / kBucketCells);
  near_.clear();
  for (int by = by0; by <= by1; ++by) {
    for (int bx = bx0; bx <= bx1; ++bx) {
      const auto b = static_cast<std::size_t>(by * bucketsWide_ + bx);
      for (std::uint32_t i = start_[b]; i < start_[b + 1]; ++i)
        near_.push_back(combatants_[units_[i]]);
    }
  }
  return near_;
}

void Combat::chooseTargets(Refs& w) {
  index_.rebuild(w);
  const pathing::GridMap& map = w.map();
  const units::SightRules& sight = w.settings.combat.sight;
  const auto every = static_cast<std::int64_t>(w.settings.combat.scanEveryTicks);
  for (Unit& unit : w.state.units) {
    unit.engaged = false;
    const units::UnitType& type = w.typeOf(unit);
    if (!unit.alive() || !type.weapon) continue;
    const units::Weapon& weapon = *type.weapon;
    const units::Combatant& self = index_.combatant(unit.id);
    if (unit.order == OrderKind::Attack) {
      // Ordered targets only: the nearest of them, once it can be engaged.
      std::erase_if(unit.attackTargets, [&](UnitId t) { return !w.unit(t).alive(); });
      ordered_.clear();
      for (UnitId t : unit.attackTargets)
        ordered_.push_back(index_.combatant(t));
      const std::optional<std::uint32_t> target =
          units::nearestEngageable(weapon, self, ordered_, map, sight);
      unit.target = target ? w.state.units[*target].id : UnitId{};
      unit.engaged = unit.target.valid();
      continue;
    }
    // Sticky; a unit without a target scans every `every` ticks, staggered by id.
    const units::Combatant* current =
        unit.target.valid() ? &index_.combatant(w.unit(unit.target).id) : nullptr;
    const bool mayScan = unit.target.valid() || (w.state.tick + unit.id.index) % every == 0;
    // Anything whose footprint comes within range has its centre within this reach.
    const double reach = weapon.range + 0.5 * (type.size + index_.maxUnitSize());
    const std::optional<std::uint32_t> target = units::chooseTarget(
        weapon, self, current, mayScan, [&] { return index_.near(unit.position, reach); }, map,
        sight);
    unit.target = target ? w.state.units[*target].id : UnitId{};
    unit.engaged = unit.target.valid() && unit.order == OrderKind::AttackMove;
  }
}

void Combat::fire(Refs& w) {
  WorldState& s = w.state;
  s.lastTickShots.clear();
  for (Unit& unit : s.units) {
    const units::UnitType& type = w.typeOf(unit);
    if (!unit.alive() || !type.weapon || !unit.target.valid() || s.tick < unit.readyTick) continue;
    const units::Weapon& weapon = *type.weapon;
    const Unit& target = w.unit(unit.target);
    const double gap = std::sqrt(units::gapSquared(w.combatantOf(unit), w.combatantOf(target)));
    Shot shot;
    shot.shooter = unit.id;
    shot.target = target.id;
    shot.damage = units::damageDealt(weapon, w.typeOf(target).armour, w.settings.combat.armour);
    shot.firedTick = s.tick;
    shot.landTick = s.tick + units::travelTicks(weapon, gap, w.settings.tickRate);
    shot.from = unit.position;
    shot.to = target.position;
    unit.readyTick = s.tick + units::cooldownTicks(weapon, w.settings.tickRate);
    ++unit.combat.shotsFired;
    s.inFlight.push_back(shot);
    s.lastTickShots.push_back(shot);
  }
  // Shots land in the order fired, including those of shooters that died meanwhile.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < s.inFlight.size(); ++i) {
    const Shot shot = s.inFlight[i];
    if (shot.landTick > s.tick) {
      s.inFlight[kept++] = shot;
      continue;
    }
    Unit& target = w.unit(shot.target);
    if (!target.alive()) continue;  // already dead: the shot is wasted
    Unit& shooter = w.unit(shot.shooter);
    const int dealt = std::min(shot.damage, target.hp);
    target.hp = units::applyDamage(target.hp, shot.damage);
    target.combat.damageTaken += dealt;
    shooter.combat.damageDealt += dealt;
    ++shooter.combat.hits;
    if (!target.alive()) {
      ++shooter.combat.kills;
      kill(w, target, shooter.id);
    }
  }
  s.inFlight.resize(kept);
}

}  // namespace warpath::engine::world
