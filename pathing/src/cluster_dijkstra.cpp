#include "cluster_dijkstra.h"

#include <algorithm>
#include <bit>

namespace warpath::pathing {

void ClusterDijkstra::run(const GridMap& map, const AgentLayer& layer, CellRect region, Cell source,
                          std::span<const Cell> targets, const CostField* costs) {
  region_ = region;
  expanded_ = 0;
  generated_ = 1;  // the source
  const std::size_t cells = static_cast<std::size_t>(region.width) * region.height;
  if (stamp_.size() < cells) {
    stamp_.assign(cells, 0);
    target_.assign(cells, 0);
    g_.assign(cells, 0.0);
    via_.assign(cells, 0);
    generation_ = 0;
  }
  // Stamps of earlier runs may have used a different region shape: a new generation
  // invalidates them all at once. Wrap-around clears everything.
  if (++generation_ >= (1u << 29)) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    std::fill(target_.begin(), target_.end(), 0);
    generation_ = 1;
  }
  const std::uint32_t openStamp = generation_ * 4 + 1;
  const std::uint32_t settled = settledStamp();

  std::size_t targetsLeft = 0;
  for (Cell t : targets) {
    if (!region.contains(t)) continue;
    std::uint32_t& mark = target_[local(t)];
    if (mark != generation_) {
      mark = generation_;
      ++targetsLeft;
    }
  }

  open_.clear();
  const std::uint8_t* masks = layer.moveMasks().data();
  const std::size_t start = local(source);
  stamp_[start] = openStamp;
  g_[start] = 0.0;
  open_.push(OpenList::makeKey(0.0, 0.0), static_cast<std::uint32_t>(start));
  const int width = region.width;
  while (!open_.empty()) {
    const std::uint32_t current = open_.pop();
    if (stamp_[current] == settled) continue;
    stamp_[current] = settled;
    ++expanded_;
    if (target_[current] == generation_ && --targetsLeft == 0 && !targets.empty()) break;
    const int lx = static_cast<int>(current % static_cast<std::uint32_t>(width));
    const int ly = static_cast<int>(current / static_cast<std::uint32_t>(width));
    const Cell here{region.x + lx, region.y + ly};
    const double g = g_[current];
    for (unsigned mask = masks[map.indexOf(here)]; mask != 0; mask &= mask - 1) {
      const int d = std::countr_zero(mask);
      const Direction& dir = kDirections[static_cast<std::size_t>(d)];
      const int nx = lx + dir.dx;
      const int ny = ly + dir.dy;
      if (nx < 0 || ny < 0 || nx >= width || ny >= region.height) continue;
      const std::size_t next = static_cast<std::size_t>(ny) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(nx);
      const double ng = g + (costs ? costs->moveCost(here, d) : dir.cost);
      if (stamp_[next] == settled || (stamp_[next] == openStamp && ng >= g_[next])) continue;
      stamp_[next] = openStamp;
      g_[next] = ng;
      via_[next] = static_cast<std::uint8_t>(d);
      open_.push(OpenList::makeKey(ng, ng), static_cast<std::uint32_t>(next));
      ++generated_;
    }
  }
}

void ClusterDijkstra::appendSteps(Cell target, std::vector<std::uint8_t>* steps) const {
  const std::size_t first = steps->size();
  Cell at = target;
  std::size_t index = local(at);
  while (g_[index] > 0.0) {
    const std::uint8_t d = via_[index];
    steps->push_back(d);
    at = {at.x - kDirections[d].dx, at.y - kDirections[d].dy};
    index = local(at);
  }
  std::reverse(steps->begin() + static_cast<std::ptrdiff_t>(first), steps->end());
}

}  // namespace warpath::pathing
