#include "engine/path_service.h"

#include <chrono>
#include <stdexcept>

#include "engine/fnv1a.h"
#include "pathing/moves.h"

namespace warpath::engine {

using namespace pathing;

PlannedPath planned(std::vector<Cell> cells) {
  Fnv1a h;
  for (const Cell& c : cells) {
    h.add(static_cast<std::uint32_t>(c.x), 4);
    h.add(static_cast<std::uint32_t>(c.y), 4);
  }
  std::vector<double> remaining(cells.size(), 0.0);
  for (std::size_t i = cells.size(); i-- > 1;) {
    const bool diagonal = cells[i].x != cells[i - 1].x && cells[i].y != cells[i - 1].y;
    remaining[i - 1] = remaining[i] + (diagonal ? kSqrt2 : 1.0);
  }
  return {std::move(cells), std::move(remaining), h.value()};
}

std::string problemWith(const PathServiceSettings& settings) {
  if (settings.clusterSize < 2 || settings.clusterSize > kMaxClusterSize) {
    return "clusterSize must be 2.." + std::to_string(kMaxClusterSize) + " (got " +
           std::to_string(settings.clusterSize) + ")";
  }
  if (settings.expansionBudget < 1) return "expansionBudget must be >= 1 (got 0)";
  if (settings.window < 1 || settings.window > kMaxCooperativeWindow) {
    return "window must be 1.." + std::to_string(kMaxCooperativeWindow) + " (got " +
           std::to_string(settings.window) + ")";
  }
  if (settings.corridor < 1 || settings.corridor > 64)
    return "corridor must be 1..64 (got " + std::to_string(settings.corridor) + ")";
  if (settings.terrainCosts && settings.algorithm != Algorithm::AStar)
    return "terrainCosts needs algorithm aa (weighted HAA* is not built yet)";
  return {};
}

PathService::PathService(const AnnotatedGrid& grid, const PathServiceSettings& settings,
                         std::vector<Capability> capabilities, int maxAgentSize,
                         std::vector<CostField> costProfiles)
    : settings_(settings), costProfiles_(std::move(costProfiles)) {
  if (std::string problem = problemWith(settings); !problem.empty())
    throw std::invalid_argument(problem);
  const auto began = std::chrono::steady_clock::now();
  if (const auto quality = abstractionQualityFor(settings.algorithm)) {
    AbstractionSpec spec;
    spec.clusterSize = settings.clusterSize;
    spec.maxAgentSize = maxAgentSize;
    spec.capabilities = std::move(capabilities);
    spec.quality = *quality;
    abstraction_ = std::make_unique<ClusterAbstraction>(ClusterAbstraction::build(grid, spec));
  }
  planner_.emplace(grid, settings.algorithm, abstraction_.get());
  if (!costProfiles_.empty()) weighted_.emplace(grid);
  metrics_.preprocessMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
}

PathService::~PathService() = default;

void PathService::request(const PathRequest& request) {
  queue_.push_back(request);
  ++metrics_.requests;
  metrics_.maxQueue = std::max(metrics_.maxQueue, queue_.size());
}

void PathService::cancel(UnitId unit) {
  std::erase_if(queue_, [&](const PathRequest& r) { return r.unit == unit; });
}

std::uint64_t PathService::serve(std::vector<PathDelivery>& out) {
  std::uint64_t spent = 0;
  while (!queue_.empty()) {
    const PathRequest& front = queue_.front();
    const Key key{front.agent.size, front.agent.capability.mask(),
                  front.start.x,    front.start.y,
                  front.goal.x,     front.goal.y,
                  front.costProfile};
    auto hit = cache_.find(key);
    // Cached answers cost no budget, so duplicates queued behind a search ride along with it.
    if (hit == cache_.end() && spent >= settings_.expansionBudget) break;
    const PathRequest request = front;
    queue_.pop_front();
    if (hit != cache_.end()) {
      ++metrics_.cacheHits;
    } else {
      std::vector<Cell> cells;
      const bool weighted = request.costProfile >= 0 &&
                            static_cast<std::size_t>(request.costProfile) < costProfiles_.size();
      const PathResult result =
          weighted
              ? weighted_->findPath(request.agent, request.start, request.goal, &cells,
                                    costProfiles_[static_cast<std::size_t>(request.costProfile)])
              : planner_->findPath(request.agent, request.start, request.goal, &cells);
      ++metrics_.searches;
      metrics_.expanded += result.metrics.expanded;
      metrics_.microseconds += result.metrics.microseconds;
      spent += result.metrics.expanded;
      if (result.found())
        ++metrics_.found;
      else
        ++metrics_.failed;
      if (cache_.size() >= settings_.cacheCapacity && !cacheOrder_.empty()) {
        cache_.erase(cacheOrder_.front());
        cacheOrder_.pop_front();
      }
      SharedPath path;
      if (result.found()) path = std::make_shared<const PlannedPath>(planned(std::move(cells)));
      hit = cache_.emplace(key, Answer{result.status, std::move(path)}).first;
      cacheOrder_.push_back(key);
    }
    out.push_back({request.unit, request.serial, hit->second.status, hit->second.path});
  }
  return spent;
}

}  // namespace warpath::engine
