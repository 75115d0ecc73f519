// Cooperative movement (docs/cooperative.md): every moving unit reserves a window of space-time
// (its footprint over the ticks its moves take) and follows it; units that follow no plan hold
// their footprint. Windows are planned in a deterministic priority order within the tick's
// expansion budget, and cycles of units waiting on each other are broken.

#include <algorithm>
#include <cmath>

#include "engine/fnv1a.h"
#include "engine/src/world/phases.h"
#include "pathing/moves.h"

namespace warpath::engine::world {

using namespace pathing;

namespace {

// A unit this far [Unit: cells] from where its plan puts it has fallen off its plan.
constexpr double kOffSchedule = 1.0;
// How far ahead [Unit: s] a unit steers toward its schedule.
constexpr double kLookaheadSeconds = 0.3;

// Two units whose directions to their goals are within about 45° (cosine) go the same way.
constexpr double kSameWay = 0.7;
// [Unit: cells] Around a passage, those kept out of it stand back this far: the mouth is left
// to the stream coming out.
constexpr int kMouth = 2;
// [Unit: moves] The stream out of a passage: those kept out do not stand on the next moves of
// the paths of those let through, past the passage.
constexpr int kStream = 6;
// At most this many units are let through a passage and not past it yet: more crowd its mouth
// and crush the ones at its sides (at the 1-cell door, 12 or more left some unit there 9 s
// without progress; 3 to 6 starve the door).
constexpr std::uint32_t kInFlight = 8;
// [Unit: s] Once one kept out of a passage has waited this long, nobody new is let through the
// other way: the passage drains and turns.
constexpr double kGreenSeconds = 15.0;
// [Unit: s] A passage counts as used one way (updateGates) once its holder has held it this long:
// paths delivered over several ticks (the sliced service) make a two-way door look one-way for a
// moment at the start.
constexpr double kOneWaySettleSeconds = 2.0;

Cell cellAt(const GridMap& map, std::uint32_t index) {
  const auto width = static_cast<std::uint32_t>(map.width());
  return {static_cast<int>(index % width), static_cast<int>(index / width)};
}

bool sameWay(units::Vec2 a, units::Vec2 b) {
  return a.dot(b) > kSameWay;
}

std::uint32_t ownerOf(const Unit& unit) {
  return unit.id.index;
}

// Ticks one cardinal move takes at the unit's top speed: the unit of `window` and of waits.
Tick cardinalTicks(const Refs& w, const units::UnitType& type) {
  return std::max<Tick>(1, static_cast<Tick>(std::ceil(w.settings.tickRate / type.maxSpeed())));
}

bool following(const Unit& unit) {
  return unit.alive() && unit.state == UnitState::Moving && unit.path && !unit.engaged;
}

// Where a unit that follows no plan stands for the table: its goal cell once parked (steering
// brings it back there), else the nearest anchor its footprint fits.
Cell standingAnchor(const Refs& w, const Unit& unit) {
  if (unit.alive() && unit.state == UnitState::Parked) return unit.goalCell;
  if (!unit.alive()) return units::centreToAnchor(unit.position, w.typeOf(unit).size);
  return nearestStandable(w, unit);
}

bool hasBody(const Unit& unit) {
  return unit.alive() || unit.wreckUntilTick >= 0;
}

}  // namespace

}  // namespace warpath::engine::world

namespace warpath::engine {

TimedPlan timedPlan(std::vector<pathing::TimedCell> steps, pathing::CooperativeStatus status,
                    bool timed, bool cruising) {
  Fnv1a h;
  h.add(static_cast<std::uint64_t>(status));
  h.add(timed ? 1 : 0);
  for (const pathing::TimedCell& s : steps) {
    h.add(static_cast<std::uint64_t>(static_cast<std::uint32_t>(s.cell.x)) << 32 |
          static_cast<std::uint32_t>(s.cell.y));
    h.add(static_cast<std::uint64_t>(s.tick));
  }
  // Hashed only when set, so the digests of windows stay what they were.
  if (cruising) h.add(2);
  return {std::move(steps), status, timed, cruising, h.value()};
}

}  // namespace warpath::engine

