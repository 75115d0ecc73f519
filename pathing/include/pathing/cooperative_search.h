#pragma once
// Cooperative pathfinding in space-time (Silver 2005, WHCA*; Sturtevant & Buro 2006, CPRA*):
// an agent plans a window of timed moves, waits included, that keeps clear of what others have
// reserved (pathing/reservation_table.h), guided by a distance field to its goal that ignores
// the others:
//   - ReverseResumableSearch: exact distances on the whole map, by a backward A* resumed on
//     demand (WHCA*'s heuristic).
//   - CorridorDistance: exact distances inside a corridor around the agent's hierarchical path,
//     infinite outside it, so the search stays in the corridor (CPRA*(k), k the corridor's
//     half-width): a refinement of the HAA* route that cooperates.
// Time is in ticks of the simulation; a move's duration follows from the agent's speed on the
// terrain it moves onto. STL only; a CooperativeSearch owns its scratch (one per thread).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/enum_names.h"
#include "pathing/moves.h"
#include "pathing/open_list.h"
#include "pathing/reservation_table.h"
#include "pathing/search.h"

namespace warpath::pathing {

// Distances to one goal for one agent kind, ignoring other agents. Non-const: the searches
// behind them run lazily, and can be advanced in slices (settle) so that a sliced
// CooperativeSearch counts their work against its allowance.
class DistanceField {
 public:
  virtual ~DistanceField() = default;
  // [Unit: move cost, 1 a cardinal step, √2 a diagonal] +inf when the goal cannot be reached
  // from `c` (or, for a corridor, `c` lies outside it). Settles `c` first, without bound.
  double distance(Cell c) {
    std::uint64_t unbounded = kUnboundedExpansions;
    settle(c, unbounded);
    return settled(c);
  }
  // Advances the search behind the field until distance(c) is known, by at most `allowance`
  // expansions (decremented by those taken); false when they ran out first (call again: the
  // search resumes where it stopped, so the field is the same however it was sliced).
  virtual bool settle(Cell c, std::uint64_t& allowance) = 0;
  // distance(c) of a cell settle() answered true for.
  virtual double settled(Cell c) const = 0;
  // Nodes expanded so far building the field (a measurement).
  virtual std::uint64_t expanded() const = 0;
  // Every distance is known: settle() answers true at once and spends nothing, for any cell.
  virtual bool complete() const = 0;
};

// Reverse Resumable A* (Silver 2005): A* from `goal` toward `start` on the agent's layer (its
// moves are symmetric), resumed until the asked cell is closed; with the octile heuristic every
// closed cell's distance is exact. Memory grows with the cells touched, never with the map.
class ReverseResumableSearch final : public DistanceField {
 public:
  ReverseResumableSearch(const AnnotatedGrid& grid, Agent agent, Cell goal, Cell start);
  bool settle(Cell c, std::uint64_t& allowance) override;
  double settled(Cell c) const override;
  std::uint64_t expanded() const override { return expanded_; }
  bool complete() const override { return open_.empty(); }

 private:
  struct Entry {
    double g = 0.0;
    bool closed = false;
  };
  struct Open {
    double f;
    double g;
    std::uint32_t cell;
  };
  void push(std::uint32_t cell, double g);

  const AnnotatedGrid& grid_;
  Agent agent_;
  const GridMap& map_;
  std::span<const std::uint8_t> moves_;
  Cell target_;
  std::unordered_map<std::uint32_t, Entry> entries_;
  std::vector<Open> open_;  // a binary heap (std::push_heap) on (f, then larger g, then cell)
  std::uint64_t expanded_ = 0;
};

// The cells within Chebyshev distance `radius` of `path` (the agent's path from the
// hierarchical planner, start to goal) where the agent can stand, with exact distances to
// path.back() inside them from one backward Dijkstra over them; +inf outside. The corridor is
// laid out on construction; the Dijkstra runs on the first settle (to its end: every distance
// waits for it), in slices when settled with an allowance.
class CorridorDistance final : public DistanceField {
 public:
  // [Limit: !path.empty(), radius >= 0]
  CorridorDistance(const AnnotatedGrid& grid, Agent agent, std::span<const Cell> path, int radius);
  bool settle(Cell c, std::uint64_t& allowance) override;
  double settled(Cell c) const override;
  std::uint64_t expanded() const override { return expanded_; }
  bool complete() const override { return open_.empty(); }

