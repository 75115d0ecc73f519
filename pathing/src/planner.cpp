#include "pathing/planner.h"

namespace warpath::pathing {

std::string_view toString(Algorithm algorithm) {
  switch (algorithm) {
    case Algorithm::AStar:
      return "aa";
    case Algorithm::HaaHigh:
      return "haa-hq";
    case Algorithm::HaaLow:
      return "haa-lq";
    case Algorithm::Hybrid:
      return "hybrid";
  }
  return "unknown";
}

std::optional<Algorithm> algorithmFromName(std::string_view name) {
  for (Algorithm a : {Algorithm::AStar, Algorithm::HaaHigh, Algorithm::HaaLow, Algorithm::Hybrid}) {
    if (toString(a) == name) return a;
  }
  return std::nullopt;
}

std::optional<AbstractionQuality> abstractionQualityFor(Algorithm algorithm) {
  switch (algorithm) {
    case Algorithm::AStar:
      return std::nullopt;
    case Algorithm::HaaLow:
      return AbstractionQuality::Low;
    case Algorithm::HaaHigh:
    case Algorithm::Hybrid:
      return AbstractionQuality::High;
  }
  return std::nullopt;
}

namespace {

using Impl = std::variant<AnnotatedAStar, HierarchicalAStar, HybridPlanner>;

}  // namespace

Planner::Planner(const AnnotatedGrid& grid, Algorithm algorithm,
                 const ClusterAbstraction* abstraction, HybridOptions hybrid, HaaOptions haa)
    : algorithm_(algorithm), impl_([&]() -> Impl {
        switch (algorithm) {
          case Algorithm::HaaHigh:
          case Algorithm::HaaLow:
            return Impl(std::in_place_type<HierarchicalAStar>, *abstraction, haa);
          case Algorithm::Hybrid:
            return Impl(std::in_place_type<HybridPlanner>, *abstraction, hybrid, haa);
          case Algorithm::AStar:
            break;
        }
        return Impl(std::in_place_type<AnnotatedAStar>, grid);
      }()) {}

PathResult Planner::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path) {
  return std::visit([&](auto& planner) { return planner.findPath(agent, start, goal, path); },
                    impl_);
}

}  // namespace warpath::pathing
