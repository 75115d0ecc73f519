#pragma once
// The phases of a world tick (DESIGN.md §4), each with one job, and what they share. World::step
// (engine/src/world.cpp) calls them in order; nothing here is visible outside the engine.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "engine/world.h"

namespace warpath::engine::world {

// What every phase reads (map, catalogue, settings) and writes (the state, the step's events).
struct Refs {
  const pathing::AnnotatedGrid& grid;
  const std::vector<units::UnitType>& catalogue;
  const WorldSettings& settings;
  WorldState& state;
  std::vector<Event>& events;

  const pathing::GridMap& map() const { return grid.map(); }
  const units::UnitType& typeOf(const Unit& unit) const;
  // What the combat rules (units/combat.h) see of a unit.
  units::Combatant combatantOf(const Unit& unit) const;
  // The unit a handle names. A handle the world did not give out is a bug: checked as an
  // invariant (units reached through commands and scripts go through World::find first).
  Unit& unit(UnitId id);
  const Unit& unit(UnitId id) const;
  void log(EventKind kind, const Unit& unit, int detail = 0);
};

int chebyshev(pathing::Cell a, pathing::Cell b);
// The largest unit size in the catalogue (1 when it is empty).
int maxUnitSize(const std::vector<units::UnitType>& catalogue);
// Each path is an allocation of its own, so a pass over every unit that reads each one's next
// waypoint waits on a cache miss or two per unit (stress_2000: most of the rules' and a fifth of
// steering's time). A pass calls this at unit i to have the cache fetch the path of unit i + 8
// and the waypoint (cell and remaining length) of unit i + 4 meanwhile. Changes no state.
// Always inlined: GCC 12 finds a call to it free of side effects and deletes it otherwise.
[[gnu::always_inline]] inline void prefetchPaths(const std::vector<Unit>& all, std::size_t i) {
  if (i + 8 < all.size() && all[i + 8].path) __builtin_prefetch(all[i + 8].path.get());
  if (i + 4 >= all.size() || !all[i + 4].path) return;
  const PlannedPath& path = *all[i + 4].path;
  const std::size_t next = all[i + 4].next;
  if (next < path.cells.size()) __builtin_prefetch(&path.cells[next]);
  if (next < path.remaining.size()) __builtin_prefetch(&path.remaining[next]);
}

// --- Orders: what a unit was told and what it holds for it (engine/src/world/orders.cpp) ---

// Applies a command to its living units, in the order listed.
void applyCommand(Refs& w, const Command& command);
// Undoes what the current order holds: goal claim, parking spot, path, attack targets.
void leaveOrder(Refs& w, Unit& unit);
// Attack order: heads for the nearest living target (a new path when it moved, or `force`);
// the order ends when every target is dead.
void pursue(Refs& w, Unit& unit, bool force);
// The anchor nearest the unit's body where its footprint fits.
pathing::Cell nearestStandable(const Refs& w, const Unit& unit);
// The index of the path cell the unit last passed, where what lies ahead on its path is read
// from: the waypoint before the one it steers to, or with PathServiceSettings::rewindPushedBack
// the last one it stands beyond, if it was pushed back behind that one. `rewind` false: the
// waypoint before, whatever the rule (the terrain check of replays before format 29).
// [Limit: unit.path]
std::size_t placeOnPath(const Refs& w, const Unit& unit, bool rewind = true);
void requestPath(Refs& w, Unit& unit);
// Drops the unit's path and window (and what they reserve) and asks for a new path, the
// progress window restarted: a repath from scratch.
void startPathAfresh(Refs& w, Unit& unit);
// A jammed unit asks for a way around the units standing for good (not following a path) on the
// next stretch of its path, back onto the path past them (docs/cooperative.md, "Detours"). False,
// asking nothing, when none stands there, or they stand at the end of the path; with
// PathServiceSettings::detoursToGoal only when one stands on the goal, or all of them are
// teammates sent to the same area as the same type (else the way leads to the goal, and keeps
// clear of every unit standing in its region). `beforeNewGoal` (asked before a new goal cell):
// false as well for such teammates anywhere on the stretch, whom a new goal cell or the parked
// teammates' rule serve better.
bool requestDetour(Refs& w, Unit& unit, bool beforeNewGoal = false);
// Parked teammates move on (docs/cooperative.md): a unit waiting on a teammate parked on the
// way into their goal area by an order of the same kind (same type, team and area) takes that
// one's goal cell and hands it its own, which lies beyond it; both ask for paths. False,
// changing nothing, when `parked` is not such a teammate, or their goal cells overlap.
bool takeGoalOfParkedTeammate(Refs& w, Unit& unit, Unit& parked);
// Serves the path service within its budget and hands each answer to its unit; returns the
// expansions spent.
std::uint64_t deliverPaths(Refs& w, std::vector<PathDelivery>& scratch);
// [Unit: ticks] The time a unit alone needs along the path it follows, `followed` (the
// delivered one, or its lane): under terrain costs the plan's cost (scaled by the lane's
// detour), else each move at its top speed there. What the report's delays are measured
// against.
std::int64_t freeFlowTicks(const Refs& w, const Unit& unit, const PathDelivery& delivery,
                           const PlannedPath& followed);
// Units whose goal area reassignGoal last found without a free cell for them, and what that
// answer depended on: the goal board around the area (its digest there), the terrain (changes
// applied), the unit's component and its area. Until one of those changes the answer stays the
// same, so the rules do not scan the area again every tick (stress_2000 with the rules of replay
// format 14: about 40 units a tick near the end, up to 1,600 cells each, most of the rules'
// time). Scratch, not state: it only skips work.
class FullGoalAreas {
 public:
  bool stillFull(const Refs& w, const Unit& unit, std::uint32_t component) const;
  void remember(const Refs& w, const Unit& unit, std::uint32_t component);