namespace warpath::engine::world {

void releaseReservations(Refs& w, Unit& unit) {
  if (w.state.reservations) w.state.reservations->release(ownerOf(unit));
  unit.plan.reset();
  unit.held = {-1, -1};
  unit.heldSince = -1;
}

void standAt(Refs& w, Unit& unit, Cell anchor, std::int32_t gate, bool admitted, Tick gateSince) {
  TimedPlan stub = timedPlan({{anchor, w.state.tick}}, CooperativeStatus::Blocked, true);
  stub.gate = gate;
  stub.admitted = admitted;
  stub.gateSince = gateSince;
  releaseReservations(w, unit);
  CooperativeSearch::reserve(*w.state.reservations, stub.steps, w.typeOf(unit).size, ownerOf(unit),
                             kForever);
  unit.plan = std::make_shared<const TimedPlan>(std::move(stub));
}

void expireWindow(Refs& w, Unit& unit) {
  if (!unit.plan || unit.plan->gate < 0) {
    releaseReservations(w, unit);
    return;
  }
  standAt(w, unit, nearestStandable(w, unit), unit.plan->gate, unit.plan->admitted,
          unit.plan->gateSince);
}

bool waitingAt(const TimedPlan& plan, Tick tick) {
  const std::vector<TimedCell>& s = plan.steps;
  if (tick >= s.back().tick) return plan.status != CooperativeStatus::ReachedGoal;
  const std::span<const TimedCell> steps(s);
  const auto next = units::nextStep(steps, static_cast<double>(tick));
  if (next == steps.end()) return false;  // a plan of one step, not begun
  const TimedCell& from = *(next - 1);
  return tick >= from.tick && from.cell == next->cell;
}

Traffic::Traffic() = default;
Traffic::~Traffic() = default;

CooperativeRequest Traffic::requestFor(const Refs& w, const Unit& unit, Cell start) {
  const units::UnitType& type = w.typeOf(unit);
  const PathServiceSettings& settings = w.settings.pathing;
  CooperativeRequest r;
  r.agent = type.agent();
  r.start = start;
  r.startTick = w.state.tick;
  r.goal = unit.goalCell;
  r.self = ownerOf(unit);
  for (int slot = 0; slot < kTraversableTerrainSlots; ++slot) {
    const double speed = type.speedOn(static_cast<Terrain>(slot));
    r.ticksPerCell[static_cast<std::size_t>(slot)] = speed > 0.0 ? w.settings.tickRate / speed : 0;
  }
  const Tick step = cardinalTicks(w, type);
  // Reaching speed v at acceleration a from rest loses v / 2a against moving at speed.
  r.startTicks = static_cast<Tick>(
      std::ceil(w.settings.tickRate * type.maxSpeed() / (2.0 * type.acceleration)));
  r.startsAtRest = unit.velocity.length() < 0.5 * type.maxSpeed();
  r.waitTicks = std::max<Tick>(1, step / 2);
  r.window = step * settings.window;
  r.maxWindow = 4 * r.window;
  // The last cell is held until the next re-plan (due when half the window is left) and a
  // little longer, so a re-plan that waits a tick for the budget still finds it free.
  r.holdTicks = r.window / 2 + r.waitTicks;
  r.passing = &passingRoom(w, r.agent);
  r.keepOutExit = settings.keepOutExit;
  // A window searched whole within a tick is bounded by the tick's budget too; a sliced one
  // spreads over ticks instead.
  r.expansionLimit = sliced(w)
                         ? kWindowExpansionLimit
                         : std::min<std::uint64_t>(settings.expansionBudget, kWindowExpansionLimit);
  // Units heading the same way share reservations: they queue behind one another as in the
  // open, and the table arbitrates only between flows that meet head on or cross.
  // (Written without a branch: it runs for every window, over all units, and the branch on each
  // heading was mispredicted often.)
  sharing_.assign(w.state.units.size(), 0);
  const units::Vec2 mine = headings_[unit.id.index];
  const std::size_t others = std::min(sharing_.size(), headings_.size());
  const units::Vec2* const theirs = headings_.data();
  std::uint8_t* const shares = sharing_.data();
  for (std::size_t other = 0; other < others; ++other)
    shares[other] = sameWay(mine, theirs[other]) ? 1 : 0;
  if (unit.id.index < others) shares[unit.id.index] = 0;
  r.sharing = &sharing_;
  return r;
}

void Traffic::terrainChanged() {
  pending_.reset();  // its search read the old terrain (and its field goes)
  passing_.clear();
  lastPassing_ = nullptr;
  fields_.clear();
  lookahead_.clear();
}

const std::vector<std::uint8_t>& Traffic::passingRoom(const Refs& w, Agent agent) {
  // Units are asked about in id order, and a group's ids run together: the last field asked
  // for is nearly always the one asked for again.
  if (lastPassing_ != nullptr && lastPassingAgent_ == agent) return *lastPassing_;
  auto it = passing_.find(agent);
  if (it == passing_.end())
    it = passing_.emplace(agent, pathing::passingRoom(w.grid, agent, w.settings.pathing.dents()))
             .first;
  lastPassingAgent_ = agent;
  lastPassing_ = &it->second;
  return it->second;
}

DistanceField& Traffic::fieldFor(const Refs& w, const Unit& unit) {
  if (fields_.size() < w.state.units.size()) fields_.resize(w.state.units.size());
  Field& f = fields_[unit.id.index];
  // Distances belong to one spatial path (the corridor) or one goal (RRA*).
  if (!f.field || f.path != unit.path || f.goal != unit.goalCell) {
    const Agent agent = w.typeOf(unit).agent();
    const std::vector<Cell>& cells = unit.path->cells;
    if (w.settings.pathing.corridorSearch)
      f.field =
          std::make_unique<CorridorDistance>(w.grid, agent, cells, w.settings.pathing.corridor);
    else
      f.field =
          std::make_unique<ReverseResumableSearch>(w.grid, agent, unit.goalCell, cells.front());
    f.path = unit.path;
    f.goal = unit.goalCell;
  }
  return *f.field;
}

void Traffic::hold(Refs& w, Unit& unit) {
  if (!hasBody(unit)) {
    if (unit.held.x >= 0 || unit.plan) releaseReservations(w, unit);
    return;
  }
  const Cell anchor = standingAnchor(w, unit);
  if (!unit.plan && unit.held == anchor) return;
  releaseReservations(w, unit);
  w.state.reservations->reserve(anchor, w.typeOf(unit).size, w.state.tick, kForever, ownerOf(unit));
  unit.held = anchor;
  unit.heldSince = w.state.tick;
}

bool Traffic::chokepointAhead(const Refs& w, const Unit& unit) {
  // A window reaches `window` moves ahead and then on to the far side of a chokepoint, so a
  // unit needs one once a tracked cell is that near along its path (or under it now).
  const int size = w.typeOf(unit).size;
  const ReservationTable& table = *w.state.reservations;
  if (table.tracks(units::centreToAnchor(unit.position, size), size)) return true;
  // The path cells found untracked are remembered: a unit scans about a cell a tick.
  Lookahead& known = lookaheadOf(w, unit);
  const std::vector<Cell>& cells = unit.path->cells;
  const std::size_t from = placeOnPath(w, unit);
  const std::size_t reach = static_cast<std::size_t>(w.settings.pathing.window + size + 2);
  const std::size_t to = std::min(cells.size(), from + reach);
  for (std::size_t i = std::max(from, known.clearUntil); i < to; ++i) {
    if (table.tracks(cells[i], size)) {
      known.clearUntil = i;
      return true;
    }
  }
  known.clearUntil = std::max(known.clearUntil, to);
  return false;
}

Traffic::Lookahead& Traffic::lookaheadOf(const Refs& w, const Unit& unit) {
  if (lookahead_.size() < w.state.units.size()) lookahead_.resize(w.state.units.size());
  Lookahead& known = lookahead_[unit.id.index];
  const std::uint64_t tracks = w.state.reservations->trackChanges();
  if (known.path != unit.path || known.trackChanges != tracks) known = {unit.path, 0, tracks};
  return known;
}

bool Traffic::chokepointAheadNow(const Refs& w, const Unit& unit) {
  std::int8_t& known = chokepoint_[unit.id.index];
  if (known < 0) known = chokepointAhead(w, unit) ? 1 : 0;
  return known != 0;
}

void Traffic::cruise(Refs& w, Unit& unit) {
  if (unit.plan && unit.plan->cruising && unit.plan->gate < 0) return;
  releaseReservations(w, unit);
  unit.plan = std::make_shared<const TimedPlan>(timedPlan(
      {{nearestStandable(w, unit), w.state.tick}}, CooperativeStatus::Windowed, false, true));
}

std::int32_t Traffic::walksThroughOneWay(const Refs& w, const Unit& unit) {
  if (w.typeOf(unit).size > 1) return -1;
  const std::int32_t p = aheadOf(w, unit);
  if (p < 0) return -1;
  const Gate& gate = gates_[static_cast<std::size_t>(p)];
  return gate.oneWay && sameWay(headings_[unit.id.index], headings_[gate.holder]) ? p : -1;
}

void Traffic::cruiseThrough(Refs& w, Unit& unit, std::int32_t gate) {
  if (unit.plan && unit.plan->cruising && unit.plan->gate == gate) return;
  const Tick since = unit.plan && unit.plan->gate == gate && unit.plan->admitted
                         ? unit.plan->gateSince
                         : w.state.tick;
  releaseReservations(w, unit);
  TimedPlan plan = timedPlan({{nearestStandable(w, unit), w.state.tick}},
                             CooperativeStatus::Windowed, false, true);
  plan.gate = gate;
  plan.admitted = true;
  plan.gateSince = since;
  unit.plan = std::make_shared<const TimedPlan>(std::move(plan));
}

bool Traffic::needsWindow(const Refs& w, const Unit& unit) {
  if (!unit.plan || unit.plan->cruising) return true;
  const TimedPlan& plan = *unit.plan;
  // Kept out of a passage whose gate now lets it through: its turn has come.
  if (keptOut(plan) && static_cast<std::size_t>(plan.gate) < gates_.size() &&
      admits(plan.gate, unit))
    return true;
  const Tick now = w.state.tick;
  const Tick end = plan.steps.back().tick;
  const units::UnitType& type = w.typeOf(unit);
  switch (plan.status) {
    case CooperativeStatus::ReachedGoal:
      break;
    case CooperativeStatus::Windowed: {
      // Inside a passage a unit keeps the window that commits it to the far side (a new one
      // could lose its turn to whoever planned since), unless that window is nearly used up.
      const Tick step = cardinalTicks(w, type);
      const Tick left = end - now;
      const Tick inPassage = 2 * step;
      const Tick elsewhere = step * w.settings.pathing.window / 2;
      // Where the unit stands is looked up only when the answer depends on it.
      if (left <= std::min(inPassage, elsewhere)) return true;
      if (left > std::max(inPassage, elsewhere)) break;
      const Cell here = nearestStandable(w, unit);
      const bool narrow =
          w.map().contains(here) && passingRoom(w, type.agent())[w.map().indexOf(here)] == 0;
      if (left <= (narrow ? inPassage : elsewhere)) return true;
      break;
    }
    default:  // Blocked: try again once its safe prefix runs out
      if (now >= end) return true;
      break;
  }
  // One kept out of a passage but caught inside it with the holder backs out ahead of the holder:
  // a window that ended (at its goal, say) is planned again.
  if (now >= end && keptOut(plan) && backsOut(w, unit, plan.gate)) return true;
  // One kept out of a passage waits where it is pushed (steering.cpp), on its schedule or not.
  return plan.timed && !keptOut(plan) && !onSchedule(w, unit);
}

bool Traffic::sliced(const Refs& w) {
  return w.settings.pathing.sliced && w.settings.pathing.slicedWindows;
}

void Traffic::markKeepOut(const std::vector<std::pair<std::uint32_t, std::uint8_t>>& cells,
                          bool set) {
  for (const auto& [cell, level] : cells)
    keepOut_[cell] = set ? level : 0;
}

void Traffic::planWindow(Refs& w, Unit& unit, std::uint64_t& spent, std::uint64_t limit) {
  // The gate of the passage ahead: a unit let through keeps its turn from window to window;
  // one kept out plans around the passage and its mouth.
  const std::int32_t gate = aheadOf(w, unit);
  const Tick now = w.state.tick;
  bool admitted = false;
  Tick gateSince = now;
  if (gate >= 0) {
    const bool same = unit.plan && unit.plan->gate == gate;
    if (same && unit.plan->admitted) {
      admitted = true;
    } else {
      admitted = admits(gate, unit);
      Gate& g = gates_[static_cast<std::size_t>(gate)];
      if (admitted && g.holder == kNone) {
        g.holder = unit.id.index;
        g.holderSince = now;
      }
      if (admitted) ++g.inFlight;
    }
    if (same && unit.plan->admitted == admitted) gateSince = unit.plan->gateSince;
  }
  releaseReservations(w, unit);
  const Cell start = nearestStandable(w, unit);
  CooperativeRequest request = requestFor(w, unit, start);
  const bool keptOut = gate >= 0 && !admitted;
  // Kept out of the passage and its mouth, nor does it stand in the stream coming out.
  std::vector<std::pair<std::uint32_t, std::uint8_t>> closed;
  if (keptOut) {
    for (const std::uint32_t cell : streams_[static_cast<std::size_t>(gate)])
      closed.emplace_back(cell, 1);
    if (backsOut(w, unit, gate)) {
      appendBackingOutLevels(w, gate, closed);
    } else {
      const auto& passage = passages_[static_cast<std::size_t>(gate)].keepOut;
      closed.insert(closed.end(), passage.begin(), passage.end());
    }
    request.keepOut = &keepOut_;
  }
  DistanceField& field = fieldFor(w, unit);
  if (!search_) search_.emplace(w.grid);
  if (!sliced(w)) {
    markKeepOut(closed, true);
    CooperativePlan found = search_->plan(request, field, *w.state.reservations);
    markKeepOut(closed, false);
    spent += found.metrics.expanded;
    work_.expanded += found.metrics.expanded + found.fieldExpanded;
    commitWindow(w, unit, std::move(found), start, request, gate, admitted, gateSince);
    return;
  }
  // Sliced: what the request points to lives as long as the search. (Not emplace(): clang
  // decides whether the nested struct, with its member initializers, is default-constructible
  // while Traffic is still incomplete, and says no.)
  PendingWindow& p = pending_.emplace(PendingWindow{});
  p.unit = unit.id.index;
  p.path = unit.path;
  p.goal = unit.goalCell;
  p.start = start;
  p.gate = gate;
  p.admitted = admitted;
  p.gateSince = gateSince;
  p.sharing = sharing_;
  p.keepOut = std::move(closed);
  p.request = request;
  p.request.sharing = &p.sharing;
  p.status = search_->beginPlan(p.request, field, *w.state.reservations);
  resumeWindow(w, spent, limit);
}

bool Traffic::stillPending(const Refs& w) const {
  const Unit& unit = w.state.units[pending_->unit];
  return following(unit) && unit.path == pending_->path && unit.goalCell == pending_->goal;
}

void Traffic::resumeWindow(Refs& w, std::uint64_t& spent, std::uint64_t limit) {
  PendingWindow& p = *pending_;
  Unit& unit = w.state.units[p.unit];
  if (p.status == CooperativeStatus::Pending) {
    markKeepOut(p.keepOut, true);
    const std::uint64_t before = search_->expandedSoFar();
    p.status = search_->updatePlan(limit > spent ? limit - spent : 0);
    markKeepOut(p.keepOut, false);
    const std::uint64_t used = search_->expandedSoFar() - before;
    spent += used;
    work_.expanded += used;
  }
  if (p.status == CooperativeStatus::Pending) {
    // It stands at its start until its window comes, on a plan that says so (a wait that is no
    // jam, its place at a passage's gate kept) and holds the start for good meanwhile.
    standAt(w, unit, p.start, p.gate, p.admitted, p.gateSince);
    work_.paused = true;
    return;
  }
  // The plan starts now: the unit has stood at its start since the search began, and others
  // may have reserved in its way meanwhile (then it stands and plans again, first in order as
  // its wait ages it).
  CooperativePlan found = search_->finalizePlanAt(w.state.tick);
  const PendingWindow done = std::move(p);
  pending_.reset();
  commitWindow(w, unit, std::move(found), done.start, done.request, done.gate, done.admitted,
               done.gateSince);
}

void Traffic::commitWindow(Refs& w, Unit& unit, CooperativePlan found, Cell start,
                           const CooperativeRequest& request, std::int32_t gate, bool admitted,
                           Tick gateSince) {
  DistanceField& field = fieldFor(w, unit);
  const bool keptOut = gate >= 0 && !admitted;
  releaseReservations(w, unit);  // a sliced search's unit stood at its start meanwhile
  MovementStats& stats = w.state.movement;
  stats.expanded += found.metrics.expanded;
  ++stats.windows;
  const int size = w.typeOf(unit).size;
  switch (found.status) {
    case CooperativeStatus::InvalidStart:
    case CooperativeStatus::InvalidGoal:
    case CooperativeStatus::Unreachable:
    case CooperativeStatus::Pending:  // never: planWindow and resumeWindow commit done plans
      // Pushed out of its corridor (or its goal changed under it): a new spatial path.
      hold(w, unit);
      w.log(EventKind::Repath, unit, 1);
      requestPath(w, unit);
      unit.state = UnitState::WaitingPath;
      return;
    case CooperativeStatus::Blocked:
      ++stats.blockedWindows;
      if (found.steps.empty()) found.steps.push_back({start, w.state.tick});
      CooperativeSearch::reserve(*w.state.reservations, found.steps, size, ownerOf(unit),
                                 request.waitTicks);
      break;
    case CooperativeStatus::Windowed:
      CooperativeSearch::reserve(*w.state.reservations, found.steps, size, ownerOf(unit),
                                 request.holdTicks);
      break;
    case CooperativeStatus::ReachedGoal:
      CooperativeSearch::reserve(*w.state.reservations, found.steps, size, ownerOf(unit), kForever);
      break;
  }
  // Giving way: the window starts by moving away from the goal to let another unit by.
  const double here = field.distance(start);
  for (const TimedCell& step : found.steps) {
    if (step.cell == start) continue;
    if (field.distance(step.cell) > here + 1e-9) ++stats.giveWays;
    break;
  }
  // Timed when it waits or crosses a chokepoint; a blocked unit keeps to its (short) plan, and
  // one kept out of a passage to its window (its path runs through the passage). A vehicle in a
  // queue let through a passage nobody the other way waits for follows its path as a queue in
  // the open does: keeping to schedules there only made the vehicles jostle at its mouth
  // (narrow_pass). Alone it keeps to its window, which starts from where it stands.
  const Gate* held = gate >= 0 ? &gates_[static_cast<std::size_t>(gate)] : nullptr;
  const bool queueUnopposed =
      size >= 2 && admitted && held && held->keptOut == 0 && held->inFlight > 1;
  bool timed = found.status == CooperativeStatus::Blocked || keptOut;
  for (std::size_t i = 0; i < found.steps.size() && !timed; ++i) {
    timed = (i > 0 && found.steps[i].cell == found.steps[i - 1].cell) ||
            (!queueUnopposed && w.state.reservations->tracks(found.steps[i].cell, size));
  }
  TimedPlan plan = timedPlan(std::move(found.steps), found.status, timed);
  plan.gate = gate;
  plan.admitted = admitted;
  plan.gateSince = gate >= 0 ? gateSince : -1;
  unit.plan = std::make_shared<const TimedPlan>(std::move(plan));
}

void Traffic::findPassages(const Refs& w) {
  const ReservationTable& table = *w.state.reservations;
  if (passageTracks_ == table.trackChanges()) return;
  passageTracks_ = table.trackChanges();
  const GridMap& map = w.map();
  const auto cells = static_cast<std::size_t>(map.width()) * static_cast<std::size_t>(map.height());
  passageOf_.assign(cells, -1);
  passages_.clear();
  keepOut_.assign(cells, 0);
  backOutDistance_.assign(cells, -1);
  // Connected (8 ways) sets of tracked cells, by a flood from each unlabelled one in index order;
  // then each one's mouth, by rings of Chebyshev distance around it.
  std::vector<std::uint32_t> frontier;
  std::vector<std::int32_t> ring(cells, -1);  // per cell: the passage whose mouth reached it
  for (std::uint32_t seed = 0; seed < cells; ++seed) {
    const Cell c = cellAt(map, seed);
    if (passageOf_[seed] >= 0 || !table.tracks(c, 1)) continue;
    const auto id = static_cast<std::int32_t>(passages_.size());
    Passage& passage = passages_.emplace_back();
    frontier.assign(1, seed);
    passageOf_[seed] = id;
    for (std::size_t i = 0; i < frontier.size(); ++i) {
      const Cell at = cellAt(map, frontier[i]);
      for (const Direction& d : kDirections) {
        const Cell next{at.x + d.dx, at.y + d.dy};
        if (!map.contains(next) || passageOf_[map.indexOf(next)] >= 0 || !table.tracks(next, 1))
          continue;
        passageOf_[map.indexOf(next)] = id;
        frontier.push_back(map.indexOf(next));
      }
    }
    units::Vec2 sum{};
    for (const std::uint32_t cell : frontier) {
      passage.keepOut.emplace_back(cell, static_cast<std::uint8_t>(kMouth + 1));
      ring[cell] = id;
      const Cell at = cellAt(map, cell);
      sum = sum + units::Vec2{at.x + 0.5, at.y + 0.5};
    }
    passage.centre = sum * (1.0 / static_cast<double>(frontier.size()));
    for (std::size_t from = 0, level = kMouth; level > 0; --level) {
      const std::size_t to = passage.keepOut.size();
      for (std::size_t i = from; i < to; ++i) {
        const Cell at = cellAt(map, passage.keepOut[i].first);
        for (const Direction& d : kDirections) {
          const Cell next{at.x + d.dx, at.y + d.dy};
          if (!map.contains(next) || ring[map.indexOf(next)] == id) continue;
          ring[map.indexOf(next)] = id;
          passage.keepOut.emplace_back(map.indexOf(next), static_cast<std::uint8_t>(level));
        }
      }
      from = to;
    }
  }
  gates_.assign(passages_.size(), {});
}

std::int32_t Traffic::passageAt(const GridMap& map, const std::vector<std::uint8_t>& passing,
                                Cell anchor) const {
  if (!map.contains(anchor) || passing[map.indexOf(anchor)] != 0) return -1;
  return passageOf_[map.indexOf(anchor)];
}

std::int32_t Traffic::aheadOf(const Refs& w, const Unit& unit) {
  std::int32_t& known = ahead_[unit.id.index];
  // A passage is tracked: a unit with no tracked cell ahead has none (and chokepointAhead
  // remembers what it scanned).
  if (known == kUnknown) known = chokepointAheadNow(w, unit) ? passageAhead(w, unit) : -1;
  return known;
}

std::int32_t Traffic::passageAhead(const Refs& w, const Unit& unit) {
  const units::UnitType& type = w.typeOf(unit);
  const GridMap& map = w.map();
  const std::vector<std::uint8_t>& passing = passingRoom(w, type.agent());
  if (const std::int32_t here =
          passageAt(map, passing, units::centreToAnchor(unit.position, type.size));
      here >= 0)
    return here;
  // The scan along the path changes with its first waypoint only (the passages are found again
  // only when the tracked cells change, which begins the Lookahead anew).
  Lookahead& known = lookaheadOf(w, unit);
  const std::size_t from = placeOnPath(w, unit);
  if (known.passageFrom == from) return known.passage;
  const std::vector<Cell>& cells = unit.path->cells;
  const std::size_t reach = static_cast<std::size_t>(w.settings.pathing.window + type.size + 2);
  std::int32_t found = -1;
  for (std::size_t i = from; i < std::min(cells.size(), from + reach) && found < 0; ++i)
    found = passageAt(map, passing, cells[i]);
  known.passageFrom = from;
  known.passage = found;
  return found;
}

units::Vec2 Traffic::passageHeading(const Refs& w, const Unit& unit, std::int32_t p) {
  // From the path's cell before the passage to its cell after it, scanning two windows' worth
  // of path cells.
  const std::vector<std::uint8_t>& passing = passingRoom(w, w.typeOf(unit).agent());
  const std::vector<Cell>& cells = unit.path->cells;
  const std::size_t from = placeOnPath(w, unit);
  const std::size_t reach = static_cast<std::size_t>(2 * w.settings.pathing.window);
  std::size_t first = cells.size();
  std::size_t last = cells.size();
  for (std::size_t i = from; i < std::min(cells.size(), from + reach); ++i) {
    const bool inside = passageAt(w.map(), passing, cells[i]) == p;
    if (inside && first == cells.size()) first = i;
    if (inside) last = i;
    if (!inside && first != cells.size()) break;
  }
  if (first == cells.size()) return {};
  const Cell a = cells[first > 0 ? first - 1 : 0];
  const Cell b = cells[std::min(cells.size() - 1, last + 1)];
  return {static_cast<double>(b.x - a.x), static_cast<double>(b.y - a.y)};
}

void Traffic::updateGates(const Refs& w) {
  gates_.assign(passages_.size(), {});
  const Tick now = w.state.tick;
  const auto green = static_cast<Tick>(std::llround(kGreenSeconds * w.settings.tickRate));
  // Held by whoever was let through first and still has the passage ahead (or is in it).
  const auto gated = [&](const Unit& unit) {
    return following(unit) && unit.plan && unit.plan->gate >= 0 &&
           static_cast<std::size_t>(unit.plan->gate) < gates_.size() &&
           aheadOf(w, unit) == unit.plan->gate;
  };
  streams_.resize(gates_.size());
  for (std::vector<std::uint32_t>& stream : streams_)
    stream.clear();
  for (const Unit& unit : w.state.units) {
    if (!unit.plan || !unit.plan->admitted || !gated(unit)) continue;
    Gate& gate = gates_[static_cast<std::size_t>(unit.plan->gate)];
    if (gate.holder == kNone || unit.plan->gateSince < gate.holderSince) {
      gate.holder = unit.id.index;
      gate.holderSince = unit.plan->gateSince;
    }
    ++gate.inFlight;
    addStream(w, unit, streams_[static_cast<std::size_t>(unit.plan->gate)]);
  }
  for (const Unit& unit : w.state.units) {
    if (!unit.plan || unit.plan->admitted || !gated(unit)) continue;
    Gate& gate = gates_[static_cast<std::size_t>(unit.plan->gate)];
    ++gate.keptOut;
    if (gate.holder != kNone && now - unit.plan->gateSince > green &&
        !sameWay(headings_[unit.id.index], headings_[gate.holder]))
      gate.turning = true;
  }
  // A passage used one way only: its gate lets any number through (nobody waits to come the
  // other way; the limit crowded stress_2000's jeeps at a gap, those let through stuck among
  // those kept out), and walkers cross it without windows (plan). One way once its holder has
  // held it kOneWaySettleSeconds and nobody following a path through it goes the other way.
  if (!w.settings.pathing.oneWayPassages) return;
  const auto settle = static_cast<Tick>(std::llround(kOneWaySettleSeconds * w.settings.tickRate));
  for (Gate& gate : gates_)
    gate.oneWay = gate.holder != kNone && now - gate.holderSince >= settle;
  for (const Unit& unit : w.state.units) {
    if (!following(unit)) continue;
    const std::int32_t p = aheadOf(w, unit);
    if (p < 0) continue;
    Gate& gate = gates_[static_cast<std::size_t>(p)];
    if (gate.oneWay && !sameWay(headings_[unit.id.index], headings_[gate.holder]))
      gate.oneWay = false;
  }
}

void Traffic::addStream(const Refs& w, const Unit& unit, std::vector<std::uint32_t>& stream) {
  // The footprints along the unit's path from where it leaves the passage, kStream moves on.
  const units::UnitType& type = w.typeOf(unit);
  const GridMap& map = w.map();
  const std::vector<Cell>& cells = unit.path->cells;
  const std::size_t from = placeOnPath(w, unit);
  const std::size_t reach =
      static_cast<std::size_t>(w.settings.pathing.window + type.size + 2 + kStream);
  const std::vector<std::uint8_t>& passing = passingRoom(w, type.agent());
  int left = -1;  // moves since the passage, -1 before its end
  for (std::size_t i = from; i < std::min(cells.size(), from + reach) && left < kStream; ++i) {
    const Cell a = cells[i];
    if (passageAt(map, passing, a) == unit.plan->gate) {
      left = 0;
      continue;
    }
    if (left < 0) continue;
    ++left;
    for (int dy = 0; dy < type.size; ++dy) {
      for (int dx = 0; dx < type.size; ++dx) {
        const Cell c{a.x + dx, a.y + dy};
        if (map.contains(c)) stream.push_back(map.indexOf(c));
      }
    }
  }
}

void Traffic::letOutFromInside(Refs& w) {
  std::vector<Unit>& all = w.state.units;
  const Tick now = w.state.tick;
  for (Unit& unit : all) {
    if (!following(unit) || !unit.plan || unit.plan->admitted || unit.plan->gate < 0) continue;
    const std::int32_t p = unit.plan->gate;
    if (static_cast<std::size_t>(p) >= gates_.size() || aheadOf(w, unit) != p) continue;
    Gate& gate = gates_[static_cast<std::size_t>(p)];
    if (gate.holder == kNone || gate.inFlight != 1 || !insidePassage(w, unit, p)) continue;
    Unit& holder = all[gate.holder];
    if (sameWay(headings_[unit.id.index], headings_[holder.id.index]) ||
        insidePassage(w, holder, p))
      continue;
    // Each plans its next window under its new turn: the holder around the passage, its mouth
    // and the stream coming out, the unit out of it.
    standAt(w, holder, nearestStandable(w, holder), p, false, now);
    standAt(w, unit, nearestStandable(w, unit), p, true, now);
    gate.holder = unit.id.index;
    gate.holderSince = now;
    gate.turning = false;  // (keptOut and inFlight stay: one unit in, one out)
    std::vector<std::uint32_t>& stream = streams_[static_cast<std::size_t>(p)];
    stream.clear();
    addStream(w, unit, stream);
  }
}

bool Traffic::insidePassage(const Refs& w, const Unit& unit, std::int32_t p) {
  const units::UnitType& type = w.typeOf(unit);
  return passageAt(w.map(), passingRoom(w, type.agent()),
                   units::centreToAnchor(unit.position, type.size)) == p;
}

bool Traffic::backsOut(const Refs& w, const Unit& unit, std::int32_t p) {
  // Vehicles only: walkers in a one-wide corridor with a passing bay halfway backed out of it
  // all the way instead of pulling over (bay_3v3: 27 of seeds 1-200 failing against none).
  if (!w.settings.pathing.keptOutBacksOut || w.typeOf(unit).size < 2 || p < 0 ||
      static_cast<std::size_t>(p) >= gates_.size())
    return false;
  const std::uint32_t holder = gates_[static_cast<std::size_t>(p)].holder;
  if (holder == kNone || holder == unit.id.index) return false;
  const Unit& other = w.state.units[holder];
  return !sameWay(headings_[unit.id.index], headings_[holder]) && insidePassage(w, unit, p) &&
         insidePassage(w, other, p);
}

void Traffic::appendBackingOutLevels(const Refs& w, std::int32_t p,
                                     std::vector<std::pair<std::uint32_t, std::uint8_t>>& closed) {
  const GridMap& map = w.map();
  const auto& levels = passages_[static_cast<std::size_t>(p)].keepOut;
  // The passage's own cells are those at the top level (its mouth's rings lie below).
  std::vector<std::uint32_t>& order = backOutOrder_;
  order.clear();
  const Unit& holder = w.state.units[gates_[static_cast<std::size_t>(p)].holder];
  const int size = w.typeOf(holder).size;
  const Cell anchor = units::centreToAnchor(holder.position, size);
  for (const auto& [cell, level] : levels) {
    if (level != kMouth + 1) continue;
    const Cell at = cellAt(map, cell);
    if (at.x >= anchor.x && at.x < anchor.x + size && at.y >= anchor.y && at.y < anchor.y + size) {
      backOutDistance_[cell] = 0;
      order.push_back(cell);
    }
  }
  // Moves from the holder's footprint through the passage's cells, breadth first.
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Cell at = cellAt(map, order[i]);
    for (const Direction& d : kDirections) {
      const Cell next{at.x + d.dx, at.y + d.dy};
      if (!map.contains(next)) continue;
      const std::uint32_t index = map.indexOf(next);
      if (passageOf_[index] != p || backOutDistance_[index] >= 0) continue;
      backOutDistance_[index] = backOutDistance_[order[i]] + 1;
      order.push_back(index);
    }
  }
  // Breadth first, the last cell reached is the farthest.
  const int farthest = order.empty() ? 0 : backOutDistance_[order.back()];
  for (const auto& [cell, level] : levels) {
    if (level != kMouth + 1 || backOutDistance_[cell] < 0) {
      closed.emplace_back(cell, level);
      continue;
    }
    // Highest next to the holder, kMouth + 1 farthest from it; capped where a level must fit.
    const int rank = std::min(farthest - backOutDistance_[cell], 255 - (kMouth + 1));
    closed.emplace_back(cell, static_cast<std::uint8_t>(kMouth + 1 + rank));
  }
  for (const std::uint32_t cell : order)
    backOutDistance_[cell] = -1;
}

