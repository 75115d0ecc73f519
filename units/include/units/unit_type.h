#pragma once
// What a kind of unit is, as plain data: footprint, terrain capability, movement limits and
// hit points, armour and weapon. Catalogues of these are loaded by the engine; nothing here reads
// files.

#include <array>
#include <optional>
#include <string>

#include "pathing/annotated_grid.h"
#include "pathing/terrain.h"
#include "pathing/terrain_costs.h"
#include "units/combat.h"

namespace warpath::units {

struct UnitType {
  std::string name;
  int size = 1;  // [Unit: cells] [Limit: 1..255] side of the square footprint (planner agent)
  pathing::Capability capability;  // terrains the unit may stand on [Limit: non-empty]
  // [Unit: cells/s] top speed per traversable terrain slot; only slots in `capability` matter.
  std::array<double, pathing::kTraversableTerrainSlots> speed{};
  double acceleration = 4.0;  // [Unit: cells/s²] [Limit: > 0]
  double turnRate = 6.0;      // [Unit: rad/s] [Limit: > 0] how fast the heading may change
  double radius = 0.4;        // [Unit: cells] body radius [Limit: 0 < radius <= size/2]
  int hp = 100;               // [Limit: >= 1]
  ArmourClass armour = ArmourClass::Infantry;
  std::optional<Weapon> weapon;  // unarmed when empty

  pathing::Agent agent() const { return {size, capability}; }
  // Top speed on a terrain; 0 on terrains outside the capability.
  double speedOn(pathing::Terrain t) const;
  // The largest top speed over the capability's terrains.
  double maxSpeed() const;
  // What the planner charges it (issue 13: cost = time): 1 / top speed per terrain [Unit: s
  // per cell]; no cost where it has no speed.
  pathing::TerrainCosts terrainCosts() const;
  // Sets the same top speed on every terrain.
  void setSpeed(double cellsPerSecond) { speed.fill(cellsPerSecond); }
};

// Empty when the type is usable, else what is wrong with it (for error messages). The message
// begins with the field as scenario files spell it ("radius must be …", "speed on water …",
// "weapon: range …"): the scenario loader reports it at that key.
std::string problemWith(const UnitType& type);

}  // namespace warpath::units