 private:
  struct Seen {
    std::uint64_t board = 0;
    std::uint64_t terrainChanges = 0;
    std::uint32_t component = 0;
    pathing::CellRect area{};
    bool full = false;
  };
  std::vector<Seen> seen_;  // by unit index
};
// Moves the unit to the nearest free goal cell of its area; false when there is none other.
// With `full`, an area it remembers as full for the unit is not scanned again.
bool reassignGoal(Refs& w, Unit& unit, FullGoalAreas* full = nullptr);
// The unit's goal claim moves from its goal cell to `cell`, which becomes its goal cell.
void moveGoalCell(Refs& w, Unit& unit, pathing::Cell cell);
// hp reached 0: the unit leaves its order, the path service and (after its wreck) physics.
void kill(Refs& w, Unit& unit, UnitId killer);

// --- Combat: targets and fire (engine/src/world/combat.cpp) ---

// Living units bucketed by position (CSR), rebuilt every tick, so that a scan for targets looks
// at the units near the shooter only.
class TargetIndex {
 public:
  // `maxUnitSize`: the largest size in the catalogue (it never changes during a run).
  explicit TargetIndex(int maxUnitSize) : maxUnitSize_(maxUnitSize) {}
  void rebuild(const Refs& w);
  const units::Combatant& combatant(UnitId id) const { return combatants_[id.index]; }
  int maxUnitSize() const { return maxUnitSize_; }
  // Every living unit whose centre may lie within `reach` of `centre` (a superset: whole
  // buckets), in bucket order.
  const std::vector<units::Combatant>& near(units::Vec2 centre, double reach);

 private:
  static constexpr int kBucketCells = 8;  // side of a bucket
  int bucketsWide_ = 0;
  int bucketsHigh_ = 0;
  int maxUnitSize_;
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> units_;
  std::vector<std::uint32_t> fill_;           // next free slot per bucket
  std::vector<units::Combatant> combatants_;  // per unit, this tick
  std::vector<units::Combatant> near_;        // the last near() answer
};

class Combat {
 public:
  explicit Combat(int maxUnitSize) : index_(maxUnitSize) {}
  // Each armed living unit keeps, changes or drops its target (units::chooseTarget); halts
  // to fight under AttackMove and Attack orders.
  void chooseTargets(Refs& w);
  // Ready units fire in id order; shots due land in the order fired (deaths).
  void fire(Refs& w);

