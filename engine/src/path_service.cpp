#include "engine/path_service.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <unordered_map>

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
  if (settings.levels < 1 || settings.levels > 2)
    return "levels must be 1..2 (got " + std::to_string(settings.levels) + ")";
  if (settings.levelTwoSize < 2 || settings.levelTwoSize > 256)
    return "levelTwoSize must be 2..256 (got " + std::to_string(settings.levelTwoSize) + ")";
  if (settings.buildThreads < 1 || settings.buildThreads > pathing::kMaxBuildThreads) {
    return "buildThreads must be 1.." + std::to_string(pathing::kMaxBuildThreads) + " (got " +
           std::to_string(settings.buildThreads) + ")";
  }
  if (settings.expansionBudget < 1) return "expansionBudget must be >= 1 (got 0)";
  if (settings.window < 1 || settings.window > kMaxCooperativeWindow) {
    return "window must be 1.." + std::to_string(kMaxCooperativeWindow) + " (got " +
           std::to_string(settings.window) + ")";
  }
  if (settings.corridor < 1 || settings.corridor > 64)
    return "corridor must be 1..64 (got " + std::to_string(settings.corridor) + ")";
  return {};
}

namespace {

double elapsedMilliseconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
      .count();
}

// Two profiles plan alike when they agree on the terrains the map has.
bool sameOnMap(const CostProfile& a, const CostProfile& b, Capability present) {
  if (a.agent.size != b.agent.size) return false;
  const auto cut = [&](const CostProfile& p) {
    return Capability::fromMask(p.agent.capability.mask() & p.costs.capability().mask() &
                                present.mask());
  };
  const Capability terrains = cut(a);
  if (terrains != cut(b)) return false;
  for (int slot = 0; slot < kTraversableTerrainSlots; ++slot) {
    const auto i = static_cast<std::size_t>(slot);
    if (terrains.allows(static_cast<Terrain>(slot)) && a.costs.perCell[i] != b.costs.perCell[i])
      return false;
  }
  return true;
}

}  // namespace

PathService::PathService(const AnnotatedGrid& grid, const PathServiceSettings& settings,
                         std::vector<Capability> capabilities, int maxAgentSize,
                         std::vector<CostProfile> costProfiles)
    : grid_(grid), settings_(settings), detourSearch_(grid) {
  if (std::string problem = problemWith(settings); !problem.empty())
    throw std::invalid_argument(problem);
  const auto began = std::chrono::steady_clock::now();
  const auto quality = abstractionQualityFor(settings.algorithm);
  if (quality && !settings.terrainCosts) {
    AbstractionSpec spec;
    spec.clusterSize = settings.clusterSize;
    spec.maxAgentSize = maxAgentSize;
    spec.capabilities = std::move(capabilities);
    spec.quality = *quality;
    spec.levels = settings.levels;
    spec.levelTwoSize = settings.levelTwoSize;
    spec.threads = settings.buildThreads;
    abstraction_ = std::make_unique<ClusterAbstraction>(ClusterAbstraction::build(grid, spec));
  }
  // Requests without a profile plan in the uniform model (by AA* when the algorithm needs a
  // graph and none was built).
  planner_.emplace(grid, abstraction_ || !quality ? settings.algorithm : Algorithm::AStar,
                   abstraction_.get(), pathing::HybridOptions{},
                   pathing::HaaOptions{.insertion = settings.insertion}, nullptr,
                   settings.jumpSuccessors);
  if (settings.cooperative && settings.congestion && quality)
    congestion_.emplace(grid, settings.clusterSize);
  present_ = grid.map().terrainsPresent();
  costProfiles_ = std::move(costProfiles);
  mergeCostProfiles();
  metrics_.preprocessMilliseconds = elapsedMilliseconds(began);
}

