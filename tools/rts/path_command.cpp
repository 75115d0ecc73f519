// `rts path`: plan one path and print it.

#include <fmt/core.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/scenario.h"
#include "pathing/annotated_grid.h"
#include "pathing/map_io.h"
#include "pathing/terrain.h"
#include "pathing/terrain_costs.h"
#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/planner_choice.h"
#include "rts/render_support.h"

namespace warpath::tools {
namespace {

using namespace pathing;

struct PathOptions {
  std::string mapFile;
  AgentChoice agent;
  std::string from;
  std::string to;
  PlannerChoice planner;
  bool json = false;
  bool draw = false;
  std::string png;  // empty: no picture
  bool pngGraph = false;
  std::string costsFile;  // empty: the uniform model
  std::string unitType;   // empty: the agent of --size and --capability
  std::string catalogueFile = WARPATH_CATALOGUE;
};

// The catalogue type named `name`: its agent, and its costs (1 / speed per terrain).
std::pair<Agent, TerrainCosts> unitAgent(const std::string& catalogueFile,
                                         const std::string& name) {
  Result<std::vector<units::UnitType>> catalogue = engine::loadCatalogue(catalogueFile);
  if (!catalogue) throw BadInput{catalogue.error().describe()};
  std::string names;
  for (const units::UnitType& type : catalogue.value()) {
    if (type.name == name) return {type.agent(), type.terrainCosts()};
    names += (names.empty() ? "" : ", ") + type.name;
  }
  throw BadInput{fmt::format("--unit: no type '{}' in {} (it has {})", name, catalogueFile, names)};
}

// The map as text with the agent's footprint along the path drawn as '*', start 's', goal 'g'.
std::string drawPath(const GridMap& map, Agent agent, const std::vector<Cell>& path) {
  std::vector<std::string> rows(static_cast<std::size_t>(map.height()));
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x)
      rows[static_cast<std::size_t>(y)] += mapChar(map.at({x, y}));
  }
  const auto stamp = [&](Cell anchor, char glyph) {
    for (int dy = 0; dy < agent.size; ++dy) {
      for (int dx = 0; dx < agent.size; ++dx) {
        rows[static_cast<std::size_t>(anchor.y + dy)][static_cast<std::size_t>(anchor.x + dx)] =
            glyph;
      }
    }
  };
  for (Cell c : path)
    stamp(c, '*');
  if (!path.empty()) {
    stamp(path.front(), 's');
    stamp(path.back(), 'g');
  }
  std::string out;
  for (const std::string& row : rows)
    out += row + '\n';
  return out;
}

