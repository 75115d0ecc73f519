#include "render/palette.h"

#include <vector>

namespace warpath::render::palette {

Rgba terrainColour(pathing::Terrain t) {
  switch (t) {
    case pathing::Terrain::Ground:
      return kGround;
    case pathing::Terrain::Swamp:
      return kSwamp;
    case pathing::Terrain::Trees:
      return kTrees;
    case pathing::Terrain::Water:
      return kWater;
    case pathing::Terrain::Blocked:
      return kBlocked;
  }
  return pathing::isTraversable(t) ? kOtherTerrain : kBlocked;
}

Rgba teamColour(int team) {
  const int n = static_cast<int>(kTeams.size());
  return kTeams[static_cast<std::size_t>(((team % n) + n) % n)];
}

namespace {

std::vector<Rgba> makeGifPalette() {
  std::vector<Rgba> colours{kGround,     kSwamp, kTrees,     kWater,     kBlocked,  kOtherTerrain,
                            kBackground, kBlack, kWhite,     kHpGood,    kHpLost,   kWreck,
                            kWreckMark,  kStuck, kGraphNode, kInterEdge, kIntraEdge};
  colours.insert(colours.end(), kTeams.begin(), kTeams.end());
  colours.insert(colours.end(), kHeat.begin(), kHeat.end());
  // The cube covers whatever blending makes (translucent overlays over terrain).
  for (int r = 0; r < 6 && colours.size() < 256; ++r) {
    for (int g = 0; g < 6 && colours.size() < 256; ++g) {
      for (int b = 0; b < 6 && colours.size() < 256; ++b) {
        colours.push_back({static_cast<std::uint8_t>(r * 51), static_cast<std::uint8_t>(g * 51),
                           static_cast<std::uint8_t>(b * 51), 255});
      }
    }
  }
  return colours;
}

}  // namespace

std::span<const Rgba> gifPalette() {
  static const std::vector<Rgba> palette = makeGifPalette();  // immutable once built
  return palette;
}

}  // namespace warpath::render::palette