 private:
  // The slot of `c` in distances_ (-1 outside the rows' spans): O(1), as the Dijkstra asks it
  // for every neighbour it relaxes.
  std::ptrdiff_t slot(Cell c) const {
    const int row = c.y - top_;
    if (row < 0 || row >= static_cast<int>(rowX0_.size())) return -1;
    const auto r = static_cast<std::size_t>(row);
    const int dx = c.x - rowX0_[r];
    if (dx < 0 || static_cast<std::uint32_t>(dx) >= rowBegin_[r + 1] - rowBegin_[r]) return -1;
    return static_cast<std::ptrdiff_t>(rowBegin_[r]) + dx;
  }

  // The corridor row by row: each row's span from its first to its last cell, a slot per cell
  // of the span in `distances_` (a path that turns back leaves gaps in a span: slots outside
  // the corridor, never reached).
  int top_ = 0;                          // first row of the corridor
  std::vector<int> rowX0_;               // per row from top_: first column of its span
  std::vector<std::uint32_t> rowBegin_;  // per row: first slot; one entry past the end
  std::vector<double> distances_;        // +inf until reached
  std::uint64_t expanded_ = 0;
  // The Dijkstra under way (from the goal's slot), dropped when done.
  std::vector<Cell> cellOf_;                   // per slot
  std::vector<std::uint8_t> moves_;            // per slot: the agent's moves there (moves.h)
  static constexpr std::uint8_t kOutside = 0;  // a gap in a row's span
  static constexpr std::uint8_t kOpen = 1;     // in the corridor, not settled yet
  static constexpr std::uint8_t kClosed = 2;   // settled
  std::vector<std::uint8_t> state_;            // per slot
  TwoCostOpenList open_;
};

// Which anchors without a 2s×2s square round their footprint have passing room all the same.
enum class Dents : std::uint8_t {
  // None: a notch in a ragged forest edge is a chokepoint like a door (replay formats up to 16).
  Narrow,
  // Dents: 8-connected sets of such anchors at most 2s + 1 across that traffic goes round close
  // by (their bordering anchors with room meet through anchors with room within 2s + 1 cells of
  // them): a notch in a ragged edge, a gap between a rock and a swamp. Units there block nobody.
  Open,
};

// One byte per cell: 1 where two agents of this kind could stand side by side around an
// anchor (some 2s×2s square of the capability's terrains contains its footprint, or it is in a
// dent: `dents`), 0 where they could not pass each other (a corridor, a door, a bridge narrower
// than two of them).
std::vector<std::uint8_t> passingRoom(const AnnotatedGrid& grid, Agent agent,
                                      Dents dents = Dents::Open);

// One byte per cell: 1 on every cell some footprint covers where an agent of one of these
// kinds stands without passing room — the chokepoints, where units must take turns. Open ground
// is 0: there local avoidance lets units slide past each other.
std::vector<std::uint8_t> contestedCells(const AnnotatedGrid& grid, std::span<const Agent> agents,
                                         Dents dents = Dents::Open);

// The anchor reaches `cell` at `tick` (and stays until the next entry's tick).
struct TimedCell {
  Cell cell;
  Tick tick = 0;
  bool operator==(const TimedCell&) const = default;
};

// While an agent moves from a to b over [t, t + d) it holds a until three quarters of the way
// and b from a quarter of the way: a follower may close up to half a move behind it, and two
// agents swapping cells always overlap (each enters the other's cell before the other left).
struct MoveSpan {
  Tick leaveBy;  // the end of the hold on a
  Tick enterAt;  // the start of the hold on b
};
constexpr MoveSpan moveSpan(Tick t, Tick d) {
  return {t + (3 * d + 3) / 4, t + d / 4};
}

// How an agent kept out of a passage (CooperativeRequest::keepOut) steps out of it.
enum class KeepOutExit : std::uint8_t {
  // A footprint is kept out by its highest level, then by how many of its cells have that
  // level, and each move must lower the pair: a footprint wider than a band of one level
  // (a large unit standing across the stream out of a passage) leaves it a row at a time. An
  // agent standing kept out does not wait there, even where it starts: it steps out, or its
  // plan is Blocked and it holds its place (a wait there would be planned again each window,
  // and it would never leave).
  Stepwise,
  // Before replay format 11: the highest level alone must fall, and the agent may wait at its
  // start however kept out it stands.
  HighestLevel,
};

struct CooperativeRequest {
  Agent agent;
  Cell start;
  Tick startTick = 0;
  Cell goal;
  std::uint32_t self = 0;  // the agent's owner id in the table: its own reservations are ignored
  // [Unit: ticks per cell] how long a cost-1 step takes onto a footprint whose centre cell
  // (anchor + size/2) has this terrain; a move of cost c takes max(1, ceil(c · ticksPerCell))
  // ticks. <= 0 or not finite: the terrain is not entered.
  std::array<double, kTraversableTerrainSlots> ticksPerCell{};
  // [Unit: ticks] [Limit: >= 0] what a move begun at rest (after a wait, or the first move
  // when `startsAtRest`) takes longer than one at speed: the time lost accelerating (v / 2a).
  Tick startTicks = 0;
  bool startsAtRest = false;
  Tick waitTicks = 8;    // [Unit: ticks] [Limit: >= 1] one wait move
  Tick window = 128;     // [Unit: ticks] [Limit: >= 1] plan at least this far past startTick
  Tick maxWindow = 512;  // [Unit: ticks] [Limit: >= window] where a window extended by
                         // `passing` ends regardless
  // [Unit: ticks] [Limit: >= 0] a window's last cell must stay free this long after it ends:
  // the agent stands there until it plans again.
  Tick holdTicks = 16;
  // passingRoom() of the agent kind, or null. When set, a window does not end (before
  // maxWindow) where there is no passing room, and nobody waits there (but at the start): a
  // unit commits to a whole corridor, door or bridge, or waits before it, so that two never
  // meet head-on inside one.
  const std::vector<std::uint8_t>* passing = nullptr;
  std::uint64_t expansionLimit = 20000;  // [Limit: >= 1] space-time nodes expanded
  // Per owner id, or null: 1 where the agent may overlap that owner's reservations (units
  // moving the same way, which queue behind one another on their own).
  const std::vector<std::uint8_t>* sharing = nullptr;
  // One byte per cell, or null: where the agent is kept out (a passage open to the other way
  // now, and its mouth), the level rising toward the passage. A footprint's keep-out is its
  // cells' highest level (and, by `keepOutExit`, how many cells have it); the agent moves onto a
  // kept-out footprint only from one kept out more (out of the passage and its mouth), waits
  // on one only as keepOutExit says, and a window does not end at one (before maxWindow).
  const std::vector<std::uint8_t>* keepOut = nullptr;
  KeepOutExit keepOutExit = KeepOutExit::Stepwise;
};

enum class CooperativeStatus : std::uint8_t {
  ReachedGoal,   // the window ends at the goal, which is free from then on
  Windowed,      // planned to the window's end
  Blocked,       // no safe window within the limits: `steps` is the longest safe prefix found
  InvalidStart,  // the agent cannot stand at the start
  InvalidGoal,   // … or at the goal
  Unreachable,   // the distance field says the goal cannot be reached from the start
  Pending,       // a sliced plan not finished yet (updatePlan it again)
};
inline constexpr EnumNames<CooperativeStatus, 7> kCooperativeStatusNames{{{
    {CooperativeStatus::ReachedGoal, "reached-goal"},
    {CooperativeStatus::Windowed, "windowed"},
    {CooperativeStatus::Blocked, "blocked"},
    {CooperativeStatus::InvalidStart, "invalid-start"},
    {CooperativeStatus::InvalidGoal, "invalid-goal"},
    {CooperativeStatus::Unreachable, "unreachable"},
    {CooperativeStatus::Pending, "pending"},
}}};

struct CooperativePlan {
  CooperativeStatus status = CooperativeStatus::Blocked;
  // From {start, startTick}; consecutive entries are one legal move or a wait on one cell;
  // ticks strictly increase. Empty for InvalidStart, InvalidGoal and Unreachable.
  std::vector<TimedCell> steps;
  SearchMetrics metrics;  // expanded: space-time nodes
  // Nodes the distance field expanded for this plan (the corridor's Dijkstra, RRA*'s resumed
  // search): work besides metrics.expanded, counted against a sliced plan's allowance.
  std::uint64_t fieldExpanded = 0;
};

// Empty when the request's [Limit]s hold, else the first that does not and why.
std::string problemWith(const CooperativeRequest& request);

// A* over (anchor cell, tick): the agent's 8 moves plus a wait. A move a→b from t lasting d is
// legal when the footprint at a is free of other owners over [t, leaveBy) and the one at b over
// [enterAt, t+d) (moveSpan); a wait
// when a's footprint is free over [t, t+waitTicks). The start is the exception: the agent stands
// there already (two bodies can round to one anchor), so while waiting there first (up to
// `window`) and leaving it, the owners that share the start at startTick are ignored. g is ticks
// since startTick, h the field's distance times the smallest ticksPerCell (admissible). The first
// state popped that is
//   (1) the goal, free from then on: ReachedGoal; or
//   (2) at or past startTick + window, free for holdTicks more, and with passing room and not
//       kept out (or past maxWindow): Windowed
// ends the search. Among equal times fewer moves win (a unit waits rather than shuffles); ties
// then go to the larger g, then to the state generated first.
class CooperativeSearch {
 public:
  explicit CooperativeSearch(const AnnotatedGrid& grid);

