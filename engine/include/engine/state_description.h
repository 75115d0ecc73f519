#pragma once
// One description per type of the simulation state: describe(v, x) calls v(name, field) for
// every field of x, in declaration order. The state hash walks these descriptions (so it covers
// every field), and tests/engine/state_description_test.cpp checks that each description names
// as many fields as its struct has: a field added to a struct and not here fails that test.
// Types with private state (GoalBoard, SplitMix64, Physics, PathService)
// describe what they expose for it.

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "engine/scenario_run.h"
#include "engine/world.h"

namespace warpath::engine {

// The layout of the state that replays of format N recorded hashes of: fields added later are
// described with Since{N}, and a hasher for an older format leaves them out, so that replays
// recorded before a field existed still verify.
struct Since {
  std::uint32_t format;
};
// The newest layout (format 7 kept 6's, format 9 kept 8's).
inline constexpr std::uint32_t kStateFormat = 8;

template <class V>
void describe(V& v, const pathing::Cell& c) {
  v("x", c.x);
  v("y", c.y);
}
template <class V>
void describe(V& v, const pathing::CellRect& r) {
  v("x", r.x);
  v("y", r.y);
  v("width", r.width);
  v("height", r.height);
}
template <class V>
void describe(V& v, const pathing::Agent& a) {
  v("size", a.size);
  v("capability", a.capability.mask());
}
template <class V>
void describe(V& v, const units::Vec2& p) {
  v("x", p.x);
  v("y", p.y);
}
template <class V>
void describe(V& v, const UnitId& id) {
  v("index", id.index);
  v("generation", id.generation);
}
template <class V>
void describe(V& v, const BodyId& id) {
  v("index", id.index);
}
template <class V>
void describe(V& v, const units::ProgressMonitor& m) {
  v("origin", m.origin);
  v("originTick", m.originTick);
  v("stuckInARow", m.stuckInARow);
  v(Since{4}, "originRemaining", m.originRemaining);
}
template <class V>
void describe(V& v, const pathing::SplitMix64& rng) {
  v("state", rng.state());
}
template <class V>
void describe(V& v, const GoalBoard& board) {
  v("digest", board.digest());
}
template <class V>
void describe(V& v, const PlannedPath& p) {
  v("cells", p.cells.size());                    // the cells themselves through their digest
  v(Since{4}, "remaining", p.remaining.size());  // a function of the cells
  v("digest", p.digest);
}
template <class V>
void describe(V& v, const pathing::TimedCell& c) {
  v("cell", c.cell);
  v("tick", c.tick);
}
template <class V>
void describe(V& v, const TimedPlan& p) {
  v("steps", p.steps.size());  // the steps themselves through their digest
  v("status", p.status);
  v("timed", p.timed);
  v("cruising", p.cruising);
  v("digest", p.digest);
  v("gate", p.gate);
  v("admitted", p.admitted);
  v("gateSince", p.gateSince);
}
template <class V>
void describe(V& v, const MovementStats& m) {
  v("windows", m.windows);
  v("blockedWindows", m.blockedWindows);
  v("waits", m.waits);
  v("giveWays", m.giveWays);
  v("deadlocksBroken", m.deadlocksBroken);
  v("maxWaitTicks", m.maxWaitTicks);
  v("expanded", m.expanded);
}
// What each owner holds follows from its unit's plan and held footprint (both described); the
// count of intervals stored covers what forget() has dropped.
template <class V>
void describe(V& v, const pathing::ReservationTable& table) {
  v("intervals", table.intervalCount());
}
template <class V>
void describe(V& v, const CombatStats& c) {
  v("shotsFired", c.shotsFired);
  v("hits", c.hits);
  v("damageDealt", c.damageDealt);
  v("damageTaken", c.damageTaken);
  v("kills", c.kills);
}
template <class V>
void describe(V& v, const Unit& u) {
  v("id", u.id);
  v("type", u.type);
  v("team", u.team);
  v("group", u.group);
  v("hp", u.hp);
  v("body", u.body);
  v("position", u.position);
  v("velocity", u.velocity);
  v("state", u.state);
  v("goalArea", u.goalArea);
  v("goalCell", u.goalCell);
  v("orderTick", u.orderTick);
  v("arrivalTick", u.arrivalTick);
  v("pathSerial", u.pathSerial);
  v("path", u.path);
  v("next", u.next);
  v("progress", u.progress);
  v("everStuck", u.everStuck);
  v("repaths", u.repaths);
  v(Since{4}, "plan", u.plan);
  v(Since{4}, "held", u.held);
  v(Since{4}, "heldSince", u.heldSince);
  v(Since{4}, "waitSince", u.waitSince);
  v(Since{4}, "waitedTicks", u.waitedTicks);
  v(Since{4}, "plannedTicks", u.plannedTicks);
  v("order", u.order);
  v("attackTargets", u.attackTargets);
  v("target", u.target);
  v("readyTick", u.readyTick);
  v("engaged", u.engaged);
  v("deathTick", u.deathTick);
  v("wreckUntilTick", u.wreckUntilTick);
  v("killedBy", u.killedBy);
  v("combat", u.combat);
  v(Since{6}, "wreckArea", u.wreckArea);
}
template <class V>
void describe(V& v, const Shot& s) {
  v("shooter", s.shooter);
  v("target", s.target);
  v("damage", s.damage);
  v("firedTick", s.firedTick);
  v("landTick", s.landTick);
  v("from", s.from);
  v("to", s.to);
}
template <class V>
void describe(V& v, const Command& c) {
  v("kind", c.kind);
  v("units", c.units);
  v("area", c.area);
  v("targets", c.targets);
}
template <class V>
void describe(V& v, const Detour& d) {
  v("avoid", d.avoid);
  v("region", d.region);
  v("rest", d.rest);
  v("rejoin", d.rejoin);
}
// A request's detour when it has one, and nothing at all when it has none: requests without
// one hash as they did before detours (replay format 13) existed.
struct DetourIfAny {
  const std::shared_ptr<const Detour>& detour;
};
template <class V>
void describe(V& v, const DetourIfAny& d) {
  if (d.detour) v("detour", *d.detour);
}
template <class V>
void describe(V& v, const PathRequest& r) {
  v("unit", r.unit);
  v("serial", r.serial);
  v("agent", r.agent);
  v("start", r.start);
  v("goal", r.goal);
  v(Since{5}, "costProfile", r.costProfile);
  v(Since{8}, "speed", r.speed);
  v("detour", DetourIfAny{r.detour});
}
// Box2D's own state (contacts, warm starts) is not reachable; the bodies' positions and
// velocities are, through the units they move (read back every step), and so is the count.
template <class V>
void describe(V& v, const Physics& physics) {
  v("bodies", physics.stats().bodies);
}
// The queue decides future answers; the answer cache does not (a cached answer equals a fresh
// search), and its hits are counted in the metrics. The bookings of congestion-aware routes
// (engine/congestion.h) follow from the paths delivered, dated by tick, and are left out like
// the cache; the searches they caused are counted. Wall-clock metrics are left out.
template <class V>
void describe(V& v, const PathService& paths) {
  v("queue", paths.queue());
  const PathServiceMetrics& m = paths.metrics();
  v("requests", m.requests);
  v("cacheHits", m.cacheHits);
  v("searches", m.searches);
  v("found", m.found);
  v("failed", m.failed);
  v("expanded", m.expanded);
  v("maxQueue", m.maxQueue);
  v(Since{8}, "congestedSearches", m.congestedSearches);
  // Sliced searches carry a search across ticks: its progress decides when answers come. Only
  // then: runs without them hash as they always have.
  if (paths.settings().sliced) v("slicedExpanded", paths.slicedExpanded());
}
template <class V>
void describe(V& v, const TerrainEdit& e) {
  v("kind", e.kind);
  v("area", e.area);
  v("terrain", e.terrain);
}
// The terrain is the map with the changes applied: their digest stands for it.
template <class V>
void describe(V& v, const TerrainLog& t) {
  v("pending", t.pending);
  v("applied", t.applied);
  v("digest", t.digest);
}
template <class V>
void describe(V& v, const WorldState& s) {
  v("tick", s.tick);
  v("rng", s.rng);
  v("units", s.units);
  v("pending", s.pending);
  v("inFlight", s.inFlight);
  v("lastTickShots", s.lastTickShots);
  v("goals", s.goals);
  v("physics", s.physics);
  v("paths", s.paths);
  v(Since{4}, "reservations", s.reservations);
  v(Since{4}, "movement", s.movement);
  v(Since{6}, "terrain", s.terrain);
}
template <class V>
void describe(V& v, const RunState& s) {
  v("members", s.members);
  v("spawned", s.spawned);
  v("ended", s.ended);
  v("winner", s.winner);
  v("endTick", s.endTick);
  v("exited", s.exited);
  v("exitedCount", s.exitedCount);
  v("holdSince", s.holdSince);
}

// A 64-bit hash over a described value, one multiply-rotate round per word (as xxHash64's
// rounds): integers and enums exactly, doubles quantised to 1/1024 (so float noise below that
// is ignored), containers by size then elements, pointers by presence then what they point to.
class StateHasher {
 public:
  // Hashes the state as format `format` laid it out (fields Since a later format are left out).
  explicit StateHasher(std::uint32_t format = kStateFormat) : format_(format) {}
  template <class T>
  void operator()(const char* /*name*/, const T& value) {
    add(value);
  }
  template <class T>
  void operator()(Since since, const char* /*name*/, const T& value) {
    if (format_ >= since.format) add(value);
  }
  std::uint64_t value() const { return hash_; }

