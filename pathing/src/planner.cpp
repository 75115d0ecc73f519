#include "pathing/planner.h"

#include "limit_messages.h"

namespace warpath::pathing {

std::string_view toString(Algorithm algorithm) {
  return kAlgorithmNames.name(algorithm);
}

std::optional<Algorithm> algorithmFromName(std::string_view name) {
  return kAlgorithmNames.parse(name);
}

std::optional<AbstractionQuality> abstractionQualityFor(Algorithm algorithm) {
  switch (algorithm) {
    case Algorithm::AStar:
    case Algorithm::Jps:
    case Algorithm::JpsPlus:
      return std::nullopt;
    case Algorithm::HaaLow:
      return AbstractionQuality::Low;
    case Algorithm::HaaHigh:
    case Algorithm::Hybrid:
      return AbstractionQuality::High;
  }
  return std::nullopt;
}

std::string problemWith(const AnnotatedGrid& grid, Algorithm algorithm,
                        const ClusterAbstraction* abstraction, const HybridOptions& hybrid) {
  if (std::string problem = problemWith(hybrid); !problem.empty()) return problem;
  const std::optional<AbstractionQuality> quality = abstractionQualityFor(algorithm);
  if (!quality) return {};
  const std::string needed(toString(algorithm));
  if (!abstraction) return "abstraction must be given for " + needed + " (got none)";
  if (abstraction->spec().quality != *quality) {
    return "abstraction must be of quality " +
           std::string(kAbstractionQualityNames.name(*quality)) + " for " + needed + " (got " +
           std::string(kAbstractionQualityNames.name(abstraction->spec().quality)) + ")";
  }
  if (&abstraction->grid() != &grid) return "abstraction must be built on the planner's grid";
  return {};
}

namespace {

using Impl = std::variant<AnnotatedAStar, HierarchicalAStar, HybridPlanner, JumpPointSearch>;

}  // namespace

Planner::Planner(const AnnotatedGrid& grid, Algorithm algorithm,
                 const ClusterAbstraction* abstraction, HybridOptions hybrid, HaaOptions haa,
                 const CostField* costs, JumpSuccessors jumpSuccessors)
    : algorithm_(algorithm), costs_(costs), impl_([&]() -> Impl {
        limits::require(problemWith(grid, algorithm, abstraction, hybrid));
        if ((algorithm == Algorithm::Jps || algorithm == Algorithm::JpsPlus) && costs) {
          limits::require(std::string(toString(algorithm)) +
                          " plans on uniform costs only (got terrain costs)");
        }
        switch (algorithm) {
          case Algorithm::HaaHigh:
          case Algorithm::HaaLow:
            return Impl(std::in_place_type<HierarchicalAStar>, *abstraction, haa);
          case Algorithm::Hybrid:
            return Impl(std::in_place_type<HybridPlanner>, *abstraction, hybrid, haa);
          case Algorithm::Jps:
            return Impl(std::in_place_type<JumpPointSearch>, grid, JumpDistances::Scanned,
                        kDefaultJumpTableBudget, jumpSuccessors);
          case Algorithm::JpsPlus:
            return Impl(std::in_place_type<JumpPointSearch>, grid, JumpDistances::Precomputed,
                        kDefaultJumpTableBudget, jumpSuccessors);
          case Algorithm::AStar:
            break;
        }
        return Impl(std::in_place_type<AnnotatedAStar>, grid);
      }()) {}

PathResult Planner::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                             const EdgeSurcharge* surcharge) {
  // Each planner's own findPath times the whole query once (PhaseTiming).
  if (auto* grid = std::get_if<AnnotatedAStar>(&impl_)) {
    return costs_ ? grid->findPath(agent, start, goal, path, *costs_)
                  : grid->findPath(agent, start, goal, path);
  }
  if (auto* jps = std::get_if<JumpPointSearch>(&impl_))
    return jps->findPath(agent, start, goal, path);
  if (auto* hierarchical = std::get_if<HierarchicalAStar>(&impl_))
    return hierarchical->findPath(agent, start, goal, path, surcharge);
  return std::get<HybridPlanner>(impl_).findPath(agent, start, goal, path, surcharge);
}

PathStatus Planner::beginPath(Agent agent, Cell start, Cell goal, const EdgeSurcharge* surcharge) {
  if (auto* grid = std::get_if<AnnotatedAStar>(&impl_); grid && costs_)
    return grid->beginPath(agent, start, goal, *costs_);
  if (auto* hierarchical = std::get_if<HierarchicalAStar>(&impl_))
    return hierarchical->beginPath(agent, start, goal, surcharge);
  if (auto* hybrid = std::get_if<HybridPlanner>(&impl_))
    return hybrid->beginPath(agent, start, goal, surcharge);
  return std::visit([&](auto& planner) { return planner.beginPath(agent, start, goal); }, impl_);
}

PathStatus Planner::updatePath(std::uint64_t maxExpansions) {
  return std::visit([&](auto& planner) { return planner.updatePath(maxExpansions); }, impl_);
}

PathResult Planner::finalizePath(std::vector<Cell>* path) {
  return std::visit([&](auto& planner) { return planner.finalizePath(path); }, impl_);
}

std::uint64_t Planner::expandedSoFar() const {
  return std::visit([](const auto& planner) { return planner.expandedSoFar(); }, impl_);
}

std::uint64_t Planner::nextStepExpansions() const {
  return std::visit([](const auto& planner) { return planner.nextStepExpansions(); }, impl_);
}

void Planner::prepare(Agent agent) {
  if (auto* jps = std::get_if<JumpPointSearch>(&impl_)) jps->prepare(agent);
  if (auto* hybrid = std::get_if<HybridPlanner>(&impl_)) hybrid->prepare(agent);
  if (auto* haa = std::get_if<HierarchicalAStar>(&impl_)) haa->prepare(agent);
}

std::size_t Planner::insertionTableBytes() const {
  if (const auto* haa = std::get_if<HierarchicalAStar>(&impl_)) return haa->insertionTableBytes();
  if (const auto* hybrid = std::get_if<HybridPlanner>(&impl_)) return hybrid->insertionTableBytes();
  return 0;
}

std::vector<LayerBytes> Planner::layerBytes() const {
  const auto* jps = std::get_if<JumpPointSearch>(&impl_);
  return jps ? jps->layerBytes() : std::vector<LayerBytes>{};
}

}  // namespace warpath::pathing