void PathService::mergeCostProfiles() {
  weighted_.clear();
  distinctOf_.clear();
  for (const CostProfile& profile : costProfiles_) {
    std::size_t k = 0;
    while (k < weighted_.size() &&
           !sameOnMap({weighted_[k]->agent, weighted_[k]->costs}, profile, present_))
      ++k;
    if (k == weighted_.size()) {
      auto planner = std::make_unique<WeightedPlanner>();
      planner->agent = {profile.agent.size,
                        Capability::fromMask(profile.agent.capability.mask() &
                                             profile.costs.capability().mask())};
      planner->costs = profile.costs;
      weighted_.push_back(std::move(planner));
    }
    distinctOf_.push_back(static_cast<int>(k));
  }
}

PathService::WeightedPlanner& PathService::weightedPlanner(int costProfile) {
  WeightedPlanner& w =
      *weighted_[static_cast<std::size_t>(distinctOf_[static_cast<std::size_t>(costProfile)])];
  if (w.planner) return w;
  const auto began = std::chrono::steady_clock::now();
  const auto quality = abstractionQualityFor(settings_.algorithm);
  // A unit that can enter no terrain with a cost has no graph to build: AA* answers it
  // (InvalidStart).
  if (quality && !w.agent.capability.empty()) {
    AbstractionSpec spec =
        weightedAbstractionSpec(w.agent, w.costs, settings_.clusterSize, *quality);
    spec.levels = settings_.levels;
    spec.levelTwoSize = settings_.levelTwoSize;
    spec.threads = settings_.buildThreads;
    w.abstraction =
        std::make_unique<ClusterAbstraction>(ClusterAbstraction::build(grid_, std::move(spec)));
    w.planner.emplace(grid_, settings_.algorithm, w.abstraction.get());
  } else {
    w.field.emplace(grid_, w.agent, w.costs);
    w.planner.emplace(grid_, Algorithm::AStar, nullptr, HybridOptions{}, HaaOptions{}, &*w.field);
  }
  metrics_.preprocessMilliseconds += elapsedMilliseconds(began);
  return w;
}

std::size_t PathService::builtCostPlanners() const {
  return static_cast<std::size_t>(std::count_if(
      weighted_.begin(), weighted_.end(), [](const auto& w) { return w->planner.has_value(); }));
}

const ClusterAbstraction* PathService::abstraction() const {
  if (abstraction_) return abstraction_.get();
  for (const auto& w : weighted_) {
    if (w->abstraction) return w->abstraction.get();
  }
  return nullptr;
}

PathService::~PathService() = default;

std::uint64_t PathService::slicedExpanded() const {
  if (detourInFlight_) return detourSearch_.expandedSoFar();
  return inFlight_ ? inFlight_->expandedSoFar() : 0;
}

void PathService::countWindows(std::uint64_t served, std::uint64_t windows, bool paused) {
  metrics_.maxTickExpanded = std::max(metrics_.maxTickExpanded, served + windows);
  if (paused) ++metrics_.windowSlices;
}

