#pragma once
// Every colour the renderer draws with, in one place, so that the GIF writer's fixed palette
// holds each of them exactly and quantising a frame never shifts terrain or team colours.

#include <array>
#include <span>

#include "pathing/terrain.h"
#include "render/image.h"

namespace warpath::render::palette {

inline constexpr Rgba kGround{178, 186, 128};
inline constexpr Rgba kSwamp{112, 122, 72};
inline constexpr Rgba kTrees{38, 96, 44};
inline constexpr Rgba kWater{44, 92, 156};
inline constexpr Rgba kBlocked{52, 50, 56};
inline constexpr Rgba kOtherTerrain{196, 124, 196};  // traversable kinds beyond the named four
inline constexpr Rgba kBackground{16, 16, 20};       // outside the map (letterbox)

inline constexpr Rgba kBlack{0, 0, 0};
inline constexpr Rgba kWhite{255, 255, 255};
inline constexpr Rgba kHpGood{60, 220, 60};
inline constexpr Rgba kHpLost{200, 30, 30};
inline constexpr Rgba kWreck{84, 72, 64};
inline constexpr Rgba kWreckMark{30, 26, 24};
inline constexpr Rgba kStuck{255, 0, 255};
inline constexpr Rgba kGraphNode{255, 255, 255};
inline constexpr Rgba kInterEdge{255, 96, 64};
inline constexpr Rgba kIntraEdge{255, 214, 64};
inline constexpr Rgba kClusterBorder{0, 0, 0};

// Team i is drawn in kTeams[i % size].
inline constexpr std::array<Rgba, 8> kTeams{{{70, 140, 255},
                                             {232, 48, 40},
                                             {250, 210, 40},
                                             {210, 70, 220},
                                             {60, 222, 222},
                                             {250, 140, 30},
                                             {236, 236, 236},
                                             {255, 120, 160}}};

// Clearance heat map: value 1 is kHeat[0], values >= kHeat.size() the last entry.
inline constexpr std::array<Rgba, 6> kHeat{
    {{200, 0, 0}, {240, 110, 0}, {240, 200, 0}, {150, 220, 0}, {40, 200, 90}, {0, 160, 200}}};

Rgba terrainColour(pathing::Terrain t);
Rgba teamColour(int team);

// The colours above, exactly, followed by a 6x6x6 colour cube: 256 entries at most.
std::span<const Rgba> gifPalette();

}  // namespace warpath::render::palette
