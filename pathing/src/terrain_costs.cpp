#include "pathing/terrain_costs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pathing/moves.h"

namespace warpath::pathing {

namespace {
constexpr double kNoCost = std::numeric_limits<double>::infinity();

bool hasCost(double c) {
  return c > 0.0 && std::isfinite(c);
}
}  // namespace

TerrainCosts TerrainCosts::uniform(Capability capability) {
  TerrainCosts costs;
  for (int slot = 0; slot < kTraversableTerrainSlots; ++slot) {
    if (capability.allows(static_cast<Terrain>(slot)))
      costs.perCell[static_cast<std::size_t>(slot)] = 1.0;
  }
  return costs;
}

Capability TerrainCosts::capability() const {
  std::uint8_t mask = 0;
  for (int slot = 0; slot < kTraversableTerrainSlots; ++slot) {
    if (hasCost(perCell[static_cast<std::size_t>(slot)]))
      mask |= static_cast<std::uint8_t>(1u << slot);
  }
  return Capability::fromMask(mask);
}

CostField::CostField(const AnnotatedGrid& grid, Agent agent, const TerrainCosts& costs)
    : agent_(agent),
      costs_(costs),
      width_(grid.map().width()),
      anchor_(grid.map().cellCount(), kNoCost),
      cheapest_(kNoCost) {
  fill(grid, {0, 0, grid.map().width(), grid.map().height()});
}

void CostField::update(const AnnotatedGrid& grid, CellRect area) {
  // An anchor's footprint reaches size - 1 cells right and down of it.
  const int reach = std::max(1, agent_.size) - 1;
  fill(grid, {area.x - reach, area.y - reach, area.width + reach, area.height + reach});
}

void CostField::fill(const AnnotatedGrid& grid, CellRect region) {
  const GridMap& map = grid.map();
  const int x0 = std::max(0, region.x);
  const int y0 = std::max(0, region.y);
  const int x1 = std::min(map.width(), region.x + region.width);
  const int y1 = std::min(map.height(), region.y + region.height);
  const int s = std::max(1, agent_.size);
  const auto cellCost = [&](int x, int y) {
    const Terrain t = map.at({x, y});
    const double c = isTraversable(t) ? costs_.perCell[static_cast<std::size_t>(t)] : kNoCost;
    return hasCost(c) ? c : kNoCost;
  };
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      double& anchor = anchor_[map.indexOf({x, y})];
      anchor = kNoCost;
      if (!grid.canStand(agent_, {x, y})) continue;
      // The slowest terrain under the footprint (s is small: a direct scan).
      double worst = 0.0;
      for (int dy = 0; dy < s; ++dy) {
        for (int dx = 0; dx < s; ++dx)
          worst = std::max(worst, cellCost(x + dx, y + dy));
      }
      anchor = worst;
      cheapest_ = std::min(cheapest_, worst);
    }
  }
}

double CostField::pathCost(std::span<const Cell> path) const {
  double total = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int d = directionOf(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
    total += d < 0 ? kNoCost : moveCost(path[i - 1], d);
  }
  return total;
}

}  // namespace warpath::pathing