void PathService::changeTerrain(const TerrainChange& change) {
  if (!change.changed) return;
  // A search under way read the old terrain (and graphs about to be repaired): begun again.
  inFlight_ = nullptr;
  detourInFlight_ = false;
  const auto began = std::chrono::steady_clock::now();
  ++metrics_.terrainChanges;
  // The graphs catch up in chunks a few clusters a side, within the ticks' budgets (serve()):
  // a large change is spread over several ticks, and requests wait for the last chunk.
  const bool graphs =
      abstraction_ || std::any_of(weighted_.begin(), weighted_.end(),
                                  [](const auto& w) { return w->abstraction != nullptr; });
  const int side = kRepairChunkClusters * settings_.clusterSize;
  const CellRect& a = change.area;
  for (int y = a.y / side * side; graphs && y < a.y + a.height; y += side) {
    for (int x = a.x / side * side; x < a.x + a.width; x += side) {
      const int x0 = std::max(x, a.x);
      const int y0 = std::max(y, a.y);
      pendingRepairs_.push_back({x0, y0, std::min(x + side, a.x + a.width) - x0,
                                 std::min(y + side, a.y + a.height) - y0});
    }
  }
  // Profiles merged because they agreed on the map's terrains may differ on a terrain the
  // change brought: merged again, their planners built anew when next asked.
  const std::uint8_t brought = grid_.map().terrainsIn(change.area).mask();
  if ((brought & ~present_.mask()) != 0) {
    present_ = present_ | Capability::fromMask(brought);
    mergeCostProfiles();
  }
  for (const auto& w : weighted_) {
    if (w->field) w->field->update(grid_, change.area);
  }
  if (congestion_) congestion_->terrainChanged();
  // A path that crosses the change (its footprints grown by the agent's size) may no longer be
  // legal, and a failed answer may now succeed; answers elsewhere stay legal (a shortcut the
  // change opened is not looked for).
  const CellRect area = change.area;
  const auto touched = [&](const Key& key, const Answer& answer) {
    if (!answer.path) return true;
    const int size = std::get<0>(key);
    return std::any_of(answer.path->cells.begin(), answer.path->cells.end(), [&](Cell c) {
      return area.overlaps({c.x, c.y, size, size});
    });
  };
  std::erase_if(cacheOrder_, [&](const Key& key) {
    const auto it = cache_.find(key);
    if (it == cache_.end() || !touched(key, it->second)) return false;
    cache_.erase(it);
    ++metrics_.cacheDropped;
    return true;
  });
  metrics_.repairMilliseconds += elapsedMilliseconds(began);
}

void PathService::request(const PathRequest& request) {
  queue_.push_back(request);
  ++metrics_.requests;
  metrics_.maxQueue = std::max(metrics_.maxQueue, queue_.size());
}

void PathService::cancel(UnitId unit) {
  if (!queue_.empty() && queue_.front().unit == unit) {
    inFlight_ = nullptr;
    detourInFlight_ = false;
  }
  std::erase_if(queue_, [&](const PathRequest& r) { return r.unit == unit; });
  if (congestion_) congestion_->cancel(unit);
}

std::uint64_t PathService::repairChunk() {
  const auto began = std::chrono::steady_clock::now();
  const TerrainChange part{pendingRepairs_.front(), true};
  pendingRepairs_.pop_front();
  std::uint64_t spent = 0;
  if (abstraction_) spent += abstraction_->repair(part).expanded;
  for (const auto& w : weighted_) {
    if (w->abstraction) spent += w->abstraction->repair(part).expanded;
  }
  ++metrics_.repairChunks;
  metrics_.repairExpanded += spent;
  metrics_.repairMilliseconds += elapsedMilliseconds(began);
  return spent;
}

void PathService::countSearch(const PathResult& result) {
  ++metrics_.searches;
  metrics_.expanded += result.metrics.expanded;
  metrics_.microseconds += result.metrics.microseconds;
}

