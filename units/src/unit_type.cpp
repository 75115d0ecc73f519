#include "units/unit_type.h"

#include <algorithm>

namespace warpath::units {

using pathing::Terrain;

double UnitType::speedOn(Terrain t) const {
  if (!pathing::isTraversable(t) || !capability.allows(t)) return 0.0;
  return speed[static_cast<std::size_t>(t)];
}

pathing::TerrainCosts UnitType::terrainCosts() const {
  pathing::TerrainCosts costs;
  for (int slot = 0; slot < pathing::kTraversableTerrainSlots; ++slot) {
    const double v = speedOn(static_cast<Terrain>(slot));
    if (v > 0.0) costs.perCell[static_cast<std::size_t>(slot)] = 1.0 / v;
  }
  return costs;
}

double UnitType::maxSpeed() const {
  double best = 0.0;
  for (int slot = 0; slot < pathing::kTraversableTerrainSlots; ++slot)
    best = std::max(best, speedOn(static_cast<Terrain>(slot)));
  return best;
}

std::string problemWith(const UnitType& type) {
  if (type.size < 1 || type.size > 255) return "size must be between 1 and 255 cells";
  if (type.capability.empty()) return "capability must name at least one terrain";
  for (int slot = 0; slot < pathing::kTraversableTerrainSlots; ++slot) {
    const auto t = static_cast<Terrain>(slot);
    if (type.capability.allows(t) && !(type.speedOn(t) > 0.0))
      return "speed on " + std::string(pathing::terrainName(t)) + " must be positive";
  }
  if (!(type.acceleration > 0.0)) return "acceleration must be positive";
  if (!(type.turnRate > 0.0)) return "turn_rate must be positive";
  // The body must fit its footprint, or physics would let it touch cells the planner never
  // promised were passable.
  if (!(type.radius > 0.0) || type.radius > 0.5 * type.size)
    return "radius must be positive and at most size/2";
  if (type.hp < 1) return "hp must be at least 1";
  if (static_cast<int>(type.armour) >= kArmourClasses) return "unknown armour class";
  if (type.weapon) {
    const std::string problem = problemWith(*type.weapon);
    if (!problem.empty()) return "weapon: " + problem;
  }
  return {};
}

}  // namespace warpath::units
