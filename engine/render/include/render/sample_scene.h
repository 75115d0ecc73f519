#pragma once
// Deterministic scenes with every kind of thing a frame can show (teams, unit types and
// sizes, wrecks, damage, paths, stuck units, arrival zones): one source for render tests,
// benchmarks and samples. Same inputs => same scene.

#include <cstdint>

#include "pathing/grid_map.h"
#include "render/frame_scene.h"

namespace warpath::render {

struct SampleSceneSpec {
  int units = 200;  // [Limit: >= 0]
  int teams = 2;    // [Limit: >= 1]
  std::uint64_t seed = 1;
  std::int64_t tick = 0;
};

// Units stand on traversable cells (where the map has any); every 11th is a wreck, every 7th
// damaged, every 13th stuck; each team has an arrival zone in a corner.
FrameScene sampleScene(const pathing::GridMap& map, const SampleSceneSpec& spec);

}  // namespace warpath::render