bool Traffic::admits(std::int32_t p, const Unit& unit) const {
  const Gate& gate = gates_[static_cast<std::size_t>(p)];
  return gate.holder == kNone || (!gate.turning && (gate.inFlight < kInFlight || gate.oneWay) &&
                                  sameWay(headings_[unit.id.index], headings_[gate.holder]));
}

std::optional<std::uint32_t> Traffic::waitsFor(Refs& w, const Unit& unit) {
  // The unit is waiting: whoever holds the cell it would step to next toward its goal.
  const units::UnitType& type = w.typeOf(unit);
  const Cell here = nearestStandable(w, unit);
  const GridMap& map = w.map();
  if (!map.contains(here)) return std::nullopt;
  DistanceField& field = fieldFor(w, unit);
  const std::uint8_t moves = w.grid.layer(type.agent()).moveMasks()[map.indexOf(here)];
  std::optional<Cell> best;
  double bestDistance = field.distance(here);
  for (int d = 0; d < kDirectionCount; ++d) {
    if ((moves & (1u << d)) == 0) continue;
    const Direction& dir = kDirections[static_cast<std::size_t>(d)];
    const Cell next{here.x + dir.dx, here.y + dir.dy};
    const double distance = field.distance(next);
    if (distance < bestDistance) {
      bestDistance = distance;
      best = next;
    }
  }
  if (!best) return std::nullopt;
  const Tick now = w.state.tick;
  return w.state.reservations->blocker(*best, type.size, now, now + 2 * cardinalTicks(w, type),
                                       ownerOf(unit));
}

