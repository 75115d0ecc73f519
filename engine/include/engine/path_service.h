#pragma once
// The one path service every unit asks. Requests queue in arrival order and are served in
// that order, a tick at a time, until the tick's budget of node expansions is spent (the
// request that crosses the budget finishes; a tick always serves at least one), or with
// `sliced` searches the request at the head is advanced only up to the budget and resumed next
// tick. Budgets count expansions, never wall time, so the simulation stays deterministic. Answers
// are cached by (agent, start, goal): identical requests within a tick are coalesced and repeated
// ones later are free, until a change of terrain touches them (changeTerrain).

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "engine/congestion.h"
#include "engine/handle.h"
#include "pathing/aa_star.h"
#include "pathing/annotated_grid.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/cooperative_search.h"
#include "pathing/lanes.h"
#include "pathing/planner.h"
#include "pathing/terrain_costs.h"

namespace warpath::engine {

struct PathServiceSettings {
  pathing::Algorithm algorithm = pathing::Algorithm::Hybrid;
  int clusterSize = 16;  // [Unit: cells] [Limit: 2..pathing::kMaxClusterSize]
  // Levels of the HAA* graph (pathing::AbstractionSpec::levels): 2 adds level-2 clusters of
  // levelTwoSize × levelTwoSize clusters, crossed by exact level-2 edges (the same path costs;
  // fewer nodes expanded on long queries across large maps, more memory). [Limit: 1..2]
  int levels = 1;
  int levelTwoSize = 4;  // [Unit: clusters] [Limit: 2..256]
  // Not a scenario key (`rts run --threads`): threads that search the HAA* graphs' clusters at
  // once when they are built and repaired (pathing::AbstractionSpec::threads). Every graph,
  // and so every run, is the same for any count. [Limit: 1..pathing::kMaxBuildThreads]
  int buildThreads = 1;
  std::uint64_t expansionBudget = 20000;  // [Limit: >= 1] node expansions per tick
  std::size_t cacheCapacity = 4096;       // answers kept; the oldest go first
  // Cooperative movement (docs/cooperative.md): moving units plan space-time windows against
  // each other's reservations at chokepoints, and the movement rules that go with it hold
  // (turning-circle slow-down, stuck = no progress along the path, pushing limited to the
  // pushed unit's speed, units holding position braced). false: each unit follows its spatial
  // path alone and Box2D settles every conflict, exactly as the first release did. On by
  // default since replay format 7: it passes more of the chokepoint scenarios than independent
  // planning (docs/cooperative.md); replays of older formats play back with it off.
  bool cooperative = true;
  // [Unit: moves] [Limit: 1..kMaxCooperativeWindow] how far ahead a unit reserves: this many
  // cardinal moves at its top speed; re-planned when half of it is left.
  int window = 16;
  // How a window is searched: true: CPRA*(k), inside a corridor of `corridor` cells around the
  // unit's HAA* path, with exact distances in the corridor as the heuristic; false: WHCA* with
  // a reverse resumable A* (exact distances on the whole map) as the heuristic.
  bool corridorSearch = true;
  int corridor = 4;
  // Congestion-aware routes (engine/congestion.h), with cooperation and a hierarchical
  // algorithm: each delivered path books its unit at the narrow places it crosses, and a long
  // route's abstract search adds the wait expected there, so that it takes a free bridge when
  // the detour costs less than the wait. Cached answers are used only where they meet no
  // queue, and answers that meet one are not cached.
  bool congestion = true;  // [Unit: cells] [Limit: 1..64] the CPRA*(k) corridor's half-width k
  // Terrain costs (docs/terrain_costs.md): each unit type plans the fastest route for its own
  // speeds (cost = 1 / speed per terrain) instead of the shortest in cells, with any algorithm
  // (the hierarchical ones on a weighted graph per cost profile). Off by default, so scenarios
  // plan as they always did.
  bool terrainCosts = false;
  // Sliced searches (issue 15): the search of the request at the head of the queue stops when
  // the tick's budget is spent and resumes next tick, and an HAA* insertion (one step of up to
  // clusterSize^2 cells) that does not fit in what is left waits for the next tick, so a tick's
  // requests never spend more than the budget (or one insertion, when the budget is smaller).
  // Answers are planned as unsliced ones, delivered when done (congestion waits: those expected
  // when the search began, read as the queues stand while it runs). Off by default: the request
  // that crosses the budget runs to its end, as scenarios always have.
  // With cooperation the window searches (engine/src/world/traffic.cpp) are sliced too: they
  // spend what the spatial searches left of the budget (at least kWindowBatch a tick), a
  // search that reaches it pauses and resumes next tick while its unit stands where it is, and
  // its plan is checked against the reservations when it ends (docs/cooperative.md).
  bool sliced = false;
  // How HAA* links a query's ends to their clusters' nodes (`insertion`, pathing::InsertionMode):
  // a Dijkstra per end (the default, as scenarios always have), or tables per unit kind and
  // cluster, built at a cluster's first query and again after a terrain change redoes it
  // (docs/haa.md "Insertion by tables"): fewer expansions a long query, other cells at times
  // among equal-cost ways. Weighted graphs (`terrain_costs`) keep the Dijkstra.
  pathing::InsertionMode insertion = pathing::InsertionMode::Search;
  // Not a scenario key: false plays back replays of format 8, whose sliced runs sliced only the
  // spatial searches (kFirstSlicedWindowsReplayVersion).
  bool slicedWindows = true;
  // Not a scenario key: EverySide plays back replays before format 10 with `jps` and `jps+` as
  // they searched then (kFirstForcedJumpsReplayVersion).
  pathing::JumpSuccessors jumpSuccessors = pathing::JumpSuccessors::ForcedOnly;
  // Not a scenario key: HighestLevel plays back replays before format 11 with units kept out
  // of a passage leaving it as they did then (kFirstKeptOutRulesReplayVersion).
  pathing::KeepOutExit keepOutExit = pathing::KeepOutExit::Stepwise;
  // Not a scenario key: false plays back replays before format 11, when units kept out of a
  // passage were let through in the priority order of all (longest wait first), not nearest to
  // it first (kFirstKeptOutRulesReplayVersion).
  bool nearestKeptOutFirst = true;
  // Not a scenario key: false plays back replays before format 12, when vehicles' lanes ended
  // at a junction too wide for lanes (pathing::keepRight's throughJunctions;
  // kFirstJunctionRulesReplayVersion).
  bool lanesThroughJunctions = true;
  // Not a scenario key: false plays back replays before format 12, when a walker stepping off a
  // vehicle's course (driven into, or in another team's vehicle's lane ahead) stepped to the
  // side it was on even where it had no room there (docs/cooperative.md).
  bool stepAsideToRoom = true;
  // Not a scenario key: false plays back replays before format 13, when a cooperating unit
  // without a timed window that jammed asked for its path again instead of a detour around the
  // units standing in its way (docs/cooperative.md, "Detours").
  bool jamDetours = true;
  // Not a scenario key: false plays back replays before format 14, when a vehicle stopped in
  // the traffic claimed no lane, whatever stopped it (docs/cooperative.md, "Lanes").
  bool standingVehicleLanes = true;
  // Not a scenario key: false plays back replays before format 15, when a cooperating unit
  // inside its goal area, whose goal cell another had parked on and whose area had no other
  // free cell for it, went on pushing (docs/cooperative.md, "Full goal areas").
  bool parkWhenAreaFull = true;
  // Not a scenario key: false plays back replays before format 16, when a passage's gate let at
  // most 8 units through at a time and walkers crossed it in timed windows even while nobody
  // came the other way (docs/cooperative.md, "One-way passages").
  bool oneWayPassages = true;
  // Not a scenario key: false plays back replays before format 17, when a notch in a ragged
  // edge (a dent, pathing::Dents) was a chokepoint like a door (docs/cooperative.md, "Dents").
  bool openDents = true;
  pathing::Dents dents() const { return openDents ? pathing::Dents::Open : pathing::Dents::Narrow; }
  // Not a scenario key: false plays back replays before format 18, when a vehicle's lane ended
  // at its passage's mouth (pathing::keepRight's holdBeyond; docs/cooperative.md, "Lanes").
  bool laneApproaches = true;
  // Not a scenario key: false plays back replays before format 19, when a cooperating unit
  // queued behind one going its way counted its windows without progress toward the stuck flag
  // like a unit jammed (docs/cooperative.md, "Queues are not jams").
  bool queuesExcused = true;
  // Not a scenario key: false plays back replays before format 20, when a vehicle's lane held
  // two footprints beyond its passage however wide the passage was (pathing::LaneRules;
  // docs/cooperative.md, "Lanes held farther beyond wide passages").
  bool widerLaneApproaches = true;
  // Not a scenario key: false plays back replays before format 21, when two vehicles meeting
  // head on outside timed windows pushed nose to nose instead of each veering to its right
  // (docs/cooperative.md, "Head on in the open").
  bool headOnKeepRight = true;
  // Not a scenario key: false plays back replays before format 22, when a vehicle's lane whose
  // detour cost more than two cells per cell of footprint side plus one was dropped however far
  // it had to shift (pathing::LaneRules::detourByShift; docs/cooperative.md, "Lanes across
  // wide passages").
  bool wideLaneDetours = true;
  // Not a scenario key: false plays back replays before format 22, when a unit's planned time
  // (the report's delays, and the state hash) was its delivered path's, before its lane.
  bool plannedTimeWithLanes = true;
  // Not a scenario key: false plays back replays before format 22, when a vehicle veered right
  // only from a vehicle moving at it, not from a lighter one that steers its way however it
  // moves (pushed back, or stopped against it; docs/cooperative.md, "Lighter vehicles that want
  // to come our way").
  bool headOnByIntent = true;
  // Not a scenario key: false plays back replays before format 23, when a unit kept out of a
  // passage waited where it stood even inside it, while the holder of the passage's turn, going
  // the other way and not yet in, pushed it back through (docs/cooperative.md, "Inside goes
  // first").
  bool insideGoesFirst = true;
  // Not a scenario key: false plays back replays before format 24, when a unit waiting in its
  // window on a teammate parked on the way into their goal area (same type, team and area) went
  // on waiting, instead of taking the parked one's goal cell and sending it on to its own, which
  // lies beyond (docs/cooperative.md, "Parked teammates move on").
  bool parkedMoveOn = true;
  // Not a scenario key: false plays back replays before format 25, when the turning-circle cap
  // slowed a cooperating unit until it could pass through the centre of its waypoint, not just
  // within the waypoint's radius, which held vehicles jostled in a crowd to 2/3 of their speed
  // (units::turnLimitedSpeed's `within`; docs/cooperative.md, "Turning within the waypoint").
  bool turnsWithinWaypoints = true;
  // Not a scenario key: false plays back replays before format 26, when only units of the
  // lightest kind stepped off the course of a vehicle driving into them, and a jeep a heavier
  // tank drove into kept driving at it, pushed back (docs/cooperative.md, "Lighter vehicles step
  // aside").
  bool lighterVehiclesStepAside = true;
  // Not a scenario key: false plays back replays before format 26, when a unit turning about
  // always turned the shorter way round, even into a wall or a river's bank, which cancelled the
  // turn (docs/cooperative.md, "Turning away from walls").
  bool turnAwayFromWalls = true;
  // Not a scenario key: false plays back replays before format 27, when a unit kept out of a
  // passage but standing inside it, with the holder inside too and coming at it, kept the window
  // it had (ending at its goal, say) and waited to be pushed, and the two could press together
  // in a corridor until the run ended (docs/cooperative.md, "Backing out ahead of the holder").
  bool keptOutBacksOut = true;
  // Not a scenario key: false plays back replays before format 28, when a unit pushed back along
  // its path went on as if it stood at the waypoint it had reached: it read what lies ahead (the
  // passage it must ask to cross, the stream it leaves) from there and steered back to it, so a
  // tank shoved back through a corridor took the corridor as behind it and drove into it again
  // without asking for its turn (docs/cooperative.md, "Pushed back along the path").
  bool rewindPushedBack = true;
  // Not a scenario key: false plays back replays before format 29, when a terrain change made a
  // unit repath if it touched its path from the waypoint before the one it steers to, not from
  // its place on the path (docs/terrain_changes.md): a unit pushed back behind that waypoint
  // kept a path through a change on the cells it had yet to walk again.
  bool routeFromPlaceOnPath = true;
  // Not a scenario key: false plays back replays before format 30, when a jammed unit asked for
  // a new goal cell before a way round the units standing in its way, a detour was refused when
  // they stood within a footprint and two cells of the path's end, and a detour kept clear only of
  // the units standing on the path's next stretch: a rifleman jammed against a line of parked
  // jeeps just before its goal area was given goal cells behind the line until the run ended
  // (docs/cooperative.md, "Detours to the goal"). Teammates of the unit's kind sent to its area
  // standing in its way are still the goal rule's first.
  bool detoursToGoal = true;
  pathing::LaneRules laneRules() const {
    return {lanesThroughJunctions, laneApproaches, widerLaneApproaches, wideLaneDetours};
  }
};
inline constexpr int kMaxCooperativeWindow = 256;
// [Unit: expansions] what sliced window searches may spend in a tick the spatial searches left
// less of the budget: one batch, so that windows never wait for the budget forever.
inline constexpr std::uint64_t kWindowBatch = 256;
// [Unit: clusters] side of a chunk of graph repair (PathService::changeTerrain).
inline constexpr int kRepairChunkClusters = 4;

struct Detour;

struct PathRequest {
  UnitId unit;
  std::uint64_t serial = 0;  // the unit's request number; stale answers are ignored
  pathing::Agent agent;
  pathing::Cell start;
  pathing::Cell goal;
  int costProfile = -1;  // index into the service's cost profiles; -1: every cell costs 1
  // [Unit: cells/s] the unit's top speed, for the waits of congestion-aware routes; 0: the
  // request neither meets nor joins a queue.
  double speed = 0.0;
  // A jammed unit's way around what stands in its way; null for any other request.
  std::shared_ptr<const Detour> detour = nullptr;
};

// What one kind of unit plans by under terrain costs: its agent and its cost per terrain.
struct CostProfile {
  pathing::Agent agent;
  pathing::TerrainCosts costs;
};

// A found path: anchor cells from start to goal, and a digest of them computed once when the
// path is planned, so that the state hash covers every unit's path without walking it each tick.
struct PlannedPath {
  std::vector<pathing::Cell> cells;
  std::vector<double> remaining;  // [Unit: cells] path length from cells[i] to the end
  std::uint64_t digest = 0;       // FNV-1a over the cells
};
PlannedPath planned(std::vector<pathing::Cell> cells);
using SharedPath = std::shared_ptr<const PlannedPath>;

// A jammed unit's detour (docs/cooperative.md, "Detours"): the service plans from the request's
// start to `rest`'s cell `rejoin` by AA* inside `region`, entering the footprints in `avoid`
// (the units standing in its way) only at a penalty of kDetourPenalty cells each anchor, and
// delivers that way on along `rest` to its end. Where no way inside the region is found, the
// request is planned as any other. The answer is neither cached nor taken from the cache.
struct Detour {
  std::vector<pathing::CellRect> avoid;
  pathing::CellRect region;
  SharedPath rest;  // [Limit: rejoin < rest->cells.size(), region holds the request's start and it]
  std::uint32_t rejoin = 0;
};
// [Unit: cells of travel] what a detour pays for each anchor it enters whose footprint overlaps a
// unit standing in the way (times the cheapest cost of a cell under terrain costs): a way around
// is taken when it is at most this much longer per anchor saved.
inline constexpr double kDetourPenalty = 10.0;

struct PathDelivery {
  UnitId unit;
  std::uint64_t serial = 0;
  pathing::PathStatus status = pathing::PathStatus::Unreachable;
  SharedPath path;  // set when found
  // [Unit: s] the path's cost under its unit's terrain costs (its predicted travel time);
  // negative when planned in the uniform model.
  double seconds = -1.0;
};

struct PathServiceMetrics {
  std::uint64_t requests = 0;
  std::uint64_t cacheHits = 0;  // answered from the cache, coalesced duplicates included
  std::uint64_t searches = 0;
  std::uint64_t found = 0;
  std::uint64_t failed = 0;  // unreachable or invalid start/goal
  std::uint64_t expanded = 0;
  std::size_t maxQueue = 0;
  double microseconds = 0.0;  // wall time of the searches: measurement only
  double preprocessMilliseconds = 0.0;
  std::uint64_t terrainChanges = 0;
  std::uint64_t cacheDropped = 0;  // answers dropped because a change touched them
  std::uint64_t repairChunks = 0;
  std::uint64_t repairExpanded = 0;  // cells the graph repairs' searches expanded
  double repairMilliseconds = 0.0;   // wall time of graph repairs: measurement only
  // Searches that met a queue on the way (congestion-aware routes): planned with the waits as
  // surcharges, the cache passed by.
  std::uint64_t congestedSearches = 0;
  // The most one tick spent: serve()'s searches and repairs, and with cooperation the window
  // searches' space-time and distance-field nodes (countWindows).
  std::uint64_t maxTickExpanded = 0;
  std::uint64_t slices = 0;        // sliced searches' pauses at the end of a tick's budget
  std::uint64_t windowSlices = 0;  // sliced window searches' pauses (countWindows)
  std::uint64_t detours = 0;       // detours found (PathRequest::detour); also in `searches`
  bool operator==(const PathServiceMetrics& o) const {  // wall-clock fields excluded
    return std::tie(requests, cacheHits, searches, found, failed, expanded, maxQueue,
                    terrainChanges, cacheDropped, repairChunks, repairExpanded, congestedSearches,
                    maxTickExpanded, slices, windowSlices, detours) ==
           std::tie(o.requests, o.cacheHits, o.searches, o.found, o.failed, o.expanded, o.maxQueue,
                    o.terrainChanges, o.cacheDropped, o.repairChunks, o.repairExpanded,
                    o.congestedSearches, o.maxTickExpanded, o.slices, o.windowSlices, o.detours);
  }
};

class PathService {
 public:
  // Builds the abstraction the algorithm needs for these capabilities and agent sizes up to
  // maxAgentSize. The grid must outlive the service. Throws std::invalid_argument when
  // problemWith(settings) is not empty, or (for the hierarchical algorithms) when the
  // abstraction's spec is not usable (pathing::problemWith(AbstractionSpec): capabilities
  // empty, maxAgentSize outside 1..255); callers taking user input check problemWith first.
  // `costProfiles`: what requests with costProfile >= 0 plan by (used with terrainCosts).
  // Profiles equal on the map's terrains share one planner; each planner (and, for the
  // hierarchical algorithms, its weighted graph) is built when its first request is served,
  // so only the kinds of unit on the map pay for one. With terrainCosts no uniform graph is
  // built: every request carries a profile.
  PathService(const pathing::AnnotatedGrid& grid, const PathServiceSettings& settings,
              std::vector<pathing::Capability> capabilities, int maxAgentSize,
              std::vector<CostProfile> costProfiles = {});
  ~PathService();
  PathService(const PathService&) = delete;
  PathService& operator=(const PathService&) = delete;

