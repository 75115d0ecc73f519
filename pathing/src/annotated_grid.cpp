#include "pathing/annotated_grid.h"

#include <cstdlib>
#include <sstream>

#include "pathing/moves.h"

namespace warpath::pathing {

AgentLayer AgentLayer::compute(const GridMap& map, const ClearanceField& clearance, Agent agent) {
  AgentLayer layer;
  const int w = map.width();
  const int h = map.height();
  layer.moveMasks_.assign(map.cellCount(), 0);
  layer.components_.assign(map.cellCount(), 0);
  const auto stands = [&](int x, int y) { return clearance.at({x, y}) >= agent.size; };

  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!stands(x, y)) continue;
      std::uint8_t mask = 0;
      for (int d = 0; d < kDirectionCount; ++d) {
        const Direction& dir = kDirections[static_cast<std::size_t>(d)];
        if (!stands(x + dir.dx, y + dir.dy)) continue;
        if (isDiagonal(d)) {
          const Direction& a = kDirections[static_cast<std::size_t>(dir.cardinalA)];
          const Direction& b = kDirections[static_cast<std::size_t>(dir.cardinalB)];
          if (!stands(x + a.dx, y + a.dy) || !stands(x + b.dx, y + b.dy)) continue;
        }
        mask = static_cast<std::uint8_t>(mask | (1u << d));
      }
      layer.moveMasks_[map.indexOf({x, y})] = mask;
    }
  }

  // Moves are symmetric, so a flood fill over the cardinal moves alone labels components
  // (a legal diagonal implies both cardinal detours are legal).
  std::vector<std::uint32_t> stack;
  for (std::uint32_t seed = 0; seed < layer.components_.size(); ++seed) {
    if (layer.components_[seed] != 0 || !stands(map.cellAt(seed).x, map.cellAt(seed).y)) continue;
    const std::uint32_t id = ++layer.componentCount_;
    layer.components_[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::uint32_t cell = stack.back();
      stack.pop_back();
      const std::uint8_t mask = layer.moveMasks_[cell];
      for (int d = 0; d < 4; ++d) {
        if ((mask & (1u << d)) == 0) continue;
        const Direction& dir = kDirections[static_cast<std::size_t>(d)];
        const std::uint32_t next =
            static_cast<std::uint32_t>(static_cast<std::int64_t>(cell) + dir.dy * w + dir.dx);
        if (layer.components_[next] != 0) continue;
        layer.components_[next] = id;
        stack.push_back(next);
      }
    }
  }
  return layer;
}

AnnotatedGrid::AnnotatedGrid(GridMap map) : map_(std::move(map)) {}

const ClearanceField& AnnotatedGrid::clearance(Capability capability) const {
  std::lock_guard lock(mutex_);
  auto& slot = clearances_[capability];
  if (!slot) slot = std::make_unique<ClearanceField>(ClearanceField::compute(map_, capability));
  return *slot;
}

const AgentLayer& AnnotatedGrid::layer(Agent agent) const {
  const ClearanceField& field = clearance(agent.capability);
  std::lock_guard lock(mutex_);
  auto& slot = layers_[agent];
  if (!slot) slot = std::make_unique<AgentLayer>(AgentLayer::compute(map_, field, agent));
  return *slot;
}

std::size_t AnnotatedGrid::cacheBytes() const {
  std::lock_guard lock(mutex_);
  std::size_t bytes = 0;
  for (const auto& [capability, field] : clearances_) {
    bytes += field->values().size_bytes();
  }
  for (const auto& [agent, layer] : layers_) {
    bytes += layer->moveMasks().size_bytes() + layer->components().size_bytes();
  }
  return bytes;
}

std::optional<PathStatus> screenEndpoints(const AnnotatedGrid& grid, Agent agent, Cell start,
                                          Cell goal) {
  if (!grid.canStand(agent, start)) return PathStatus::InvalidStart;
  if (!grid.canStand(agent, goal)) return PathStatus::InvalidGoal;
  const AgentLayer& layer = grid.layer(agent);
  const GridMap& map = grid.map();
  if (layer.components()[map.indexOf(start)] != layer.components()[map.indexOf(goal)]) {
    return PathStatus::Unreachable;
  }
  return std::nullopt;
}

std::string findIllegalStep(const AnnotatedGrid& grid, Agent agent, std::span<const Cell> path) {
  if (path.empty()) return "path is empty";
  std::ostringstream problem;
  const auto cell = [](Cell c) {
    std::ostringstream out;
    out << '(' << c.x << ',' << c.y << ')';
    return out.str();
  };
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!grid.canStand(agent, path[i])) {
      problem << "step " << i << ": agent cannot stand on " << cell(path[i]);
      return problem.str();
    }
    if (i == 0) continue;
    const int dx = path[i].x - path[i - 1].x;
    const int dy = path[i].y - path[i - 1].y;
    if (std::abs(dx) > 1 || std::abs(dy) > 1 || (dx == 0 && dy == 0)) {
      problem << "step " << i << ": " << cell(path[i - 1]) << " -> " << cell(path[i])
              << " is not a single move";
      return problem.str();
    }
    if (dx != 0 && dy != 0 &&
        (!grid.canStand(agent, {path[i - 1].x + dx, path[i - 1].y}) ||
         !grid.canStand(agent, {path[i - 1].x, path[i - 1].y + dy}))) {
      problem << "step " << i << ": diagonal " << cell(path[i - 1]) << " -> " << cell(path[i])
              << " cuts a corner";
      return problem.str();
    }
  }
  return {};
}

double pathCost(std::span<const Cell> path) {
  double cost = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const bool diagonal = path[i].x != path[i - 1].x && path[i].y != path[i - 1].y;
    cost += diagonal ? kSqrt2 : 1.0;
  }
  return cost;
}

}  // namespace warpath::pathing