 private:
  TargetIndex index_;
  std::vector<units::Combatant> ordered_;  // scratch: an Attack order's living targets
};

// --- Traffic: cooperative windows in space-time (engine/src/world/traffic.cpp) ---

// Drops every reservation the unit holds, and its plan.
void releaseReservations(Refs& w, Unit& unit);
// The plan keeps the unit out of a passage open to the other way (its gate).
inline bool keptOut(const TimedPlan& plan) {
  return plan.gate >= 0 && !plan.admitted;
}
// Drops the unit's reservations and window but not its place at a passage's gate: it stands
// where it is and plans a new window as soon as the budget lets it.
void expireWindow(Refs& w, Unit& unit);
// Gives the unit a plan to stand at `anchor` from now (Blocked, timed: a wait, not a jam) with
// that gate claim, holding the anchor for good until its next window.
void standAt(Refs& w, Unit& unit, pathing::Cell anchor, std::int32_t gate, bool admitted,
             pathing::Tick gateSince);
// True when the plan holds the unit where it is at `tick` (a wait, or the end of a window that
// did not reach the goal).
bool waitingAt(const TimedPlan& plan, pathing::Tick tick);
// Where the unit's plan wants it: desired velocity toward its schedule (the unit has a plan).
units::ScheduleResult followSchedule(const Refs& w, const Unit& unit, double maxSpeed);
// Within a cell of where its plan puts it now.
bool onSchedule(const Refs& w, const Unit& unit);

class Traffic {
 public:
  Traffic();
  ~Traffic();
  // What one tick's windows cost.
  struct TickWork {
    std::uint64_t expanded = 0;  // space-time and distance-field nodes
    bool paused = false;         // a sliced window search stopped at the budget
  };
  // Units that follow no plan hold their footprint; the windows that ran low, or that their
  // units fell off, are planned again in priority order (the unit that waited longest first,
  // then the lower id) within `budget` expansions (at least one window a tick); once a second,
  // cycles of units waiting on each other are broken. With sliced windows (sliced()) the
  // searches stop at the budget (at least kWindowBatch a tick, path_service.h) and resume next
  // tick, the unit holding meanwhile (docs/cooperative.md). Nothing happens when cooperation is
  // off.
  TickWork plan(Refs& w, std::uint64_t budget);
  // The terrain changed: the caches that follow from the map (passing room, distance fields,
  // what is known of tracked cells ahead) are dropped and built again when next needed, and a
  // window search under way is abandoned.
  void terrainChanged();

 private:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  static constexpr std::uint64_t kWindowExpansionLimit = 20000;  // one window's search
  struct Field {
    SharedPath path;     // the spatial path (corridor) or
    pathing::Cell goal;  // the goal (RRA*) the distances belong to
    std::unique_ptr<pathing::DistanceField> field;
  };

  // A passage: a connected set of tracked cells (a door, a corridor, a bridge too narrow for
  // two). Its gate lets one way through at a time, like a one-lane bridge's traffic light.
  struct Passage {
    // Its cells and those of its mouth, with their keep-out levels (CooperativeRequest::keepOut).
    std::vector<std::pair<std::uint32_t, std::uint8_t>> keepOut;
    units::Vec2 centre;  // of its cells (the priority rule: those kept out nearer go first)
  };
  // A passage's gate this tick, as the units' plans say.
  struct Gate {
    std::uint32_t holder = kNone;  // the unit let through first (then the lower id); kNone: free
    std::int64_t holderSince = 0;
    bool turning = false;        // one kept out has waited its turn: nobody new is let through
    std::uint32_t inFlight = 0;  // let through and not past it yet
    std::uint32_t keptOut = 0;   // waiting the other way
    bool oneWay = false;         // used one way only (updateGates): no limit in flight
  };

