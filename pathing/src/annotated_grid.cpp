#include "pathing/annotated_grid.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "pathing/moves.h"

namespace warpath::pathing {

namespace {

// Bit d set when an agent of `size` anchored at (x, y) may step in direction d: it stands at
// both ends and, on a diagonal, beside it (no corner cutting).
std::uint8_t movesFrom(const ClearanceField& clearance, int size, int x, int y) {
  const auto stands = [&](int cx, int cy) { return clearance.at({cx, cy}) >= size; };
  if (!stands(x, y)) return 0;
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
  return mask;
}

}  // namespace

AgentLayer AgentLayer::compute(const GridMap& map, const ClearanceField& clearance, Agent agent) {
  AgentLayer layer;
  layer.moveMasks_.assign(map.cellCount(), 0);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x)
      layer.moveMasks_[map.indexOf({x, y})] = movesFrom(clearance, agent.size, x, y);
  }
  layer.labelComponents(map, clearance, agent);
  return layer;
}

void AgentLayer::update(const GridMap& map, const ClearanceField& clearance, Agent agent,
                        CellRect changed) {
  if (changed.width <= 0 || changed.height <= 0) return;
  // A cell's moves depend on the cells around it.
  const int x0 = std::max(0, changed.x - 1);
  const int y0 = std::max(0, changed.y - 1);
  const int x1 = std::min(map.width(), changed.x + changed.width + 1);
  const int y1 = std::min(map.height(), changed.y + changed.height + 1);
  bool differs = false;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint32_t i = map.indexOf({x, y});
      const std::uint8_t now = movesFrom(clearance, agent.size, x, y);
      // A cell where the agent now stands alone, or no longer does, changes components too.
      const bool stands = clearance.values()[i] >= agent.size;
      differs = differs || now != moveMasks_[i] || stands != (components_[i] != 0);
      moveMasks_[i] = now;
    }
  }
  if (differs) labelComponents(map, clearance, agent);
}

void AgentLayer::labelComponents(const GridMap& map, const ClearanceField& clearance, Agent agent) {
  // Moves are symmetric, so a flood fill over the cardinal moves alone labels components
  // (a legal diagonal implies both cardinal detours are legal).
  const int w = map.width();
  components_.assign(map.cellCount(), 0);
  componentCount_ = 0;
  std::vector<std::uint32_t> stack;
  for (std::uint32_t seed = 0; seed < components_.size(); ++seed) {
    if (components_[seed] != 0 || clearance.values()[seed] < agent.size) continue;
    const std::uint32_t id = ++componentCount_;
    components_[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::uint32_t cell = stack.back();
      stack.pop_back();
      const std::uint8_t mask = moveMasks_[cell];
      for (int d = 0; d < 4; ++d) {
        if ((mask & (1u << d)) == 0) continue;
        const Direction& dir = kDirections[static_cast<std::size_t>(d)];
        const std::uint32_t next =
            static_cast<std::uint32_t>(static_cast<std::int64_t>(cell) + dir.dy * w + dir.dx);
        if (components_[next] != 0) continue;
        components_[next] = id;
        stack.push_back(next);
      }
    }
  }
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

CellRect AnnotatedGrid::clip(CellRect area) const {
  const int x0 = std::max(0, area.x);
  const int y0 = std::max(0, area.y);
  const int x1 = std::min(map_.width(), area.x + std::max(0, area.width));
  const int y1 = std::min(map_.height(), area.y + std::max(0, area.height));
  if (x1 <= x0 || y1 <= y0) return {x0, y0, 0, 0};
  return {x0, y0, x1 - x0, y1 - y0};
}

TerrainChange AnnotatedGrid::setTerrain(CellRect area, Terrain terrain) {
  area = clip(area);
  bool changed = false;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      const std::size_t i = map_.indexOf(c);
      if (!obstacles_.empty() && obstacles_[i] > 0) {
        underneath_[i] = terrain;
      } else if (map_.at(c) != terrain) {
        map_.set(c, terrain);
        changed = true;
      }
    }
  }
  if (changed) refresh(area);
  return {area, changed};
}

TerrainChange AnnotatedGrid::placeObstacle(CellRect area) {
  area = clip(area);
  if (obstacles_.empty()) {
    obstacles_.assign(map_.cellCount(), 0);
    underneath_.assign(map_.cellCount(), Terrain::Blocked);
  }
  bool changed = false;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      const std::size_t i = map_.indexOf(c);
      if (obstacles_[i]++ > 0) continue;
      underneath_[i] = map_.at(c);
      if (map_.at(c) != Terrain::Blocked) {
        map_.set(c, Terrain::Blocked);
        changed = true;
      }
    }
  }
  if (changed) refresh(area);
  return {area, changed};
}

TerrainChange AnnotatedGrid::clearObstacle(CellRect area) {
  area = clip(area);
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      if (obstacles_.empty() || obstacles_[map_.indexOf({x, y})] == 0)
        throw std::invalid_argument("clearObstacle: no obstacle stands on (" + std::to_string(x) +
                                    "," + std::to_string(y) + ")");
    }
  }
  bool changed = false;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const Cell c{x, y};
      const std::size_t i = map_.indexOf(c);
      if (--obstacles_[i] > 0 || underneath_[i] == map_.at(c)) continue;
      map_.set(c, underneath_[i]);
      changed = true;
    }
  }
  if (changed) refresh(area);
  return {area, changed};
}

void AnnotatedGrid::refresh(CellRect area) {
  ++revision_;
  std::lock_guard lock(mutex_);
  for (auto& [capability, field] : clearances_) {
    const CellRect changed = field->update(map_, area);
    for (auto& [agent, layer] : layers_) {
      if (agent.capability == capability) layer->update(map_, *field, agent, changed);
    }
  }
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