PathService::DetourOutcome PathService::detourFor(const PathRequest& request, std::uint64_t budget,
                                                  std::uint64_t& spent) {
  DetourOutcome outcome;
  const Detour& detour = *request.detour;
  const bool weighted = request.costProfile >= 0 &&
                        static_cast<std::size_t>(request.costProfile) < distinctOf_.size();
  const WeightedPlanner* w = weighted ? &weightedPlanner(request.costProfile) : nullptr;
  // Under terrain costs the detour plans by the profile's own costs: its AA* field, or its
  // graph's.
  const CostField* costs = w ? (w->field         ? &*w->field
                                : w->abstraction ? w->abstraction->costs()
                                                 : nullptr)
                             : nullptr;
  if (w && !costs) return outcome;
  std::vector<Cell> cells;
  if (!detourInFlight_) {
    SearchLimits limits;
    limits.region = detour.region;
    limits.avoid = detour.avoid;  // held by the request, queued until the search ends
    limits.avoidPenalty = kDetourPenalty * (costs ? costs->cheapest() : 1.0);
    const Agent agent = w ? w->agent : request.agent;
    const Cell rejoin = detour.rest->cells[detour.rejoin];
    if (costs) {
      detourSearch_.beginPath(agent, request.start, rejoin, *costs, limits);
    } else {
      detourSearch_.beginPath(agent, request.start, rejoin, limits);
    }
    detourInFlight_ = true;
  }
  const std::uint64_t before = detourSearch_.expandedSoFar();
  const PathStatus status =
      detourSearch_.updatePath(settings_.sliced ? budget : pathing::kUnboundedExpansions);
  spent += detourSearch_.expandedSoFar() - before;
  if (status == PathStatus::Pending) {
    ++metrics_.slices;
    outcome.status = PathStatus::Pending;
    return outcome;
  }
  detourInFlight_ = false;
  const PathResult result = detourSearch_.finalizePath(&cells);
  countSearch(result);
  if (!result.found()) return outcome;
  ++metrics_.found;
  ++metrics_.detours;
  // The way around may cross the rest of the path beyond the cell it was sent to (it went round
  // the far end of an obstacle the path runs along): it joins the rest at the first such
  // crossing, at the crossing's farthest cell of the rest, instead of doubling back.
  const std::vector<Cell>& rest = detour.rest->cells;
  std::unordered_map<std::uint32_t, std::size_t> restAt;
  for (std::size_t j = detour.rejoin; j < rest.size(); ++j)
    restAt[grid_.map().indexOf(rest[j])] = j;
  std::size_t joins = detour.rejoin;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const auto it = restAt.find(grid_.map().indexOf(cells[i]));
    if (it == restAt.end()) continue;
    cells.resize(i + 1);
    joins = it->second;
    break;
  }
  cells.insert(cells.end(), rest.begin() + static_cast<std::ptrdiff_t>(joins) + 1, rest.end());
  if (costs) outcome.seconds = costs->pathCost(cells);
  outcome.status = PathStatus::Found;
  outcome.cells = std::move(cells);
  return outcome;
}

std::optional<PathResult> PathService::search(const PathRequest& request, std::uint64_t budget,
                                              double now, Congestion* congestion,
                                              std::uint64_t& spent, std::vector<Cell>& cells,
                                              double& seconds) {
  const bool weighted = request.costProfile >= 0 &&
                        static_cast<std::size_t>(request.costProfile) < distinctOf_.size();
  // The profile's agent: the request's may differ on terrains the map does not have.
  WeightedPlanner* w = weighted ? &weightedPlanner(request.costProfile) : nullptr;
  const Agent agent = w ? w->agent : request.agent;
  Planner& planner = w ? *w->planner : *planner_;
  PathResult result;
  if (inFlight_ != &planner) {
    // The waits are those expected when the search begins; a sliced one keeps them to its end.
    surcharge_.reset();
    if (congestion) surcharge_.emplace(*congestion, request.agent, request.speed, now, weighted);
  }
  const EdgeSurcharge* waits = surcharge_ ? &*surcharge_ : nullptr;
  if (!settings_.sliced) {
    result = planner.findPath(agent, request.start, request.goal, &cells, waits);
    spent += result.metrics.expanded;
  } else {
    if (inFlight_ != &planner) {
      planner.beginPath(agent, request.start, request.goal, waits);
      inFlight_ = &planner;
    }
    // A step that cannot be split (an HAA* insertion) and does not fit in what is left of the
    // tick's budget waits for the next tick, unless the tick has spent nothing yet.
    if (spent > 0 && planner.nextStepExpansions() > budget) {
      ++metrics_.slices;
      return std::nullopt;
    }
    const std::uint64_t before = planner.expandedSoFar();
    const PathStatus status = planner.updatePath(budget);
    spent += planner.expandedSoFar() - before;
    if (status == PathStatus::Pending) {
      ++metrics_.slices;
      return std::nullopt;
    }
    inFlight_ = nullptr;
    result = planner.finalizePath(&cells);
  }
  if (w) seconds = result.cost;
  return result;
}

