#include "rts/bench_support.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "rts/cli_support.h"

namespace warpath::tools {

using namespace pathing;

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const std::size_t rank =
      static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  const std::size_t index = rank == 0 ? 0 : rank - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

void ResultTally::add(const PathResult& result, std::optional<double> reference) {
  const SearchMetrics& m = result.metrics;
  micros_.push_back(m.microseconds);
  totalMicroseconds_ += m.microseconds;
  totalExpanded_ += m.expanded;
  insertionExpanded_ += m.insertionExpanded;
  abstractExpanded_ += m.abstractExpanded;
  refinementExpanded_ += m.refinementExpanded;
  gridSearchQueries_ += m.usedGridSearch ? 1 : 0;
  if (!result.found()) return;
  ++solved_;
  if (!reference) return;
  const double error = std::abs(result.cost - *reference);
  maxAbsError_ = std::max(maxAbsError_, error);
  if (error <= kOptimalTolerance) ++optimalMatches_;
  if (*reference > 0.0) {
    const double pct = 100.0 * (result.cost - *reference) / *reference;
    sumSuboptimalityPct_ += pct;
    maxSuboptimalityPct_ = std::max(maxSuboptimalityPct_, pct);
    ++compared_;
  }
}

double ResultTally::meanSuboptimalityPct() const {
  return compared_ ? sumSuboptimalityPct_ / static_cast<double>(compared_) : 0.0;
}

double ResultTally::meanMicroseconds() const {
  return micros_.empty() ? 0.0 : totalMicroseconds_ / static_cast<double>(micros_.size());
}

double ResultTally::meanExpanded() const {
  return micros_.empty() ? 0.0
                         : static_cast<double>(totalExpanded_) / static_cast<double>(queries());
}

void ResultTally::writeTo(nlohmann::json& out) const {
  const double perQuery = micros_.empty() ? 0.0 : 1.0 / static_cast<double>(queries());
  const double searchSeconds = totalMicroseconds_ / 1e6;
  out["queries"] = queries();
  out["solved"] = solved_;
  out["unreachable"] = queries() - solved_;
  out["optimal_matches"] = optimalMatches_;
  out["max_abs_error"] = maxAbsError_;
  out["mean_suboptimality_pct"] = meanSuboptimalityPct();
  out["max_suboptimality_pct"] = maxSuboptimalityPct_;
  out["median_us"] = medianMicroseconds();
  out["p95_us"] = percentile(micros_, 0.95);
  out["mean_us"] = meanMicroseconds();
  out["mean_expanded"] = meanExpanded();
  out["total_expanded"] = totalExpanded_;
  out["expanded_per_second"] =
      searchSeconds > 0.0 ? static_cast<double>(totalExpanded_) / searchSeconds : 0.0;
  out["search_seconds"] = searchSeconds;
  out["mean_insertion_expanded"] = static_cast<double>(insertionExpanded_) * perQuery;
  out["mean_abstract_expanded"] = static_cast<double>(abstractExpanded_) * perQuery;
  out["mean_refinement_expanded"] = static_cast<double>(refinementExpanded_) * perQuery;
  out["grid_search_queries"] = gridSearchQueries_;
}

std::string pathProblem(const AnnotatedGrid& grid, Agent agent, Cell start, Cell goal,
                        const PathResult& result, std::span<const Cell> path,
                        const CostField* costs) {
  if (path.empty()) return "found, but the path is empty";
  if (!(path.front() == start) || !(path.back() == goal)) {
    return fmt::format("the path runs {},{} -> {},{}", path.front().x, path.front().y,
                       path.back().x, path.back().y);
  }
  if (std::string illegal = findIllegalStep(grid, agent, path); !illegal.empty()) return illegal;
  const double walked = costs ? costs->pathCost(path) : pathCost(path);
  if (std::abs(walked - result.cost) > 1e-6) {
    return fmt::format("the path costs {:.6f}, the result says {:.6f}", walked, result.cost);
  }
  return {};
}

void printReport(const nlohmann::json& out, bool json) {
  if (json) {
    fmt::print("{}\n", out.dump());
    return;
  }
  for (const auto& [key, value] : out.items())
    fmt::print("{:<26}{}\n", key, value.dump());
}

std::vector<int> parseIntList(const std::string& text, const std::string& option) {
  std::vector<int> values;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const auto value = parseInt(std::string_view(text).substr(begin, end - begin));
    if (!value) {
      throw BadInput{option + ": expected comma-separated whole numbers, got '" + text + "'"};
    }
    values.push_back(*value);
    begin = end + 1;
  }
  return values;
}

}  // namespace warpath::tools