  // With sliced searches: the expansions the search of the request at the head of the queue
  // has spent in earlier ticks (0 when none is under way).
  std::uint64_t slicedExpanded() const;
  // The tick's cooperative windows, for the metrics: `served` what this tick's serve() spent,
  // `windows` what the window searches expanded after it, `paused` whether one stopped at the
  // budget.
  void countWindows(std::uint64_t served, std::uint64_t windows, bool paused);

  // The grid's terrain changed (AnnotatedGrid::setTerrain or an obstacle): drops the cached
  // answers the change touches (paths that cross the changed cells, and every failed answer,
  // which may now succeed), repairs the cost fields at once and queues the repair of every
  // graph in chunks of kRepairChunkClusters clusters a side. serve() repairs chunks first, at
  // least one a tick and more while the tick's budget lasts (a chunk costs the cells its
  // searches expand); requests wait until the last chunk is done, so every answer is planned
  // on the changed map.
  void changeTerrain(const pathing::TerrainChange& change);
  // Chunks of graph repair still to do.
  std::size_t repairsPending() const { return pendingRepairs_.size(); }

  void request(const PathRequest& request);
  // Drops the unit's queued requests (it died): its searches are not run (nor finished, when
  // sliced).
  void cancel(UnitId unit);
  // Serves queued requests in order within the budget, appending one delivery each. Returns
  // the node expansions spent (what is left of the budget goes to cooperative windows).
  // `now` [Unit: s of simulated time] dates the bookings of congestion-aware routes.
  std::uint64_t serve(std::vector<PathDelivery>& out, double now = 0.0);

