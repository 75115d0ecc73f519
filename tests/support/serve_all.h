#pragma once
// Draining a path service's queue, tick by tick, as the world would.

#include <cstdint>
#include <vector>

#include "engine/path_service.h"

namespace warpath::testing {

struct Served {
  std::vector<engine::PathDelivery> deliveries;
  std::vector<std::uint64_t> spentPerTick;  // the expansions each serve() spent
};

// Serves until nothing is queued.
inline Served serveAll(engine::PathService& service) {
  Served s;
  while (service.queued() > 0)
    s.spentPerTick.push_back(service.serve(s.deliveries));
  return s;
}

}  // namespace warpath::testing