std::uint64_t PathService::serve(std::vector<PathDelivery>& out, double now) {
  std::uint64_t spent = 0;
  // The graphs first: at least one chunk a tick, more while the budget lasts.
  for (bool first = true; !pendingRepairs_.empty() && (first || spent < settings_.expansionBudget);
       first = false)
    spent += repairChunk();
  if (!pendingRepairs_.empty()) {
    metrics_.maxTickExpanded = std::max(metrics_.maxTickExpanded, spent);
    return spent;
  }
  // Hands the answer to the request at the head of the queue, which leaves it, and books it.
  const auto deliver = [&](const Answer& answer, Congestion* congestion) {
    const PathRequest request = queue_.front();
    queue_.pop_front();
    inFlight_ = nullptr;  // a sliced search of the request, if any, is done or not needed
    if (congestion && answer.path)
      congestion->book(request.unit, request.agent, request.speed, answer.path->cells, now);
    out.push_back({request.unit, request.serial, answer.status, answer.path, answer.seconds});
  };
  while (!queue_.empty()) {
    const PathRequest& front = queue_.front();
    const Key key{front.agent.size, front.agent.capability.mask(),
                  front.start.x,    front.start.y,
                  front.goal.x,     front.goal.y,
                  front.costProfile};
    // Congestion-aware: the unit's own bookings go (its next path books again), and a cached
    // path that now meets a queue is planned again around it.
    Congestion* congestion = congestion_ && front.speed > 0.0 ? &*congestion_ : nullptr;
    if (congestion) congestion->cancel(front.unit);
    if (front.detour) {
      if (spent >= settings_.expansionBudget) break;
      DetourOutcome detour = detourFor(front, settings_.expansionBudget - spent, spent);
      if (detour.status == PathStatus::Pending) break;  // sliced: resumed next tick
      if (detour.status == PathStatus::Found) {
        deliver(
            {PathStatus::Found,
             std::make_shared<const PlannedPath>(planned(std::move(detour.cells))), detour.seconds},
            congestion);
        continue;
      }
      // No way around inside the region: planned as any request, its detour dropped so that
      // a sliced search of it does not look again.
      queue_.front().detour = nullptr;
    }
    auto hit = cache_.find(key);
    if (congestion && hit != cache_.end() && hit->second.path &&
        congestion->waitAlong(front.agent, front.speed, hit->second.path->cells, now) > 0.0)
      hit = cache_.end();
    // Cached answers cost no budget, so duplicates queued behind a search ride along with it.
    if (hit == cache_.end() && spent >= settings_.expansionBudget) break;
    Answer answer;
    if (hit != cache_.end()) {
      ++metrics_.cacheHits;
      answer = hit->second;
    } else {
      std::vector<Cell> cells;
      double seconds = -1.0;
      const std::optional<PathResult> result =
          search(front, settings_.expansionBudget - spent, now, congestion, spent, cells, seconds);
      if (!result) break;  // sliced: resumed next tick
      countSearch(*result);
      if (result->found())
        ++metrics_.found;
      else
        ++metrics_.failed;
      // A path that meets a queue is this moment's answer, not one to hand out later.
      const bool meetsQueue = congestion && result->found() &&
                              congestion->waitAlong(front.agent, front.speed, cells, now) > 0.0;
      if (meetsQueue) ++metrics_.congestedSearches;
      answer.status = result->status;
      if (result->found())
        answer.path = std::make_shared<const PlannedPath>(planned(std::move(cells)));
      answer.seconds = seconds;
      if (const auto stale = cache_.find(key); stale != cache_.end()) {
        // Planned again because the cached path met a queue: this answer replaces it.
        if (!meetsQueue) stale->second = answer;
      } else if (!meetsQueue) {
        if (cache_.size() >= settings_.cacheCapacity && !cacheOrder_.empty()) {
          cache_.erase(cacheOrder_.front());
          cacheOrder_.pop_front();
        }
        cache_.emplace(key, answer);
        cacheOrder_.push_back(key);
      }
    }
    deliver(answer, congestion);
  }
  metrics_.maxTickExpanded = std::max(metrics_.maxTickExpanded, spent);
  return spent;
}

}  // namespace warpath::engine
