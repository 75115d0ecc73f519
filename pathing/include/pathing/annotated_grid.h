#pragma once
// A map annotated for agents of any size and capability: true clearance per capability,
// legal moves and connected components per agent kind, each computed on first use and
// cached. Safe to share between threads: the caches fill under a lock and never change
// what they already hold, except when the terrain changes (setTerrain and the obstacle calls),
// which no query may overlap.

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pathing/clearance.h"
#include "pathing/grid_map.h"
#include "pathing/search.h"

namespace warpath::pathing {

// An agent occupies size×size cells anchored at its upper-left cell and may stand only on
// terrains in its capability.
struct Agent {
  int size = 1;  // [Unit: cells] [Limit: >= 1]
  Capability capability;
  constexpr bool operator==(const Agent&) const = default;
  constexpr auto operator<=>(const Agent&) const = default;
};

// Everything a search needs about one agent kind, one entry per cell.
class AgentLayer {
 public:
  static AgentLayer compute(const GridMap& map, const ClearanceField& clearance, Agent agent);
  // After the clearance changed inside `changed` (ClearanceField::update): the moves of the
  // cells there and next to it, and the components where they changed. `scratch` is the
  // caller's, reused between updates.
  struct Scratch;
  void update(const GridMap& map, const ClearanceField& clearance, Agent agent, CellRect changed,
              Scratch& scratch);

  // Bit d set when the agent anchored at the cell may step in direction d (see moves.h).
  std::span<const std::uint8_t> moveMasks() const { return moveMasks_; }
  // 0 where the agent cannot stand; otherwise equal ids <=> mutually reachable.
  // After updates, ids need not be consecutive: some in 1..componentCount() may label no cell.
  std::span<const std::uint32_t> components() const { return components_; }
  std::uint32_t componentCount() const { return componentCount_; }

 private:
  // What a change did to the cells the agent stands on: only removed some, only added some,
  // or both.
  enum class Change { Split, Join, Both };
  void labelComponents(const GridMap& map, const ClearanceField& clearance, Agent agent);
  void relabel(const GridMap& map, const ClearanceField& clearance, Agent agent, CellRect region,
               Change change, Scratch& scratch);

  std::vector<std::uint8_t> moveMasks_;
  std::vector<std::uint32_t> components_;
  std::uint32_t componentCount_ = 0;
  std::vector<std::uint32_t> sizes_;  // cells per component id (an estimate after updates)
};

// What a change of terrain touched (AnnotatedGrid::setTerrain, placeObstacle, clearObstacle).
struct TerrainChange {
  CellRect area;         // the cells changed, clipped to the map
  bool changed = false;  // false when no cell's terrain differs (nothing to repair)
};

class AnnotatedGrid {
 public:
  explicit AnnotatedGrid(GridMap map);
  ~AnnotatedGrid();
  AnnotatedGrid(const AnnotatedGrid&) = delete;
  AnnotatedGrid& operator=(const AnnotatedGrid&) = delete;

  const GridMap& map() const { return map_; }

  // References stay valid for the grid's lifetime.
  const ClearanceField& clearance(Capability capability) const;
  const AgentLayer& layer(Agent agent) const;
  // Computes the clearances and layers of `agents` not cached yet, on up to `threads` threads
  // (each on its own; what layer() would compute, one at a time).
  void prepare(std::span<const Agent> agents, int threads) const;

  bool canStand(Agent agent, Cell c) const {
    return agent.size >= 1 && clearance(agent.capability).at(c) >= agent.size;
  }

  // Bytes held by the caches (clearances and agent layers) so far.
  std::size_t cacheBytes() const;

  // Terrain that changes during a run (docs/terrain_changes.md). Each call repairs the cached
  // clearances and agent layers for the cells it changed; graphs and services built on the
  // grid are repaired by their owners with the returned change (ClusterAbstraction::repair).
  // Not safe while another thread queries the grid: the owner applies changes between queries.
  //
  // Sets every cell of `area` (clipped to the map) to `terrain`. Under an obstacle the terrain
  // underneath is set, and shows when the last obstacle there is cleared.
  TerrainChange setTerrain(CellRect area, Terrain terrain);
  // An obstacle (a wreck) over `area`: its cells are blocked while it stands, and keep the
  // terrain underneath. Obstacles may overlap; each clearObstacle removes one.
  TerrainChange placeObstacle(CellRect area);
  // [Limit: an obstacle placed over `area` before; else std::invalid_argument]
  TerrainChange clearObstacle(CellRect area);
  // Counts the changes made (calls that changed a cell), from 0.
  std::uint64_t revision() const { return revision_; }
  // The smallest rectangle holding every cell changed after `revision` (empty when none), for
  // caches that repair rather than rebuild; nullopt when those changes are too many to keep
  // (the last kChangesKept are), so the cache must find what changed itself.
  std::optional<CellRect> changedSince(std::uint64_t revision) const;
  static constexpr std::size_t kChangesKept = 64;
  // Threads that repair the caches of different capabilities at once after a change (each
  // capability's clearance with its agent layers); the caches come out the same for any count.
  // At least 1 (the default).
  void setUpdateThreads(int threads) { updateThreads_ = threads < 1 ? 1 : threads; }

 private:
  // Repairs the caches after the cells of `area` changed.
  void refresh(CellRect area);

  GridMap map_;
  std::vector<std::unique_ptr<AgentLayer::Scratch>> scratch_;  // for layer updates, per thread
  int updateThreads_ = 1;
  // Obstacles standing on each cell, and the terrain under them (allocated at the first one).
  std::vector<std::uint16_t> obstacles_;
  std::vector<Terrain> underneath_;
  std::uint64_t revision_ = 0;
  std::deque<CellRect> changes_;  // the areas of the last changes, the newest (revision_) last
  mutable std::mutex mutex_;
  mutable std::map<Capability, std::unique_ptr<ClearanceField>> clearances_;
  mutable std::map<Agent, std::unique_ptr<AgentLayer>> layers_;
};

// What a query can be answered without searching: InvalidStart / InvalidGoal when the agent
// cannot stand at an end, Unreachable when the ends lie in different connected components for
// the agent; nullopt when a search is needed. `layer`: grid.layer(agent), when the caller keeps
// it (the grid's look-up takes a lock).
std::optional<PathStatus> screenEndpoints(const AnnotatedGrid& grid, Agent agent, Cell start,
                                          Cell goal, const AgentLayer* layer = nullptr);
// screenEndpoints, then the limits: Unreachable when a region leaves out an end,
// BudgetExhausted for a zero budget. What every grid search answers before it searches.
std::optional<PathStatus> screenQuery(const AnnotatedGrid& grid, Agent agent, Cell start, Cell goal,
                                      const SearchLimits& limits,
                                      const AgentLayer* layer = nullptr);

// Checks that `path` is a sequence of legal single moves for the agent (start and goal
// included). Returns an empty string when legal, else what is wrong and at which step.
std::string findIllegalStep(const AnnotatedGrid& grid, Agent agent, std::span<const Cell> path);

// Sum of the move costs along a path of adjacent cells.
double pathCost(std::span<const Cell> path);

}  // namespace warpath::pathing
