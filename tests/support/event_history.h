#pragma once
// World::events() holds the last step's events only; tests that look at a whole run keep them,
// and tests of one step count them.

#include <algorithm>
#include <vector>

#include "engine/world.h"

namespace warpath::testing {

// Steps `world` `steps` times and returns every event of those steps (and of what was logged
// before the first), in order.
inline std::vector<engine::Event> stepKeepingEvents(engine::World& world, int steps) {
  std::vector<engine::Event> all;
  for (int i = 0; i < steps; ++i) {
    world.step();
    all.insert(all.end(), world.events().begin(), world.events().end());
  }
  return all;
}

// How many of the last step's events are of `kind`.
inline int countEvents(const engine::World& world, engine::EventKind kind) {
  return static_cast<int>(std::count_if(world.events().begin(), world.events().end(),
                                        [&](const engine::Event& e) { return e.kind == kind; }));
}

}  // namespace warpath::testing
