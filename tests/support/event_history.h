#pragma once
// World::events() holds the last step's events only; tests that look at a whole run keep them.

#include <vector>

#include "engine/world.h"

namespace warpath::engine::testing {

// Steps `world` `steps` times and returns every event of those steps (and of what was logged
// before the first), in order.
inline std::vector<Event> stepKeepingEvents(World& world, int steps) {
  std::vector<Event> all;
  for (int i = 0; i < steps; ++i) {
    world.step();
    all.insert(all.end(), world.events().begin(), world.events().end());
  }
  return all;
}

}  // namespace warpath::engine::testing
