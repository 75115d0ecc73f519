#pragma once
// Shared pieces of the `rts bench` subcommands: summarising per-query results into the report
// keys every bench prints (DESIGN.md §5), and checking a returned path.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/search.h"
#include "pathing/terrain_costs.h"

namespace warpath::tools {

// A found path counts as optimal when its cost is within this of the reference; MovingAI scen
// files print lengths to 2 decimals or ~6 significant digits.
inline constexpr double kOptimalTolerance = 0.01;

// Nearest-rank percentile of an unsorted sample (copied, so the caller's order is kept);
// 0 for an empty sample. [Limit: fraction in 0..1]
double percentile(std::vector<double> values, double fraction);

// Accumulates one planner's results over a query set.
class ResultTally {
 public:
  // `reference`: the optimal cost to judge a found path by; none when there is none to compare
  // with (the path then counts as solved but enters no quality figure).
  void add(const pathing::PathResult& result, std::optional<double> reference);

  std::size_t queries() const { return micros_.size(); }
  std::size_t solved() const { return solved_; }
  double meanSuboptimalityPct() const;
  double maxSuboptimalityPct() const { return maxSuboptimalityPct_; }
  double meanMicroseconds() const;
  double medianMicroseconds() const { return percentile(micros_, 0.5); }
  double meanExpanded() const;

  // queries solved unreachable optimal_matches max_abs_error mean_suboptimality_pct
  // max_suboptimality_pct median_us p95_us mean_us mean_expanded total_expanded
  // expanded_per_second search_seconds mean_insertion_expanded mean_abstract_expanded
  // mean_refinement_expanded grid_search_queries. "unreachable" counts every query without
  // a path, whatever its status.
  void writeTo(nlohmann::json& out) const;

 private:
  std::size_t solved_ = 0;
  std::size_t optimalMatches_ = 0;
  std::size_t compared_ = 0;  // found paths with a positive reference
  std::size_t gridSearchQueries_ = 0;
  double maxAbsError_ = 0.0;
  double sumSuboptimalityPct_ = 0.0;
  double maxSuboptimalityPct_ = 0.0;
  double totalMicroseconds_ = 0.0;
  std::uint64_t totalExpanded_ = 0;
  std::uint64_t insertionExpanded_ = 0;
  std::uint64_t abstractExpanded_ = 0;
  std::uint64_t refinementExpanded_ = 0;
  std::vector<double> micros_;
};

// Empty when `path` is what a found `result` for start -> goal must carry: a legal path for
// the agent from start to goal whose cost is result.cost (within 1e-6), priced by `costs`
// when given (else the uniform model); else the problem.
std::string pathProblem(const pathing::AnnotatedGrid& grid, pathing::Agent agent,
                        pathing::Cell start, pathing::Cell goal, const pathing::PathResult& result,
                        std::span<const pathing::Cell> path,
                        const pathing::CostField* costs = nullptr);

// Prints one JSON line, or one "key value" line per key.
void printReport(const nlohmann::json& out, bool json);

// "a,b,c" as integers; throws BadInput naming `option` on anything else or an empty list.
std::vector<int> parseIntList(const std::string& text, const std::string& option);

}  // namespace warpath::tools