void Traffic::breakDeadlocks(Refs& w, std::uint64_t& spent, std::uint64_t limit) {
  // Each waiting unit waits for at most one other: a cycle is found by walking from each unit
  // in id order, marking the walk with its start.
  std::vector<Unit>& all = w.state.units;
  const Tick now = w.state.tick;
  const auto patience = static_cast<Tick>(std::llround(w.settings.tickRate));
  waitFor_.assign(all.size(), kNone);
  for (Unit& unit : all) {
    if (!following(unit) || unit.waitSince < 0 || now - unit.waitSince < patience) continue;
    if (const std::optional<std::uint32_t> other = waitsFor(w, unit))
      waitFor_[unit.id.index] = *other;
  }
  // Waiting on a teammate parked in the way into their area (PathServiceSettings::parkedMoveOn):
  // that one moves on to this one's goal cell, beyond it, and this one takes its cell (it waits
  // on nobody now).
  if (w.settings.pathing.parkedMoveOn) {
    for (Unit& unit : all) {
      const std::uint32_t other = waitFor_[unit.id.index];
      if (other < all.size() && takeGoalOfParkedTeammate(w, unit, all[other]))
        waitFor_[unit.id.index] = kNone;
    }
  }
  walk_.assign(all.size(), kNone);
  for (std::uint32_t start = 0; start < all.size(); ++start) {
    std::uint32_t at = start;
    while (at != kNone && at < all.size() && walk_[at] == kNone) {
      walk_[at] = start;
      at = waitFor_[at];
    }
    if (at == kNone || at >= all.size() || walk_[at] != start) continue;
    // `at` lies on a cycle first reached from `start`: collect it.
    cycle_.clear();
    std::uint32_t member = at;
    do {
      cycle_.push_back(member);
      member = waitFor_[member];
    } while (member != at);
    // Every member drops what it holds; then they plan again in priority order, so the first
    // goes through and the others give way around its reservations.
    inPriorityOrder(w, cycle_);
    for (std::uint32_t m : cycle_)
      w.state.reservations->release(ownerOf(all[m]));
    for (std::uint32_t m : cycle_) {
      // Sliced, one window search at a time within the budget: the others hold their places
      // and plan when their turn comes.
      if (pending_ && pending_->unit == m) {
        // Its search goes on: it stands at its start again.
        standAt(w, all[m], pending_->start, pending_->gate, pending_->admitted,
                pending_->gateSince);
      } else if (sliced(w) && (pending_ || spent >= limit)) {
        releaseReservations(w, all[m]);  // hold() reserves again what the release dropped
        hold(w, all[m]);
      } else {
        planWindow(w, all[m], spent, limit);
      }
      planned_[m] = 1;
    }
    ++w.state.movement.deadlocksBroken;
  }
}