  // Sorts units (indices) into the order they plan in this tick: the priority rule.
  void inPriorityOrder(const Refs& w, std::vector<std::uint32_t>& order);
  // The passages of the tracked cells, found again when the table tracks more.
  void findPassages(const Refs& w);
  // The passage of an anchor where an agent of this kind could not pass another; -1 for none.
  // `passing`: the agent's passingRoom (looked up once by the loops that scan many anchors).
  std::int32_t passageAt(const pathing::GridMap& map, const std::vector<std::uint8_t>& passing,
                         pathing::Cell anchor) const;
  // The passage the unit stands in or meets next along its path within a window's reach where
  // it could not pass another of its kind; -1 for none.
  std::int32_t passageAhead(const Refs& w, const Unit& unit);
  // passageAhead, found once a tick per unit (the unit follows a path).
  std::int32_t aheadOf(const Refs& w, const Unit& unit);
  // The way the unit's path crosses passage `p` (not normalised; zero when it does not within
  // two windows' reach).
  units::Vec2 passageHeading(const Refs& w, const Unit& unit, std::int32_t p);
  // The gates as the units' plans left them: who holds each, and whether it is turning.
  void updateGates(const Refs& w);
  // A unit kept out of a passage that stands inside it (pushed back in, or caught in its mouth)
  // takes the turn from a holder going the other way that has not entered yet, the only one let
  // through: it cannot wait inside, and the holder cannot pass it
  // (PathServiceSettings::insideGoesFirst).
  void letOutFromInside(Refs& w);
  // The unit's anchor lies in passage `p`.
  bool insidePassage(const Refs& w, const Unit& unit, std::int32_t p);
  // With PathServiceSettings::keptOutBacksOut: the unit, a vehicle kept out of passage `p`,
  // stands inside it with the holder of its turn, who comes the other way, and backs out ahead
  // of the holder.
  bool backsOut(const Refs& w, const Unit& unit, std::int32_t p);
  // Passage `p`'s keep-out levels for a unit that backs out ahead of its holder: inside the
  // passage the levels rise toward the holder, so each move lowers them only away from it.
  void appendBackingOutLevels(const Refs& w, std::int32_t p,
                              std::vector<std::pair<std::uint32_t, std::uint8_t>>& closed);
  // The gate of passage `p` lets the unit through now: it is free, or held by units going the
  // unit's way and not turning.
  bool admits(std::int32_t p, const Unit& unit) const;
  // Appends the cells of the unit's stream out of its passage (those kept out stand clear).
  void addStream(const Refs& w, const Unit& unit, std::vector<std::uint32_t>& stream);
  pathing::CooperativeRequest requestFor(const Refs& w, const Unit& unit, pathing::Cell start);
  // pathing::passingRoom of an agent kind, computed once.
  const std::vector<std::uint8_t>& passingRoom(const Refs& w, pathing::Agent agent);
  pathing::DistanceField& fieldFor(const Refs& w, const Unit& unit);
  void hold(Refs& w, Unit& unit);
  bool chokepointAhead(const Refs& w, const Unit& unit);
  // chokepointAhead, scanned once a tick: nothing it reads changes within Traffic::plan.
  bool chokepointAheadNow(const Refs& w, const Unit& unit);
  // The passage ahead of a walker (a size-1 unit) when it is used one way only, the walker's
  // way; -1 for none.
  std::int32_t walksThroughOneWay(const Refs& w, const Unit& unit);
  // Marks the unit as let through the one-way passage `gate` and cruising: it follows its path,
  // holding nothing.
  void cruiseThrough(Refs& w, Unit& unit, std::int32_t gate);
  // Marks a unit with no chokepoint ahead as cruising: it follows its path, holding nothing.
  void cruise(Refs& w, Unit& unit);
  bool needsWindow(const Refs& w, const Unit& unit);
  // Window searches pause at the budget (PathServiceSettings::sliced with slicedWindows).
  static bool sliced(const Refs& w);
  // Plans the unit's window: to its end, or sliced, up to `limit` expansions spent this tick
  // (then it is pending and the unit holds).
  void planWindow(Refs& w, Unit& unit, std::uint64_t& spent, std::uint64_t limit);
  // Advances the pending window search up to `limit` spent; commits its plan when done.
  void resumeWindow(Refs& w, std::uint64_t& spent, std::uint64_t limit);
  // The pending search's unit still wants that window (same order, path and goal).
  bool stillPending(const Refs& w) const;
  // Hands the unit its new window and reserves it.
  void commitWindow(Refs& w, Unit& unit, pathing::CooperativePlan found, pathing::Cell start,
                    const pathing::CooperativeRequest& request, std::int32_t gate, bool admitted,
                    pathing::Tick gateSince);
  std::optional<std::uint32_t> waitsFor(Refs& w, const Unit& unit);
  void breakDeadlocks(Refs& w, std::uint64_t& spent, std::uint64_t limit);

