#pragma once
// Deliberately naive reference implementations, written from the definitions alone, that the
// fast pathing code is checked against. Correctness over speed; no shared code with pathing/.

#include <cmath>
#include <limits>
#include <queue>
#include <vector>

#include "pathing/grid_map.h"
#include "pathing/terrain.h"

namespace warpath::testing {

using pathing::Capability;
using pathing::Cell;
using pathing::GridMap;

// Largest s such that the s×s square anchored at c lies on the map, all in `capability`.
inline int bruteForceClearance(const GridMap& map, Capability capability, Cell c) {
  int s = 0;
  while (true) {
    const int next = s + 1;
    for (int dy = 0; dy < next; ++dy) {
      for (int dx = 0; dx < next; ++dx) {
        const Cell q{c.x + dx, c.y + dy};
        if (!map.contains(q) || !capability.allows(map.at(q))) return s;
      }
    }
    s = next;
  }
}

inline bool bruteForceStands(const GridMap& map, int size, Capability capability, Cell c) {
  return bruteForceClearance(map, capability, c) >= size;
}

// Dijkstra over the 8-connected grid with the agent rules (no corner cutting). Returns the
// cost from `start` to every cell, +infinity where unreachable.
inline std::vector<double> bruteForceDistances(const GridMap& map, int size, Capability capability,
                                               Cell start) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(map.cellCount(), inf);
  if (!bruteForceStands(map, size, capability, start)) return dist;
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[map.indexOf(start)] = 0.0;
  queue.push({0.0, map.indexOf(start)});
  while (!queue.empty()) {
    const auto [d, index] = queue.top();
    queue.pop();
    if (d > dist[index]) continue;
    const Cell c = map.cellAt(index);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const Cell n{c.x + dx, c.y + dy};
        if (!bruteForceStands(map, size, capability, n)) continue;
        if (dx != 0 && dy != 0 &&
            (!bruteForceStands(map, size, capability, {c.x + dx, c.y}) ||
             !bruteForceStands(map, size, capability, {c.x, c.y + dy}))) {
          continue;
        }
        const double nd = d + ((dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0);
        if (nd < dist[map.indexOf(n)] - 1e-12) {
          dist[map.indexOf(n)] = nd;
          queue.push({nd, map.indexOf(n)});
        }
      }
    }
  }
  return dist;
}

}  // namespace warpath::testing
