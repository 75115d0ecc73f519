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
    : width_(grid.map().width()), anchor_(grid.map().cellCount(), kNoCost), cheapest_(kNoCost) {
  const GridMap& map = grid.map();
  const int w = map.width();
  const int h = map.height();
  const int s = std::max(1, agent.size);
  // Per cell, then the slowest over each footprint: a sliding maximum along rows, then along
  // columns (s is small, so a direct scan of s cells each way).
  std::vector<double> cell(map.cellCount(), kNoCost);
  for (std::uint32_t i = 0; i < map.cellCount(); ++i) {
    const Terrain t = map.at(map.cellAt(i));
    if (!isTraversable(t)) continue;
    const double c = costs.perCell[static_cast<std::size_t>(t)];
    if (hasCost(c)) cell[i] = c;
  }
  std::vector<double> rowMax(map.cellCount(), kNoCost);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x + s <= w; ++x) {
      double worst = 0.0;
      for (int k = 0; k < s; ++k)
        worst = std::max(worst, cell[map.indexOf({x + k, y})]);
      rowMax[map.indexOf({x, y})] = worst;
    }
  }
  for (int y = 0; y + s <= h; ++y) {
    for (int x = 0; x + s <= w; ++x) {
      if (!grid.canStand(agent, {x, y})) continue;
      double worst = 0.0;
      for (int k = 0; k < s; ++k)
        worst = std::max(worst, rowMax[map.indexOf({x, y + k})]);
      anchor_[map.indexOf({x, y})] = worst;
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