void Traffic::inPriorityOrder(const Refs& w, std::vector<std::uint32_t>& order) {
  // The priority rule: the unit that has waited longer this order goes first (so nobody waits
  // forever), then the lower id.
  const std::vector<Unit>& all = w.state.units;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (all[a].waitedTicks != all[b].waitedTicks) return all[a].waitedTicks > all[b].waitedTicks;
    return all[a].id.index < all[b].id.index;
  });
  if (!w.settings.pathing.nearestKeptOutFirst) return;
  // Then the places those kept out of one passage were given go to them nearest its centre first,
  // so that when its gate lets them through the crowd's front files in and nobody pushes
  // through it from behind. (A reordering of places, not a comparison mixed into the sort's:
  // that one would not be a strict weak order.)
  std::vector<KeptOutPlace>& kept = keptOutPlaces_;
  kept.clear();
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    const Unit& unit = all[order[i]];
    if (!unit.plan || !keptOut(*unit.plan) ||
        static_cast<std::size_t>(unit.plan->gate) >= passages_.size())
      continue;
    const units::Vec2 d =
        unit.position - passages_[static_cast<std::size_t>(unit.plan->gate)].centre;
    kept.push_back({unit.plan->gate, d.dot(d), i, order[i]});
  }
  // By passage; within one, its places stay in ascending order.
  std::stable_sort(kept.begin(), kept.end(),
                   [](const KeptOutPlace& a, const KeptOutPlace& b) { return a.gate < b.gate; });
  for (std::size_t from = 0, to = 0; from < kept.size(); from = to) {
    places_.clear();
    for (to = from; to < kept.size() && kept[to].gate == kept[from].gate; ++to)
      places_.push_back(kept[to].place);
    std::sort(kept.begin() + static_cast<std::ptrdiff_t>(from),
              kept.begin() + static_cast<std::ptrdiff_t>(to),
              [](const KeptOutPlace& a, const KeptOutPlace& b) {
                return a.distance != b.distance ? a.distance < b.distance : a.place < b.place;
              });
    for (std::size_t k = from; k < to; ++k)
      order[places_[k - from]] = kept[k].unit;
  }
}