  // [Limit: problemWith(request) empty — otherwise InvalidStart with no steps]
  // beginPlan, one unbounded updatePlan and finalizePlan.
  CooperativePlan plan(const CooperativeRequest& request, DistanceField& field,
                       const ReservationTable& table);

  // The same plan sliced (as search.h's queries): beginPlan starts it (abandoning any
  // unfinished one) and answers at once what needs no search; updatePlan advances it by at most
  // `maxExpansions` expansions, the field's and the space-time search's together (so it never
  // spends more: a state is expanded only once the field knows every distance it needs);
  // finalizePlan gives what plan() returns for the same query (microseconds summing the calls'),
  // or Pending and no steps while unfinished. Both return Pending until the plan is done, then
  // its status. While it is unfinished the request's pointers, the field and the table must
  // stay alive; the table may change between updates (a resumed search reads it as it is: see
  // finalizePlanAt), and others may settle the field further (its distances stay the same), but
  // the grid may not change nor the field be replaced.
  CooperativeStatus beginPlan(const CooperativeRequest& request, DistanceField& field,
                              const ReservationTable& table);
  CooperativeStatus updatePlan(std::uint64_t maxExpansions);
  CooperativePlan finalizePlan() const;
  // The finished plan as begun at `startTick` (>= the request's) instead: the agent stood at
  // its start until then. Its ticks are shifted; a first move planned at speed (not
  // startsAtRest) takes startTicks longer, as the agent now starts it from rest; and the whole
  // is checked against the table as it is now, by the search's rules (each move's and wait's
  // footprints, the last cell's hold: holdTicks when Windowed, for good when ReachedGoal,
  // waitTicks when Blocked). A plan that is no longer free is dropped: Blocked with the start
  // alone, at startTick. The same as finalizePlan() when startTick is the request's.
  CooperativePlan finalizePlanAt(Tick startTick) const;
  // The plan's expansions so far, the field's included.
  std::uint64_t expandedSoFar() const { return plan_.metrics.expanded + plan_.fieldExpanded; }