  std::size_t queued() const { return queue_.size(); }
  // The requests waiting, in the order they will be served.
  const std::deque<PathRequest>& queue() const { return queue_; }
  const PathServiceMetrics& metrics() const { return metrics_; }
  const PathServiceSettings& settings() const { return settings_; }
  // The HAA* graph the service plans on (for drawing): the uniform one, or under terrain costs
  // the first weighted one built; null when the algorithm needs none (or none is built yet).
  const pathing::ClusterAbstraction* abstraction() const;
  // Cost profiles that plan differently on this map (equal ones merged), and how many of
  // their planners are built so far.
  std::size_t distinctCostProfiles() const { return weighted_.size(); }
  std::size_t builtCostPlanners() const;

 private:
  using Key = std::tuple<int, std::uint8_t, int, int, int, int, int>;
  struct Answer {
    pathing::PathStatus status;
    SharedPath path;
    double seconds;
  };

  // The planner of one distinct cost profile, built on first use. Held by pointer: the
  // planner refers to the field and the graph beside it.
  struct WeightedPlanner {
    pathing::Agent agent;  // the capability cut to the terrains that have a cost
    pathing::TerrainCosts costs;
    std::optional<pathing::CostField> field;  // AA* only
    std::unique_ptr<pathing::ClusterAbstraction> abstraction;
    std::optional<pathing::Planner> planner;
  };
  WeightedPlanner& weightedPlanner(int costProfile);
  // Repairs the graphs for the next pending chunk; returns the cells its searches expanded.
  std::uint64_t repairChunk();
  // Groups the cost profiles that plan alike on the terrains present_ (planners unbuilt).
  void mergeCostProfiles();
  // Plans `request` within `budget` expansions when sliced (else to its end), with the
  // congestion waits at `now` when `congestion` is given: the result, or nullopt while its
  // search is left pending for the next tick. Adds what it spends to `spent`.
  // A search done: counted in the metrics with what it expanded and took.
  void countSearch(const pathing::PathResult& result);
  // The search of `request`'s detour, within `budget` expansions when sliced (else to its end):
  // Pending while it is left for the next tick; Found with its cells (its start, the way around,
  // the rest of the path) and under terrain costs their cost in `seconds`; else no way inside its
  // region. Adds what it expands to `spent`.
  struct DetourOutcome {
    pathing::PathStatus status = pathing::PathStatus::Unreachable;
    std::vector<pathing::Cell> cells;
    double seconds = -1.0;
  };
  DetourOutcome detourFor(const PathRequest& request, std::uint64_t budget, std::uint64_t& spent);
  std::optional<pathing::PathResult> search(const PathRequest& request, std::uint64_t budget,
                                            double now, Congestion* congestion,
                                            std::uint64_t& spent, std::vector<pathing::Cell>& cells,
                                            double& seconds);

