#pragma once
// Local collision avoidance with Box2D 2.4, behind a header that does not include Box2D (only
// engine/src/physics includes it). Units are dynamic circles; terrain a unit may not enter is
// static geometry whose collision category only the masks of the units it forbids include.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "engine/handle.h"
#include "pathing/grid_map.h"
#include "units/steering.h"

namespace warpath::engine {

// Collision categories: one per traversable terrain slot, one for blocked cells and the map
// border, one for units. A unit's mask is the categories of the terrains its capability
// forbids, plus blocked and units.
inline constexpr std::uint16_t kBlockedCategory = 1u << pathing::kTraversableTerrainSlots;
inline constexpr std::uint16_t kUnitCategory = kBlockedCategory << 1;
constexpr std::uint16_t terrainCategory(pathing::Terrain t) {
  return pathing::isTraversable(t) ? static_cast<std::uint16_t>(1u << static_cast<unsigned>(t))
                                   : kBlockedCategory;
}
std::uint16_t collisionMaskFor(pathing::Capability capability);

struct PhysicsStats {
  int staticBoxes = 0;  // boxes of terrain geometry, border included
  int bodies = 0;       // in the simulation now
};

class Physics {
 public:
  // Builds the static geometry of every terrain that some capability in `capabilities`
  // forbids (blocked cells and the border always): cells merged into row runs, then runs
  // stacked into boxes. [Unit: 1 cell = 1 Box2D metre]
  Physics(const pathing::GridMap& map, std::span<const pathing::Capability> capabilities);
  ~Physics();
  Physics(const Physics&) = delete;
  Physics& operator=(const Physics&) = delete;

  // Adds a dynamic circle (handles are never reused). Every other call takes a handle this
  // Physics returned; any other handle is a bug (an invariant in checked builds, ignored and
  // read as a body at rest at the origin in Release).
  // `owner` is what touching() reports for this body (the engine gives the unit's index).
  BodyId addBody(units::Vec2 centre, double radius, pathing::Capability capability,
                 std::uint32_t owner = 0);
  // Turns a body into a fixed obstacle (a wreck): it stops and no longer moves when pushed.
  void freeze(BodyId body);
  // A braced body (a unit holding its position) weighs kBracedMassFactor times its own: others
  // slide around it instead of driving through it. Unbraced, it weighs what its area does.
  void setBraced(BodyId body, bool braced);
  static constexpr float kBracedMassFactor = 1000.0f;
  // Takes a body out of the simulation. Its last position and a zero velocity stay readable.
  void removeBody(BodyId body);
  // Puts a body at `centre` at rest (a unit pushed off terrain that became impassable to it).
  void moveBody(BodyId body, units::Vec2 centre);
  // Terrain that changed during a run (docs/terrain_changes.md): every cell of `area` (inside the
  // map) becomes `terrain`, and the static geometry is built again from the whole map as the
  // constructor builds it. Obstacles that stand on the planning grid (wrecks) are bodies of
  // their own and never part of this map.
  void setTerrain(pathing::CellRect area, pathing::Terrain terrain);
  void setVelocity(BodyId body, units::Vec2 velocity);
  // Advances every body by dt seconds.
  void step(double dt);
  units::Vec2 position(BodyId body) const;
  units::Vec2 velocity(BodyId body) const;
  // The owners of the moving bodies whose shapes touch `body`'s after the last step, in
  // Box2D's contact order (deterministic for one sequence of calls); `out` is overwritten.
  void touching(BodyId body, std::vector<std::uint32_t>& out) const;
  const PhysicsStats& stats() const { return stats_; }

 private:
  // The body behind a handle; null when removed or when the handle is not one of ours.
  bool known(BodyId body) const;
  // (Re)builds the static body of the terrain from map_.
  void buildTerrain();
  struct Impl;
  std::unique_ptr<Impl> impl_;
  PhysicsStats stats_;
  pathing::GridMap map_;     // the terrain the static geometry is built from
  std::uint16_t forbidden_;  // categories some unit's mask includes (blocked always)
};

}  // namespace warpath::engine
