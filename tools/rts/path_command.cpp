// `rts path`: plan one path and print it.

#include <fmt/core.h>

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/annotated_grid.h"
#include "pathing/terrain.h"
#include "rts/cli_support.h"
#include "rts/commands.h"

namespace warpath::tools {
namespace {

using namespace pathing;

struct PathOptions {
  std::string mapFile;
  int size = 1;
  std::string capability = "ground";
  std::string from;
  std::string to;
  bool json = false;
  bool draw = false;
};

char terrainGlyph(Terrain t) {
  switch (t) {
    case Terrain::Ground:
      return '.';
    case Terrain::Swamp:
      return 'S';
    case Terrain::Trees:
      return 'T';
    case Terrain::Water:
      return 'W';
    default:
      return '@';
  }
}

// The map as text with the agent's footprint along the path drawn as '*', start 's', goal 'g'.
std::string drawPath(const GridMap& map, Agent agent, const std::vector<Cell>& path) {
  std::vector<std::string> rows(static_cast<std::size_t>(map.height()));
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x)
      rows[static_cast<std::size_t>(y)] += terrainGlyph(map.at({x, y}));
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
  std::string capabilityError;
  const auto capability = parseCapability(options.capability, &capabilityError);
  if (!capability) throw BadInput{"--capability: " + capabilityError};
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

  const Agent agent{options.size, *capability};
  // Annotate first, so the query's metrics measure the search alone.
  const auto annotateBegan = std::chrono::steady_clock::now();
  if (grid.canStand(agent, from)) grid.layer(agent);
  const double annotateMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - annotateBegan)
          .count();
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  const PathResult result = search.findPath(agent, from, to, &path);

  if (options.json) {
    nlohmann::json out;
    out["map"] = options.mapFile;
    out["agent"] = {{"size", agent.size}, {"capability", agent.capability.toString()}};
    out["from"] = {from.x, from.y};
    out["to"] = {to.x, to.y};
    out["algo"] = "aa";
    out["status"] = std::string(toString(result.status));
    out["length"] = result.found() ? nlohmann::json(result.cost) : nlohmann::json(nullptr);
    nlohmann::json cells = nlohmann::json::array();
    for (Cell c : path)
      cells.push_back({c.x, c.y});
    out["path"] = std::move(cells);
    out["metrics"] = {{"expanded", result.metrics.expanded},
                      {"generated", result.metrics.generated},
                      {"microseconds", result.metrics.microseconds},
                      {"preprocess_ms", annotateMs}};
    fmt::print("{}\n", out.dump());
  } else {
    fmt::print("map       {} ({}x{})\n", options.mapFile, map.width(), map.height());
    fmt::print("agent     size {}, capability {}\n", agent.size, agent.capability.toString());
    fmt::print("query     {},{} -> {},{}\n", from.x, from.y, to.x, to.y);
    fmt::print("status    {}\n", toString(result.status));
    if (result.found()) {
      fmt::print("length    {:.2f} ({} moves)\n", result.cost, path.size() - 1);
    }
    fmt::print("metrics   expanded {}, generated {}, {:.1f} us (annotating the map: {:.2f} ms)\n",
               result.metrics.expanded, result.metrics.generated, result.metrics.microseconds,
               annotateMs);
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
  auto options = std::make_shared<PathOptions>();
  CLI::App* cmd = app.add_subcommand(
      "path",
      "Plan a shortest path for one agent on a MovingAI .map and print it.\n"
      "Exit status: 0 path found, 1 no path (unreachable, or the agent cannot stand at an "
      "end), 2 bad input.");
  cmd->add_option("map", options->mapFile, "MovingAI .map file")->required();
  cmd->add_option("--size", options->size, "agent size in cells (occupies size x size)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd->add_option("--capability", options->capability,
                  "terrains the agent may stand on, comma-separated: ground,swamp,trees,water")
      ->capture_default_str();
  cmd->add_option("--from", options->from, "start anchor (upper-left cell) as X,Y")->required();
  cmd->add_option("--to", options->to, "goal anchor (upper-left cell) as X,Y")->required();
  cmd->add_flag("--json", options->json, "print one JSON object instead of text");
  cmd->add_flag("--draw", options->draw, "also print the map with the path drawn on it");
  cmd->callback([&run, options] { run = [options] { return runPath(*options); }; });
}

}  // namespace warpath::tools
