#pragma once
// The completeness check of the hierarchical planners, shared by the unit suite (random maps)
// and the data suite (MovingAI maps): a planner's answer to a query is compared with AA*'s.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/annotated_grid.h"
#include "pathing/map_generator.h"
#include "pathing/random.h"
#include "pathing/search.h"
#include "pathing/terrain_costs.h"

namespace warpath::testing {

using pathing::Agent;
using pathing::Cell;
using pathing::PathResult;

// The agent kinds every hierarchical planner is proved on: sizes 1-3 and the capabilities of
// the unit catalogue (infantry, jeep and tank, amphibious) and the MovingAI classes.
inline std::vector<pathing::Capability> completenessCapabilities() {
  using pathing::Capability;
  using pathing::Terrain;
  return {Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees}),  // infantry
          Capability::of({Terrain::Ground}),                                  // jeep, tank
          Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water}),  // amphibious
          Capability::of({Terrain::Ground, Terrain::Swamp}),                  // MovingAI classes
          Capability::of({Terrain::Water}),
          Capability::of({Terrain::Trees})};
}

inline std::vector<Agent> completenessAgents(int maxSize = 3) {
  std::vector<Agent> agents;
  for (int size = 1; size <= maxSize; ++size) {
    for (pathing::Capability c : completenessCapabilities())
      agents.push_back({size, c});
  }
  return agents;
}

inline std::string describeQuery(Agent agent, Cell start, Cell goal) {
  std::ostringstream out;
  out << "size " << agent.size << " " << agent.capability.toString() << " " << start.x << ","
      << start.y << " -> " << goal.x << "," << goal.y;
  return out.str();
}

// Empty when `result` (with `path`) answers start -> goal as a complete planner must, given
// AA*'s `optimum` for the same query: the same status; when found, a legal path from start to
// goal whose cost is result.cost and at least the optimum (both within 1e-6); and metrics whose
// phases, when split, add up to the total. Else what is wrong. Costs are lengths, or with
// `costs` (built for the agent) travel times.
inline std::string completenessProblem(const pathing::AnnotatedGrid& grid, Agent agent, Cell start,
                                       Cell goal, const PathResult& optimum,
                                       const PathResult& result, const std::vector<Cell>& path,
                                       const pathing::CostField* costs = nullptr) {
  std::ostringstream problem;
  if (result.status != optimum.status) {
    problem << "status " << toString(result.status) << ", AA* says " << toString(optimum.status);
    return problem.str();
  }
  const pathing::SearchMetrics& m = result.metrics;
  const std::uint64_t phases =
      m.insertionExpanded + m.abstractExpanded + m.refinementExpanded + m.gridExpanded;
  if (phases != 0 && phases != m.expanded) {
    problem << "phase expansions " << m.insertionExpanded << "+" << m.abstractExpanded << "+"
            << m.refinementExpanded << "+" << m.gridExpanded << " do not add up to the total "
            << m.expanded;
    return problem.str();
  }
  if (!result.found()) return {};
  if (path.empty() || !(path.front() == start) || !(path.back() == goal)) {
    problem << "the path does not run from start to goal (" << path.size() << " cells)";
    return problem.str();
  }
  if (std::string illegal = pathing::findIllegalStep(grid, agent, path); !illegal.empty()) {
    return illegal;
  }
  problem.precision(9);
  const double walked = costs ? costs->pathCost(path) : pathing::pathCost(path);
  if (std::abs(walked - result.cost) > 1e-6) {
    problem << "the path costs " << walked << ", the result says " << result.cost;
    return problem.str();
  }
  if (result.cost < optimum.cost - 1e-6) {
    problem << "cost " << result.cost << " is below the optimum " << optimum.cost;
    return problem.str();
  }
  return {};
}

// One query of a completeness run, with AA*'s answer (under `costs` when not null).
struct CompletenessCase {
  Agent agent;
  pathing::Query query;
  PathResult optimum;
  const pathing::CostField* costs = nullptr;
};

// For every agent: `anyCount` pairs of cells where it can stand (reachable or not),
// `reachableCount` mutually reachable pairs and `randomCount` pairs of any cells (mostly
// invalid ends), each answered by AA*. With `costs` (which must outlive the cases), every
// agent moves by them (so pass only the agent they were built for), and AA* answers under them.
// Same inputs => same cases.
inline std::vector<CompletenessCase> drawCompletenessCases(
    const pathing::AnnotatedGrid& grid, const std::vector<Agent>& agents, std::uint64_t seed,
    int anyCount, int reachableCount, int randomCount, const pathing::CostField* costs = nullptr) {
  pathing::SplitMix64 rng(seed);
  pathing::AnnotatedAStar search(grid);
  std::vector<CompletenessCase> cases;
  const auto add = [&](Agent agent, pathing::Query q) {
    const PathResult optimum = costs ? search.findPath(agent, q.start, q.goal, nullptr, *costs)
                                     : search.findPath(agent, q.start, q.goal, nullptr);
    cases.push_back({agent, q, optimum, costs});
  };
  const pathing::GridMap& map = grid.map();
  for (const Agent& agent : agents) {
    const pathing::QuerySampler sampler(grid, agent);
    for (int i = 0; sampler.canStandAnywhere() && i < anyCount; ++i)
      add(agent, sampler.anyPair(rng));
    for (int i = 0; sampler.hasReachablePair() && i < reachableCount; ++i)
      add(agent, sampler.reachablePair(rng));
    for (int i = 0; i < randomCount; ++i) {
      const Cell start{rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)};
      add(agent, {start, {rng.between(0, map.width() - 1), rng.between(0, map.height() - 1)}});
    }
  }
  return cases;
}

struct CompletenessTally {
  int found = 0;
  int notFound = 0;
  int failures = 0;
  double excess = 0.0;  // sum over found queries of cost / optimum - 1

  double meanError() const { return found > 0 ? excess / found : 0.0; }
};

// Runs every case through `planner` (anything with findPath(agent, start, goal, path)) and
// reports the first few problems as test failures, labelled with `label`.
template <class Planner>
void checkCompleteness(const pathing::AnnotatedGrid& grid,
                       const std::vector<CompletenessCase>& cases, Planner& planner,
                       const std::string& label, CompletenessTally& tally) {
  std::vector<Cell> path;
  for (const CompletenessCase& c : cases) {
    path.clear();
    const PathResult result = planner.findPath(c.agent, c.query.start, c.query.goal, &path);
    const std::string problem = completenessProblem(grid, c.agent, c.query.start, c.query.goal,
                                                    c.optimum, result, path, c.costs);
    if (!problem.empty()) {
      if (++tally.failures <= 8) {
        ADD_FAILURE() << label << ": " << describeQuery(c.agent, c.query.start, c.query.goal)
                      << ": " << problem;
      }
    } else if (result.found()) {
      ++tally.found;
      if (c.optimum.cost > 0.0) tally.excess += result.cost / c.optimum.cost - 1.0;
    } else {
      ++tally.notFound;
    }
  }
}

}  // namespace warpath::testing