  void addWord(std::uint64_t v) {
    constexpr std::uint64_t kPrime1 = 0x9E3779B185EBCA87ull;
    constexpr std::uint64_t kPrime2 = 0xC2B2AE3D27D4EB4Full;
    hash_ ^= v * kPrime2;
    hash_ = ((hash_ << 31) | (hash_ >> 33)) * kPrime1;
  }

 private:
  template <class T>
  void add(const T& value) {
    if constexpr (std::is_same_v<T, double>) {
      addWord(static_cast<std::uint64_t>(std::llround(value * 1024.0)));
    } else if constexpr (std::is_enum_v<T>) {
      addWord(static_cast<std::uint64_t>(value));
    } else if constexpr (std::is_integral_v<T>) {
      addWord(static_cast<std::uint64_t>(value));
    } else if constexpr (requires {
                           value.get();
                           *value;
                         }) {  // smart pointers
      if (value) {
        addWord(1);
        add(*value);
      } else {
        addWord(0);
      }
    } else if constexpr (requires {
                           value.size();
                           value.begin();
                         }) {  // containers
      addWord(static_cast<std::uint64_t>(value.size()));
      for (const auto& element : value)
        add(element);
    } else {
      describe(*this, value);
    }
  }

  std::uint32_t format_;
  std::uint64_t hash_ = 0xCBF29CE484222325ull;
};

inline std::uint64_t hashState(const WorldState& state, std::uint32_t format = kStateFormat) {
  StateHasher h(format);
  describe(h, state);
  return h.value();
}

}  // namespace warpath::engine
