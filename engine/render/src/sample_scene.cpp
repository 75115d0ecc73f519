#include "render/sample_scene.h"

#include <algorithm>
#include <numbers>

#include "pathing/random.h"

namespace warpath::render {

FrameScene sampleScene(const pathing::GridMap& map, const SampleSceneSpec& spec) {
  pathing::SplitMix64 rng(spec.seed);
  FrameScene scene;
  scene.tick = spec.tick;
  scene.seconds = static_cast<double>(spec.tick) / 30.0;
  const int teams = std::max(1, spec.teams);
  scene.teams.resize(static_cast<std::size_t>(teams));
  const int zone = std::max(1, std::min(map.width(), map.height()) / 6);
  for (int t = 0; t < teams; ++t) {
    const bool right = t % 2 == 1;
    const bool bottom = (t / 2) % 2 == 1;
    scene.arrivalZones.push_back(
        {{right ? map.width() - zone : 0, bottom ? map.height() - zone : 0, zone, zone}, t});
  }
  const auto randomCell = [&] {
    // A traversable cell if one turns up within a few draws, else any cell.
    pathing::Cell c{};
    for (int attempt = 0; attempt < 16; ++attempt) {
      c = {rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
      if (pathing::isTraversable(map.at(c))) break;
    }
    return c;
  };
  for (int i = 0; i < spec.units; ++i) {
    UnitView u;
    u.size = 1 + i % 3;
    u.team = i % teams;
    u.type = (i / teams) % 4;
    const pathing::Cell anchor = randomCell();
    const float half = static_cast<float>(u.size) / 2.0f;
    u.centre = {static_cast<float>(anchor.x) + half, static_cast<float>(anchor.y) + half};
    u.facing = static_cast<float>(rng.unit() * 2.0 * std::numbers::pi);
    u.hp = i % 7 == 3 ? static_cast<float>(0.2 + 0.6 * rng.unit()) : 1.0f;
    u.state = i % 11 == 10 ? UnitState::Wreck : UnitState::Alive;
    u.stuck = i % 13 == 5;
    Point p = u.centre;
    for (int k = 0; k < 4; ++k) {
      p.x = std::clamp(p.x + static_cast<float>(rng.between(-4, 4)), half,
                       static_cast<float>(map.width()) - half);
      p.y = std::clamp(p.y + static_cast<float>(rng.between(-4, 4)), half,
                       static_cast<float>(map.height()) - half);
      u.path.push_back(p);
    }
    TeamCounts& counts = scene.teams[static_cast<std::size_t>(u.team)];
    if (u.state == UnitState::Wreck) {
      ++counts.dead;
    } else {
      ++counts.alive;
    }
    scene.units.push_back(std::move(u));
  }
  return scene;
}

}  // namespace warpath::render
