#pragma once
// Pictures for the CLI's subcommands, drawn by rts_render.

#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/cluster_abstraction.h"

namespace warpath::tools {

// Writes `file` (PNG): the map, the agent's footprint along `path` with the path's line, the
// agent at the goal facing its last move, and the abstraction's graph (edges usable by the
// agent) when `graph` is non-null. Throws BadInput naming the problem when it cannot.
void writePathPng(const std::string& file, const pathing::GridMap& map, pathing::Agent agent,
                  const std::vector<pathing::Cell>& path, const pathing::ClusterAbstraction* graph);

}  // namespace warpath::tools
