#pragma once
// What one frame shows, as plain values: the world (or a replay) fills a FrameScene and the
// renderer draws it. The renderer never sees the world itself, so it cannot change it.
//
// Positions are in cell units with (0, 0) the map's top-left corner: a size-s unit anchored
// at cell (x, y) has its centre at (x + s/2, y + s/2).

#include <cstdint>
#include <string>
#include <vector>

#include "pathing/grid_map.h"

namespace warpath::render {

struct Point {
  float x = 0.0f;  // [Unit: cells]
  float y = 0.0f;  // [Unit: cells]
  constexpr bool operator==(const Point&) const = default;
};

enum class UnitState : std::uint8_t {
  Alive,
  Arrived,  // reached its goal; drawn like Alive
  Wreck,    // dead, its wreck still on the map: drawn as a wreck
};

struct UnitView {
  Point centre{};
  int size = 1;         // [Unit: cells] [Limit: >= 1] side of the square footprint
  int team = 0;         // [Limit: >= 0] colour kTeams[team % 8]
  int type = 0;         // [Limit: >= 0] shape: circle, square, triangle, diamond, hexagon, ...
  float facing = 0.0f;  // [Unit: radians] 0 = +x (east), pi/2 = +y (south, down the screen)
  float hp = 1.0f;      // [Limit: 0..1] fraction of full health
  UnitState state = UnitState::Alive;
  bool stuck = false;         // drawn by the stuck overlay
  std::vector<Point> path{};  // remaining waypoints (centres), drawn by the path overlays
  // The cooperative window the unit reserved (centres from now on), drawn by the reservations
  // overlay as a trail coloured by time; `windowSeconds` per point, from the frame's time.
  std::vector<Point> window{};
  std::vector<float> windowSeconds{};
};

// A shot drawn as a line in its shooter's team colour. Instant shots: the whole line from the
// shooter to the target, in the frame after they were fired. Projectiles in flight: a short
// streak ending at the shell's position, with a white head.
struct Tracer {
  Point from{};  // [Unit: cells] the shooter's centre (instant) or the streak's tail
  Point to{};    // [Unit: cells] the target's centre (instant) or the shell's position
  int team = 0;  // [Limit: >= 0] the shooter's team
  bool projectile = false;
  constexpr bool operator==(const Tracer&) const = default;
};

struct ArrivalZone {
  pathing::CellRect area{};
  int team = 0;
};

struct TeamCounts {
  int alive = 0;
  int arrived = 0;
  int dead = 0;
};

struct FrameScene {
  std::int64_t tick = 0;
  double seconds = 0.0;             // [Unit: s] simulated time
  std::vector<UnitView> units{};    // drawn in order: later units on top
  std::vector<TeamCounts> teams{};  // HUD line per team, indexed by team
  std::vector<ArrivalZone> arrivalZones{};
  std::vector<Tracer> shots{};  // drawn over the units
  // A line of text along the bottom edge (the viewer's status and keys); empty: none.
  std::string caption{};
  // The terrain as it is now, when it may differ from the map the renderer was created with
  // (terrain changed during the run, docs/terrain_changes.md): the renderer draws it again
  // whenever `terrainRevision` differs from the last it drew. Null: the map it was created
  // with. [Limit: the renderer's map size]
  const pathing::GridMap* terrain = nullptr;
  std::uint64_t terrainRevision = 0;  // 0: the map as loaded
};

}  // namespace warpath::render