  // A sliced window search that stopped at a tick's budget: resumed first next tick. What its
  // request points to is kept here; its keep-out cells are set in keepOut_ only while it runs.
  struct PendingWindow {
    std::uint32_t unit = kNone;
    SharedPath path;  // the unit's path and goal when it began
    pathing::Cell goal;
    pathing::Cell start;
    std::int32_t gate = -1;
    bool admitted = false;
    pathing::Tick gateSince = 0;
    pathing::CooperativeRequest request;
    std::vector<std::uint8_t> sharing;
    std::vector<std::pair<std::uint32_t, std::uint8_t>> keepOut;
    pathing::CooperativeStatus status = pathing::CooperativeStatus::Pending;
  };
  // Sets (or clears) the cells a request keeps out of in keepOut_.
  void markKeepOut(const std::vector<std::pair<std::uint32_t, std::uint8_t>>& cells, bool set);

  std::optional<PendingWindow> pending_;
  TickWork work_;
  // Scratch, and caches that are pure functions of the map and the units' paths.
  std::optional<pathing::CooperativeSearch> search_;
  std::map<pathing::Agent, std::vector<std::uint8_t>> passing_;
  // passingRoom's last answer (into passing_) and the agent it was for.
  pathing::Agent lastPassingAgent_;
  const std::vector<std::uint8_t>* lastPassing_ = nullptr;
  std::vector<Field> fields_;  // per unit index
  // Per unit index: the cells of `path` before `clearUntil` are not tracked, and the first
  // passage along the path from waypoint `passageFrom` on is `passage` (passageAhead).
  struct Lookahead {
    SharedPath path;
    std::size_t clearUntil = 0;
    std::uint64_t trackChanges = 0;
    std::size_t passageFrom = SIZE_MAX;
    std::int32_t passage = -1;
  };
  // The unit's Lookahead, begun anew when its path or the tracked cells changed.
  Lookahead& lookaheadOf(const Refs& w, const Unit& unit);
  std::vector<Lookahead> lookahead_;
  std::uint64_t passageTracks_ = ~std::uint64_t{0};  // trackChanges() the passages were found at
  std::vector<std::int32_t> passageOf_;              // per cell: its passage, -1 for none
  std::vector<Passage> passages_;
  std::vector<Gate> gates_;                          // per passage
  std::vector<std::vector<std::uint32_t>> streams_;  // per passage: cells of the stream out
  std::vector<std::uint8_t> keepOut_;  // per cell: a request's keepOut, zero between searches
  std::vector<std::int32_t> backOutDistance_;  // per cell: -1 but while ranking a passage
  std::vector<std::uint32_t> backOutOrder_;    // the cells ranked, in the order reached
  std::vector<std::uint32_t> candidates_;
  // Per unit index, this tick: unit vector toward its goal, or the way it crosses the passage
  // ahead.
  std::vector<units::Vec2> headings_;
  static constexpr std::int32_t kUnknown = -2;
  std::vector<std::int32_t> ahead_;      // per unit index: aheadOf this tick, kUnknown before
  std::vector<std::int8_t> chokepoint_;  // per unit index: chokepointAheadNow, -1 before
  std::vector<std::uint8_t> sharing_;    // per unit index: the request's `sharing`
  std::vector<std::uint8_t> planned_;
  std::vector<std::uint32_t> waitFor_;
  std::vector<std::uint32_t> walk_;
  std::vector<std::uint32_t> cycle_;
  // inPriorityOrder's scratch: a unit kept out of a passage and its place in the order.
  struct KeptOutPlace {
    std::int32_t gate;
    double distance;  // squared, to the passage's centre
    std::uint32_t place;
    std::uint32_t unit;
  };
  std::vector<KeptOutPlace> keptOutPlaces_;
  std::vector<std::uint32_t> places_;
};

// --- Steering: desired velocities into physics (engine/src/world/steering.cpp) ---
// Steering's scratch, with cooperative movement: who touches each vehicle, and which vehicle
// each unit of the lightest kind steps aside for.
struct SteeringScratch {
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::vector<std::uint32_t> touching;      // each vehicle's contacts, one run per unit index
  std::vector<std::uint32_t> start;         // per unit index: its run's start; one past the end
  std::vector<std::uint32_t> stepAsideFor;  // per unit index: a vehicle's index, or kNone
  std::vector<std::uint32_t> contact;       // one body's contacts
  // One vehicle's lane (findVehicleLanes): its body centre, then its path's waypoints ahead.
  std::vector<units::Vec2> coursePoints;
  std::vector<std::uint32_t> walkers;      // walking units' indices, bucket by bucket
  std::vector<std::uint32_t> bucketStart;  // per bucket: its first entry in walkers; one past
  std::vector<std::uint32_t> bucketFill;
  std::vector<std::uint32_t> bucketOfUnit;  // per unit index: a walking unit's bucket, or kNone
  std::vector<double> giveWayWithin;        // per unit index: [cells] stop within this, or +inf
  // Per unit index: the lane to step out of, walking into it toward its vehicle; side 0: none.
  std::vector<units::Vec2> laneHeading;
  std::vector<double> laneSide;
};
void steerAll(Refs& w, SteeringScratch& scratch);
// Reached the end of its path (or window) at the goal: parks there, or, under an Attack order,
// waits at the approach cell for the target.
void arrive(Refs& w, Unit& unit, const units::UnitType& type);

// --- Physics: Box2D steps, positions read back ---
void stepPhysics(Refs& w);

// --- Rules: arrivals, wrecks, repaths, stuck units (engine/src/world/rules.cpp) ---
void applyRules(Refs& w, FullGoalAreas& fullGoalAreas);

// --- Terrain: changes during a run (engine/src/world/terrain.cpp, docs/terrain_changes.md) ---

// A dying unit's wreck: with combat.wrecksBlock and a size >= 2, queues an obstacle over the
// cells of its footprint (applied at the start of the next step) and keeps it in wreckArea.
void placeWreck(Refs& w, Unit& unit);
// The wreck is removed: queues the clearing of its obstacle, if it has one.
void clearWreck(Refs& w, Unit& unit);
// After the cells of `area` changed, in id order: with `push` (terrain set, not an obstacle),
// each living unit whose footprint can no longer stand where it is moves to the nearest anchor
// it can stand on (killed when the map has none); units whose remaining path, window or goal
// crosses `area` (or that were pushed) get a new goal cell when theirs is gone and a new path.
// With `mayOpen` (terrain set to a passable one, an obstacle cleared) units that had found no
// path try again.
void afterTerrainChange(Refs& w, const pathing::CellRect& area, bool push, bool mayOpen);
// FNV-1a of `digest` followed by the edit: TerrainLog::digest after applying `edit`.
std::uint64_t digestAfter(std::uint64_t digest, const TerrainEdit& edit);

}  // namespace warpath::engine::world