  const pathing::AnnotatedGrid& grid_;
  PathServiceSettings settings_;
  std::unique_ptr<pathing::ClusterAbstraction> abstraction_;
  std::optional<pathing::Planner> planner_;
  pathing::AnnotatedAStar detourSearch_;  // detours plan by AA*, whatever the algorithm
  bool detourInFlight_ = false;           // sliced: detourSearch_ runs for the queue's head
  std::vector<CostProfile> costProfiles_;
  // Terrains the map has or had: a profile's planner serves the terrains seen so far.
  pathing::Capability present_;
  std::vector<int> distinctOf_;  // cost profile -> index in weighted_
  std::vector<std::unique_ptr<WeightedPlanner>> weighted_;
  std::deque<PathRequest> queue_;
  std::deque<pathing::CellRect> pendingRepairs_;
  std::map<Key, Answer> cache_;
  std::deque<Key> cacheOrder_;            // insertion order, for eviction
  std::optional<Congestion> congestion_;  // with settings_.congestion in force
  // Sliced: the planner whose search for the head of the queue is under way (null: none); it
  // is abandoned (begun again later) when the head is served otherwise (from the cache), its
  // unit is cancelled or the terrain changes.
  pathing::Planner* inFlight_ = nullptr;
  // The congestion waits the search under way plans with, dated when it began.
  std::optional<Congestion::Surcharge> surcharge_;
  PathServiceMetrics metrics_;
};

// Empty when the settings can be used, else what is wrong, naming the field, its limit and
// the value ("clusterSize must be 2..4096 (got 1)").
std::string problemWith(const PathServiceSettings& settings);

}  // namespace warpath::engine