Traffic::TickWork Traffic::plan(Refs& w, std::uint64_t budget) {
  work_ = {};
  if (!w.settings.pathing.cooperative) return work_;
  // A window search left pending goes on only for the window it began: same order, path and
  // goal (else the unit plans anew in priority order).
  if (pending_ && !stillPending(w)) pending_.reset();
  ReservationTable& table = *w.state.reservations;
  const Tick now = w.state.tick;
  table.forget(now);
  std::vector<Unit>& all = w.state.units;
  planned_.assign(all.size(), 0);
  candidates_.clear();
  // Each following unit's direction to its goal (zero when it follows nothing), for `sharing`
  // and the gates.
  headings_.assign(all.size(), {});
  for (const Unit& unit : all) {
    if (!following(unit)) continue;
    const units::Vec2 toGoal =
        units::anchorToCentre(unit.goalCell, w.typeOf(unit).size) - unit.position;
    const double length = toGoal.length();
    if (length > 1e-9) headings_[unit.id.index] = toGoal * (1.0 / length);
  }
  findPassages(w);
  ahead_.assign(all.size(), kUnknown);
  chokepoint_.assign(all.size(), -1);
  // A vehicle with a passage ahead goes the way its path crosses it: vehicles converging on a
  // pass from all sides of a wide field go through it the same way (narrow_pass). Infantry keep
  // their heading to the goal: at the door, crowds judged by the way through it pressed in
  // together.
  for (const Unit& unit : all) {
    if (!following(unit) || w.typeOf(unit).size < 2) continue;
    if (const std::int32_t p = aheadOf(w, unit); p >= 0) {
      const units::Vec2 through = passageHeading(w, unit, p);
      if (through.length() > 1e-9) headings_[unit.id.index] = through * (1.0 / through.length());
    }
  }
  updateGates(w);
  if (w.settings.pathing.insideGoesFirst) letOutFromInside(w);
  for (Unit& unit : all) {
    // Far from any chokepoint a unit needs no window: Box2D alone keeps it apart from others
    // there, as nothing is reserved in the open (docs/cooperative.md).
    if (following(unit) && (!unit.plan || !unit.plan->timed) && !chokepointAheadNow(w, unit)) {
      if (pending_ && pending_->unit == unit.id.index) pending_.reset();  // needs none now
      cruise(w, unit);
      unit.waitSince = -1;
      continue;
    }
    // Nor does a walker through a passage used one way only: a crowd of walkers presses
    // through a door as without cooperation (windows made some wait at its sides for good). It
    // counts as let through, so that whoever comes the other way is kept out until it has passed.
    if (const std::int32_t p = following(unit) ? walksThroughOneWay(w, unit) : -1; p >= 0) {
      if (pending_ && pending_->unit == unit.id.index) pending_.reset();
      cruiseThrough(w, unit, p);
      unit.waitSince = -1;
      continue;
    }
    // A unit without a window (waiting for a path, or for the budget) holds where it stands.
    if (!following(unit) || !unit.plan) hold(w, unit);
    if (!following(unit)) {
      unit.waitSince = -1;
      continue;
    }
    if (needsWindow(w, unit)) candidates_.push_back(unit.id.index);
  }
  std::uint64_t spent = 0;
  // Sliced, the searches stop at the budget, or at one batch when the spatial searches left
  // less; the one left pending goes first (its unit has waited longest).
  const bool slicing = sliced(w);
  const std::uint64_t limit = slicing ? std::max(budget, kWindowBatch) : budget;
  if (pending_) {
    planned_[pending_->unit] = 1;
    resumeWindow(w, spent, limit);
  }
  // Once a second (staggered by nothing: all at once, so a cycle is seen whole).
  const auto second = static_cast<Tick>(std::max(1.0, std::round(w.settings.tickRate)));
  if (now % second == 0) breakDeadlocks(w, spent, limit);
  inPriorityOrder(w, candidates_);
  bool first = true;
  for (std::uint32_t index : candidates_) {
    if (planned_[index] != 0 || !following(all[index])) continue;
    // The budget is what the spatial searches left; a tick always plans at least one window
    // (sliced: begins one while nothing is pending and the limit is not reached).
    if (slicing ? pending_ || spent >= limit : !first && spent >= budget) break;
    first = false;
    planWindow(w, all[index], spent, limit);
    planned_[index] = 1;
  }
  // A cruising unit that nears a chokepoint without a window stands until it gets one.
  for (std::uint32_t index : candidates_) {
    Unit& unit = all[index];
    if (planned_[index] == 0 && unit.plan && unit.plan->cruising) hold(w, unit);
  }
  // Waiting: counted when it begins, timed while it lasts (the priority ages with it).
  MovementStats& stats = w.state.movement;
  for (Unit& unit : all) {
    if (!following(unit) || !unit.plan) continue;
    if (unit.plan->timed && waitingAt(*unit.plan, now)) {
      if (unit.waitSince < 0) {
        unit.waitSince = now;
        ++stats.waits;
      }
      ++unit.waitedTicks;
      stats.maxWaitTicks = std::max(stats.maxWaitTicks, now - unit.waitSince);
    } else {
      unit.waitSince = -1;
    }
  }
  return work_;
}

units::ScheduleResult followSchedule(const Refs& w, const Unit& unit, double maxSpeed) {
  const units::UnitType& type = w.typeOf(unit);
  return units::followPlan(unit.plan->steps, w.state.tick, type.size, unit.position, maxSpeed,
                           w.settings.tickRate, kLookaheadSeconds);
}

bool onSchedule(const Refs& w, const Unit& unit) {
  if (!unit.plan) return false;
  const units::UnitType& type = w.typeOf(unit);
  const units::ScheduleResult r = followSchedule(w, unit, type.maxSpeed());
  return (r.scheduled - unit.position).length() <= kOffSchedule;
}

}  // namespace warpath::engine::world