int runPath(const PathOptions& options) {
  const Algorithm algorithm = parseAlgorithm(options.planner.algo);
  Agent agent = parseAgent(options.agent);
  std::optional<TerrainCosts> costs = loadCostsOption(options.costsFile);
  // The agent moves on the terrains that have a cost.
  if (costs) agent.capability = costs->capability();
  std::string costSource = options.costsFile;
  if (!options.unitType.empty()) {
    costSource = fmt::format("unit {} of {}", options.unitType, options.catalogueFile);
    std::tie(agent, costs) = unitAgent(options.catalogueFile, options.unitType);
  }
  const Cell from = parseCell(options.from, "--from");
  const Cell to = parseCell(options.to, "--to");

  const AnnotatedGrid grid(loadMapOrThrow(options.mapFile));
  const GridMap& map = grid.map();
  for (const auto& [cell, option] : {std::pair{from, "--from"}, std::pair{to, "--to"}}) {
    if (!map.contains(cell)) {
      throw BadInput{fmt::format("{} {},{} is outside the map ({}x{}, columns 0..{}, rows 0..{})",
                                 option, cell.x, cell.y, map.width(), map.height(), map.width() - 1,
                                 map.height() - 1)};
    }
  }

  // Annotate (and build the abstraction) first, so the query's metrics measure the search
  // alone. The abstraction serves this capability, for agents up to max(3, size); under costs,
  // this agent alone.
  std::vector<Agent> annotate;
  if (grid.canStand(agent, from)) annotate.push_back(agent);
  const PreparedPlanner prepared =
      costs ? prepareCostPlanner(grid, algorithm, options.planner, agent, *costs)
            : preparePlanner(
                  grid, algorithm, options.planner, annotate,
                  {.capabilities = {agent.capability}, .maxAgentSize = std::max(3, agent.size)});
  Planner planner = prepared.makePlanner(grid);
  const double annotateMs = prepared.preprocessMs + prepareAgents(planner, annotate);
  std::vector<Cell> path;
  const PathResult result = planner.findPath(agent, from, to, &path);
  const SearchMetrics& m = result.metrics;
  if (!options.png.empty()) {
    writePathPng(options.png, map, agent, path,
                 options.pngGraph ? prepared.abstractionOrNull() : nullptr);
  }

  if (options.json) {
    nlohmann::json out;
    out["map"] = options.mapFile;
    out["agent"] = agentJson(agent);
    out["from"] = {from.x, from.y};
    out["to"] = {to.x, to.y};
    out["algo"] = std::string(toString(algorithm));
    out["status"] = std::string(toString(result.status));
    out["costs"] = costs ? nlohmann::json(costSource) : nlohmann::json(nullptr);
    out["length"] = result.found() ? nlohmann::json(result.cost) : nlohmann::json(nullptr);
    nlohmann::json cells = nlohmann::json::array();
    for (Cell c : path)
      cells.push_back({c.x, c.y});
    out["path"] = std::move(cells);
    out["metrics"] = {{"expanded", m.expanded},
                      {"generated", m.generated},
                      {"microseconds", m.microseconds},
                      {"preprocess_ms", annotateMs},
                      {"insertion_expanded", m.insertionExpanded},
                      {"abstract_expanded", m.abstractExpanded},
                      {"refinement_expanded", m.refinementExpanded},
                      {"grid_expanded", m.gridExpanded},
                      {"used_grid_search", m.usedGridSearch}};
    if (prepared.abstraction) {
      nlohmann::json abstraction{{"cluster_size", options.planner.clusterSize}};
      writeAbstractionKeys(prepared.abstractionOrNull(), abstraction);
      out["abstraction"] = std::move(abstraction);
    }
    fmt::print("{}\n", out.dump());
  } else {
    fmt::print("map       {} ({}x{})\n", options.mapFile, map.width(), map.height());
    fmt::print("agent     size {}, capability {}\n", agent.size, agent.capability.toString());
    fmt::print("query     {},{} -> {},{}\n", from.x, from.y, to.x, to.y);
    fmt::print("algo      {}{}\n", toString(algorithm),
               costs ? fmt::format(", terrain costs from {}", costSource) : "");
    fmt::print("status    {}\n", toString(result.status));
    if (result.found()) {
      fmt::print("length    {:.2f} ({} moves)\n", result.cost, path.size() - 1);
    }
    fmt::print("metrics   expanded {}, generated {}, {:.1f} us ({}: {:.2f} ms)\n", m.expanded,
               m.generated, m.microseconds,
               prepared.abstraction ? "annotating the map and building the abstraction"
                                    : "annotating the map",
               annotateMs);
    if (prepared.abstraction) {
      const AbstractionStats& stats = prepared.abstraction->stats();
      fmt::print("phases    insertion {}, abstract {}, refinement {}, grid {} expanded{}\n",
                 m.insertionExpanded, m.abstractExpanded, m.refinementExpanded, m.gridExpanded,
                 m.usedGridSearch ? "; answered by AA* on the grid" : "");
      fmt::print("graph     cluster size {}, {} nodes, {} inter-edges, {} intra-edges\n",
                 options.planner.clusterSize, stats.nodes, stats.interEdges, stats.intraEdges);
    }
    if (result.found()) {
      std::string cells;
      for (Cell c : path)
        cells += fmt::format(" {},{}", c.x, c.y);
      fmt::print("path     {}\n", cells);
      if (options.draw) fmt::print("\n{}", drawPath(map, agent, path));
    }
  }
  return result.found() ? kExitOk : kExitFailed;
}

}  // namespace

void registerPathCommand(CLI::App& app, CommandRunner& run) {
  auto [cmd, options] = addSubcommand<PathOptions>(
      app, run, "path",
      "Plan a path for one agent on a MovingAI .map and print it: the shortest with --algo aa, "
      "else the hierarchical planner's (abstraction for the agent's capability, sizes up to "
      "max(3, size)). Under --costs or --unit every --algo plans under the costs and the length "
      "is in their unit; the hierarchical planners' abstraction then serves that one agent (its "
      "size and capability) and is priced by the costs.\n"
      "Exit status: 0 path found, 1 no path (unreachable, or the agent cannot stand at an "
      "end), 2 bad input.",
      runPath);
  cmd->add_option("map", options->mapFile, "MovingAI .map file")->required();
  addAgentOptions(*cmd, options->agent);
  cmd->add_option("--from", options->from, "start anchor (upper-left cell) as X,Y")->required();
  cmd->add_option("--to", options->to, "goal anchor (upper-left cell) as X,Y")->required();
  addPlannerOptions(*cmd, options->planner);
  CLI::Option* costs = addCostsOption(*cmd, options->costsFile);
  cmd->add_option("--unit", options->unitType,
                  "plan for a catalogue type: its size, capability and costs (1 / its speed on "
                  "each terrain, seconds per cell); every --algo plans under them")
      ->excludes(costs);
  cmd->add_option("--catalogue", options->catalogueFile,
                  "unit catalogue for --unit (default: the bundled assets/units.yaml)")
      ->needs("--unit");
  cmd->add_flag("--json", options->json, "print one JSON object instead of text");
  cmd->add_flag("--draw", options->draw, "also print the map with the path drawn on it");
  cmd->add_option("--png", options->png,
                  "also write a PNG of the map with the agent's footprint along the path");
  cmd->add_flag("--png-graph", options->pngGraph,
                "draw the HAA* graph (edges the agent may use) on the --png picture")
      ->needs("--png");
}

}  // namespace warpath::tools
