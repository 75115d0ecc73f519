#pragma once
// Deterministic synthetic maps and queries for tests, benchmarks and samples: terrain patches
// of random size scattered over a map, so maps have corridors, chokepoints and open areas
// rather than salt-and-pepper noise. Same inputs => same map (and same queries) on every
// platform.

#include <cstdint>
#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/grid_map.h"
#include "pathing/random.h"

namespace warpath::pathing {

struct RandomMapSpec {
  int width = 64;   // [Unit: cells] [Limit: >= 1]
  int height = 64;  // [Unit: cells] [Limit: >= 1]
  std::uint64_t seed = 1;
  // Target share of cells per terrain, in percent; ground fills the rest. Patches overlap, so
  // the shares are approximate. [Limit: each 0..100, sum <= 100]
  int blockedPercent = 20;
  int swampPercent = 10;
  int treesPercent = 10;
  int waterPercent = 10;
  int maxPatch = 6;  // [Unit: cells] [Limit: >= 1] largest patch side; 1 gives independent cells
};

// Empty when the spec is usable, else what is wrong, naming the field, its limit and the value
// ("width must be >= 1 (got 0)"). generateRandomMap throws std::invalid_argument with this
// message; callers taking user input check it first.
std::string problemWith(const RandomMapSpec& spec);

// [Limit: problemWith(spec).empty(), else std::invalid_argument]
GridMap generateRandomMap(const RandomMapSpec& spec);

// The HAA* paper's derived maps ("soft obstacles"): exactly round(percent% of the map's
// traversable cells) cells that are traversable and not already `soft` become `soft`, painted
// as patches of up to kSoftPatchSide × kSoftPatchSide cells; blocked cells and cells already
// `soft` never change. Capped at the number of cells that can change. With one seed, a larger
// percent paints a superset of a smaller one. [Limit: percent 0..100; soft traversable; else
// std::invalid_argument naming the argument, the limit and the value]
inline constexpr int kSoftPatchSide = 4;
GridMap withSoftObstacles(const GridMap& map, int percent, Terrain soft, std::uint64_t seed);

struct Query {
  Cell start;
  Cell goal;
};

// Draws random queries for one agent kind on an annotated grid. Holds the cells the agent can
// stand on grouped by connected component, so every draw is O(log components).
class QuerySampler {
 public:
  QuerySampler(const AnnotatedGrid& grid, Agent agent);

  // False when the agent can stand nowhere on the map.
  bool canStandAnywhere() const { return !cells_.empty(); }
  // False when no two distinct cells are mutually reachable for the agent.
  bool hasReachablePair() const { return pairWeights_.back() > 0; }

  // Start and goal independently uniform over the cells where the agent can stand: either
  // may be unreachable from the other, or equal to it. [Limit: canStandAnywhere(), else
  // std::invalid_argument]
  Query anyPair(SplitMix64& rng) const;
  // Uniform over the ordered pairs of distinct, mutually reachable cells.
  // [Limit: hasReachablePair(), else std::invalid_argument]
  Query reachablePair(SplitMix64& rng) const;

 private:
  const GridMap* map_;
  std::vector<std::uint32_t> cells_;           // standable cell indices, grouped by component
  std::vector<std::uint32_t> componentBegin_;  // component k: cells_[begin[k], begin[k+1])
  std::vector<std::uint64_t> pairWeights_;     // prefix sums of n(n-1) per component, from 0
};

}  // namespace warpath::pathing
