#pragma once
// What most pathing tests start from: the catalogue's capabilities and maps written inline as
// MovingAI rows ("type octile" header included). One definition, so that test files can be
// compiled together (the test targets are unity builds).

#include <gtest/gtest.h>

#include <string>

#include "pathing/grid_map.h"
#include "pathing/map_io.h"
#include "pathing/terrain.h"

namespace warpath::pathing {

inline constexpr Capability kGround = Capability::of({Terrain::Ground});
inline constexpr Capability kInfantry =
    Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees});
inline constexpr Capability kAmphibious =
    Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water});
inline constexpr Capability kWater = Capability::of({Terrain::Water});

// The map a MovingAI text describes; a parse error fails the calling test.
inline GridMap mapFromRows(const std::string& text) {
  auto map = parseMap(text, "inline");
  EXPECT_TRUE(map) << map.error().describe();
  return map.value();
}

}  // namespace warpath::pathing
