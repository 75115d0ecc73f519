#pragma once
// The wording of every settings problem in pathing: the field, the limit and the value, e.g.
// "clusterSize must be >= 2 (got 1)", so that a user can fix the setting from the message alone.

#include <stdexcept>
#include <string>
#include <string_view>

namespace warpath::pathing::limits {

inline std::string atLeast(std::string_view field, long long limit, long long value) {
  std::string out(field);
  out.append(" must be >= ").append(std::to_string(limit));
  return out.append(" (got ").append(std::to_string(value)).append(")");
}

inline std::string between(std::string_view field, long long low, long long high, long long value) {
  std::string out(field);
  out.append(" must be ").append(std::to_string(low)).append("..").append(std::to_string(high));
  return out.append(" (got ").append(std::to_string(value)).append(")");
}

// Throws std::invalid_argument carrying `problem` unless it is empty (the settings are usable).
inline void require(const std::string& problem) {
  if (!problem.empty()) throw std::invalid_argument(problem);
}

}  // namespace warpath::pathing::limits