  // Reserves what the search checked for a plan's steps, for `owner`: each move's two
  // footprints over their moveSpan, each wait's footprint over the wait, and the last cell over
  // [last tick, last tick + hold) (kForever: for good, e.g. a unit parked at its goal).
  static void reserve(ReservationTable& table, std::span<const TimedCell> steps, int size,
                      std::uint32_t owner, Tick hold);

 private:
  struct Node {
    std::uint32_t cell;
    Tick tick;
    std::int32_t parent;
    std::uint32_t moves;  // along the plan so far (waits excluded)
  };
  // The open list: a 4-ary min-heap on (f, then larger g, then the node generated first), a
  // strict order, so it pops what any priority queue on that order pops. Entries are two words
  // compared as unsigned integers: f's bits (f >= 0, and the bits of non-negative doubles sort
  // as the doubles) and (2^32 - 1 - g) << 32 | node. Half the levels of a binary heap and two
  // thirds of its entry size: the pops were a sixth of a window search (door_30v30).
  class OpenHeap {
   public:
    struct Entry {
      std::uint64_t f;
      std::uint64_t tie;
    };
    static Entry entry(double f, Tick g, std::uint32_t node);
    static std::uint32_t nodeOf(const Entry& e) { return static_cast<std::uint32_t>(e.tie); }
    bool empty() const { return heap_.empty(); }
    void clear() { heap_.clear(); }
    void push(Entry e);
    Entry pop();  // [Limit: !empty()]

   private:
    static bool before(const Entry& a, const Entry& b) {
      return a.f != b.f ? a.f < b.f : a.tie < b.tie;
    }
    std::vector<Entry> heap_;
  };
  // A move the agent's layer allows from a cell onto terrain it may enter.
  struct Move {
    Cell next;
    Tick ticks;  // at speed (startTicks not included)
  };
  enum class Phase : std::uint8_t { Idle, Start, Search, Done };

