#include "pathing/map_generator.h"

#include <algorithm>
#include <array>
#include <span>
#include <vector>

#include "limit_messages.h"
#include "pathing/random.h"

namespace warpath::pathing {

std::string problemWith(const RandomMapSpec& spec) {
  if (spec.width < 1) return limits::atLeast("width", 1, spec.width);
  if (spec.height < 1) return limits::atLeast("height", 1, spec.height);
  const std::array<std::pair<const char*, int>, 4> shares{{{"blockedPercent", spec.blockedPercent},
                                                           {"swampPercent", spec.swampPercent},
                                                           {"treesPercent", spec.treesPercent},
                                                           {"waterPercent", spec.waterPercent}}};
  int sum = 0;
  for (const auto& [field, percent] : shares) {
    if (percent < 0 || percent > 100) return limits::between(field, 0, 100, percent);
    sum += percent;
  }
  if (sum > 100) {
    return "blockedPercent + swampPercent + treesPercent + waterPercent must be <= 100 (got " +
           std::to_string(sum) + ")";
  }
  if (spec.maxPatch < 1) return limits::atLeast("maxPatch", 1, spec.maxPatch);
  return {};
}

GridMap generateRandomMap(const RandomMapSpec& spec) {
  limits::require(problemWith(spec));
  GridMap map(spec.width, spec.height, Terrain::Ground);
  SplitMix64 rng(spec.seed);
  const std::array<std::pair<Terrain, int>, 4> shares{{{Terrain::Blocked, spec.blockedPercent},
                                                       {Terrain::Swamp, spec.swampPercent},
                                                       {Terrain::Trees, spec.treesPercent},
                                                       {Terrain::Water, spec.waterPercent}}};
  const long long cells = static_cast<long long>(spec.width) * spec.height;
  const int maxPatch = spec.maxPatch;
  for (const auto& [terrain, percent] : shares) {
    // Paint patches until roughly `percent` of the map has been painted with this terrain.
    long long budget = cells * percent / 100;
    while (budget > 0) {
      const int w = rng.between(1, maxPatch);
      const int h = rng.between(1, maxPatch);
      const int x0 = rng.between(0, spec.width - 1);
      const int y0 = rng.between(0, spec.height - 1);
      for (int y = y0; y < std::min(spec.height, y0 + h); ++y) {
        for (int x = x0; x < std::min(spec.width, x0 + w); ++x)
          map.set({x, y}, terrain);
      }
      budget -= static_cast<long long>(w) * h;
    }
  }
  return map;
}

GridMap withSoftObstacles(const GridMap& map, int percent, Terrain soft, std::uint64_t seed) {
  if (percent < 0 || percent > 100)
    throw std::invalid_argument(limits::between("percent", 0, 100, percent));
  if (!isTraversable(soft)) {
    throw std::invalid_argument("soft must be a traversable terrain (got " +
                                std::string(terrainName(soft)) + ")");
  }
  GridMap out = map;
  const std::span<const Terrain> cells = map.cells();
  std::vector<std::uint32_t> candidates;  // traversable cells not yet `soft`
  std::size_t traversable = 0;
  for (std::uint32_t i = 0; i < cells.size(); ++i) {
    if (!isTraversable(cells[i])) continue;
    ++traversable;
    if (cells[i] != soft) candidates.push_back(i);
  }
  const std::size_t share = static_cast<std::size_t>(percent);
  std::size_t remaining = std::min(candidates.size(), (traversable * share + 50) / 100);

  SplitMix64 rng(seed);
  while (remaining > 0) {
    // Anchors are drawn among the candidates, so every patch paints at least its anchor and
    // the loop ends; an anchor painted by an earlier patch is dropped and drawn again.
    const std::uint32_t pick = rng.below(static_cast<std::uint32_t>(candidates.size()));
    const Cell anchor = map.cellAt(candidates[pick]);
    candidates[pick] = candidates.back();
    candidates.pop_back();
    if (out.at(anchor) == soft) continue;
    const int w = rng.between(1, kSoftPatchSide);
    const int h = rng.between(1, kSoftPatchSide);
    // A random offset places the anchor anywhere inside its patch, so patches do not all grow
    // down and right from the cell drawn.
    const int x0 = anchor.x - rng.between(0, w - 1);
    const int y0 = anchor.y - rng.between(0, h - 1);
    for (int y = y0; y < y0 + h && remaining > 0; ++y) {
      for (int x = x0; x < x0 + w && remaining > 0; ++x) {
        const Terrain t = out.at({x, y});
        if (!isTraversable(t) || t == soft) continue;
        out.set({x, y}, soft);
        --remaining;
      }
    }
  }
  return out;
}

QuerySampler::QuerySampler(const AnnotatedGrid& grid, Agent agent) : map_(&grid.map()) {
  const AgentLayer& layer = grid.layer(agent);
  const std::span<const std::uint32_t> components = layer.components();
  // Counting sort of the standable cells by component id (ids run 1..count; 0 = cannot stand),
  // in cell order within a component so the layout is deterministic.
  const std::size_t count = layer.componentCount();
  componentBegin_.assign(count + 1, 0);
  for (std::uint32_t id : components) {
    if (id != 0) ++componentBegin_[id];  // size of component id lands at slot id (shifted below)
  }
  std::uint32_t running = 0;
  for (std::size_t k = 1; k <= count; ++k) {
    const std::uint32_t size = componentBegin_[k];
    componentBegin_[k - 1] = running;
    running += size;
  }
  componentBegin_[count] = running;
  cells_.resize(running);
  std::vector<std::uint32_t> fill(componentBegin_.begin(), componentBegin_.end() - 1);
  for (std::uint32_t i = 0; i < components.size(); ++i) {
    if (components[i] != 0) cells_[fill[components[i] - 1]++] = i;
  }
  pairWeights_.assign(count + 1, 0);
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint64_t n = componentBegin_[k + 1] - componentBegin_[k];
    pairWeights_[k + 1] = pairWeights_[k] + n * (n - 1);
  }
}

Query QuerySampler::anyPair(SplitMix64& rng) const {
  if (!canStandAnywhere()) {
    throw std::invalid_argument("anyPair: the agent can stand nowhere on the map");
  }
  const auto n = static_cast<std::uint32_t>(cells_.size());
  const Cell start = map_->cellAt(cells_[rng.below(n)]);
  const Cell goal = map_->cellAt(cells_[rng.below(n)]);
  return {start, goal};
}

Query QuerySampler::reachablePair(SplitMix64& rng) const {
  if (!hasReachablePair()) {
    throw std::invalid_argument("reachablePair: no two distinct cells are mutually reachable");
  }
  // A component is chosen with probability proportional to its ordered pairs n(n-1), then two
  // distinct cells in it. The modulo bias is below 2^-25 for any map that fits in memory.
  const std::uint64_t r = rng.next() % pairWeights_.back();
  const auto k = static_cast<std::size_t>(
      std::upper_bound(pairWeights_.begin(), pairWeights_.end(), r) - pairWeights_.begin() - 1);
  const std::uint32_t begin = componentBegin_[k];
  const std::uint32_t n = componentBegin_[k + 1] - begin;
  const std::uint32_t s = rng.below(n);
  std::uint32_t g = rng.below(n - 1);
  if (g >= s) ++g;
  return {map_->cellAt(cells_[begin + s]), map_->cellAt(cells_[begin + g])};
}

}  // namespace warpath::pathing
