#pragma once
// What every path query returns: a status and the effort it took.

#include <cstdint>
#include <string_view>

namespace warpath::pathing {

enum class PathStatus : std::uint8_t {
  Found,
  Unreachable,   // start and goal are valid but not connected for this agent
  InvalidStart,  // outside the map, or the agent cannot stand there
  InvalidGoal,   // outside the map, or the agent cannot stand there
};

std::string_view toString(PathStatus status);

struct SearchMetrics {
  std::uint64_t expanded = 0;   // nodes taken off the open list and expanded
  std::uint64_t generated = 0;  // nodes pushed onto the open list
  double microseconds = 0.0;    // wall time of the query (a measurement, never an input)
};

struct PathResult {
  PathStatus status = PathStatus::Unreachable;
  double cost = 0.0;  // [Unit: cells] path length with diagonal steps counted as √2
  SearchMetrics metrics;

  bool found() const { return status == PathStatus::Found; }
};

}  // namespace warpath::pathing