  // The moves from `here`; returns how many were written.
  std::size_t movesFrom(Cell here, std::array<Move, kDirectionCount>& out) const;
  // Settles `c` in the field within `allowance`, counting the field's expansions.
  bool settle(Cell c, std::uint64_t& allowance);
  void add(std::uint32_t cell, Tick tick, std::int32_t parent, double h);
  // Expands the node by `moves` (movesFrom(here), every distance they need settled) and a wait.
  void expand(std::int32_t index, Cell here, double h, int rank, std::span<const Move> moves);
  // Ends the search: the plan's steps from node `at` back to the start.
  void finish(CooperativeStatus status, std::int32_t at);
  bool startChain(std::int32_t at) const;
  // The agent's footprint at `c` is free of others' reservations over [from, to) (its own and
  // `sharing` owners' ignored); at the start, of those not in `startSharing` either.
  bool free(Cell c, Tick from, Tick to) const;
  bool freeAtStart(const std::vector<std::uint32_t>& startSharing, Tick from, Tick to) const;
  // 0 when the footprint at `anchor` is not kept out, else its rank by request_.keepOutExit:
  // a move onto a kept-out footprint must lower it.
  int keptOut(Cell anchor) const;
  // The plan's steps and its last cell's hold are free in the table as it is now.
  bool stillFree(const CooperativePlan& plan) const;

  const AnnotatedGrid& grid_;
  // The query under way.
  Phase phase_ = Phase::Idle;
  CooperativeRequest request_;
  DistanceField* field_ = nullptr;
  // The field was complete when last asked (it stays so): settle() skips it, as a window
  // search asks it for every move of every expansion.
  bool fieldComplete_ = false;
  const ReservationTable* table_ = nullptr;
  CooperativePlan plan_;
  double minTicks_ = 0.0;  // the least ticksPerCell: h in ticks per unit of distance
  // Per terrain slot, a move's ticks at speed: [0] cardinal, [1] diagonal; 0 where the request
  // does not enter the terrain. Worked out once a plan (movesFrom asks for each expansion).
  std::array<std::array<Tick, kTraversableTerrainSlots>, 2> moveTicks_{};
  std::span<const std::uint8_t> moveMasks_;  // the agent's layer's (AgentLayer::moveMasks)
  Tick windowEnd_ = 0;
  Tick hardEnd_ = 0;
  // Who shares the start with the agent at startTick (bodies are not cells: two can round to
  // one anchor): they do not stop it from staying there at first or leaving.
  std::vector<std::uint32_t> startSharing_;
  std::int32_t deepest_ = 0;  // the node reached latest: the longest safe prefix
  double deepestH_ = 0.0;
  std::int32_t current_ = -1;  // popped, waiting for its distances to be settled
  // Scratch, kept between queries.
  std::vector<Node> nodes_;
  OpenHeap open_;
  // The (cell, tick) states reached by the plan under way, as bits: a 512-bit block per cell
  // and 512 ticks, found by open addressing on (cell, tick / 512). A plan reaches thousands of
  // states on a few hundred cells, each at many ticks (waits), so the blocks stay in the first
  // cache level where a table of states spread them over hundreds of kilobytes: its probes were
  // a sixth of a window search (door_30v30).
  class SeenStates {
   public:
    void clear();
    bool insert(std::uint64_t key);  // (cell << 32 | tick offset); true when the key is new

   private:
    static constexpr int kTickBits = 9;  // 512 ticks a block
    static constexpr std::uint64_t kEmptySlot = ~std::uint64_t{0};
    static constexpr std::size_t kSmallSlots = 1024;
    struct Slot {
      std::uint64_t block = kEmptySlot;  // cell << 32 | tick offset >> kTickBits
      std::uint32_t bits = 0;            // its first word in bits_
    };
    static constexpr std::size_t kWords = (std::size_t{1} << kTickBits) / 64;
    std::size_t home(std::uint64_t block) const;
    // The slot holding `block`, else the empty slot where it goes.
    std::size_t slotOf(std::uint64_t block) const;
    void grow();
    std::vector<Slot> slots_;
    std::vector<std::uint32_t> used_;  // the slots holding a block
    std::vector<std::uint64_t> bits_;  // kWords per block, in the order the blocks came
  };
  SeenStates seen_;
};

}  // namespace warpath::pathing
