// The state hash covers every field of the simulation state: each description in
// engine/state_description.h names as many fields as its struct has (a field added to a struct
// and not to its description fails here), and changing any one field changes the hash.

#include "engine/state_description.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>

namespace warpath::engine {
namespace {

// Converts to any field type: T{AnyField{}, …} compiles for up to as many initialisers as the
// aggregate T has fields, and no more.
struct AnyField {
  template <class T>
  operator T() const;  // NOLINT(google-explicit-constructor): declared only, never called
};

template <class T, std::size_t... I>
constexpr bool initialisableWith(std::index_sequence<I...>) {
  return requires {
    T{(static_cast<void>(I), AnyField{})...};
  };
}

template <class T, std::size_t N = 0>
constexpr std::size_t fieldCount() {
  static_assert(std::is_aggregate_v<T>);
  if constexpr (N > 64) {
    return N;
  } else if constexpr (initialisableWith<T>(std::make_index_sequence<N + 1>{})) {
    return fieldCount<T, N + 1>();
  } else {
    return N;
  }
}

struct CountingVisitor {
  std::size_t fields = 0;
  template <class F>
  void operator()(const char*, const F&) {
    ++fields;
  }
  template <class F>
  void operator()(Since, const char*, const F&) {
    ++fields;
  }
};

template <class T>
std::size_t describedCount() {
  T value{};
  CountingVisitor v;
  describe(v, value);
  return v.fields;
}

template <class T>
void expectComplete(const char* name) {
  EXPECT_EQ(describedCount<T>(), fieldCount<T>())
      << name << ": its description in engine/state_description.h names " << describedCount<T>()
      << " fields, the struct has " << fieldCount<T>()
      << "; describe every field (the state hash is computed through the description)";
}

TEST(StateDescription, NamesEveryFieldOfEveryStateType) {
  expectComplete<pathing::Cell>("Cell");
  expectComplete<pathing::CellRect>("CellRect");
  expectComplete<pathing::Agent>("Agent");
  expectComplete<units::Vec2>("Vec2");
  expectComplete<units::ProgressMonitor>("ProgressMonitor");
  expectComplete<UnitId>("UnitId");
  expectComplete<BodyId>("BodyId");
  expectComplete<PlannedPath>("PlannedPath");
  expectComplete<CombatStats>("CombatStats");
  expectComplete<Unit>("Unit");
  expectComplete<Shot>("Shot");
  expectComplete<Command>("Command");
  expectComplete<PathRequest>("PathRequest");
  expectComplete<Detour>("Detour");
  expectComplete<TerrainEdit>("TerrainEdit");
  expectComplete<TerrainLog>("TerrainLog");
  expectComplete<WorldState>("WorldState");
  expectComplete<RunState>("RunState");
}

// The counting itself: a struct with one more field than its description is caught.
struct Widened {
  int a = 0;
  double b = 0.0;
  std::vector<int> c;
  units::Vec2 d;
};
using engine::describe;  // the overload below must not hide the library's
template <class V>
void describe(V& v, const Widened& w) {
  v("a", w.a);
  v("b", w.b);
  v("c", w.c);  // d left out on purpose
}

TEST(StateDescription, ACountThatMissesAFieldIsCaught) {
  static_assert(fieldCount<Widened>() == 4);
  EXPECT_NE(describedCount<Widened>(), fieldCount<Widened>());
}

// Changes field number `target` (0-based, top level) of a described value in a way that the
// hash must see; counts the fields it passed.
struct Perturber {
  std::size_t target = 0;
  std::size_t seen = 0;
  bool changed = false;

  template <class F>
  void operator()(const char*, const F& field) {
    if (seen++ == target) changed = change(const_cast<F&>(field));
  }
  template <class F>
  void operator()(Since, const char* name, const F& field) {
    (*this)(name, field);
  }

  template <class F>
  static bool change(F& f) {
    if constexpr (std::is_same_v<F, bool>) {
      f = !f;
    } else if constexpr (std::is_enum_v<F>) {
      f = static_cast<F>(static_cast<std::underlying_type_t<F>>(f) + 1);
    } else if constexpr (std::is_arithmetic_v<F>) {
      f = static_cast<F>(f + 1);
    } else if constexpr (std::is_same_v<F, pathing::SplitMix64>) {
      f.next();
    } else if constexpr (std::is_same_v<F, GoalBoard>) {
      f = GoalBoard(pathing::GridMap(2, 2));
      f.take(GoalLayer::Parked, {1, 1}, 1, UnitId{0, 0});
    } else if constexpr (std::is_same_v<F, SharedPath>) {
      f = std::make_shared<const PlannedPath>(planned({{1, 2}}));
    } else if constexpr (std::is_same_v<F, SharedPlan>) {
      f = std::make_shared<const TimedPlan>(
          timedPlan({{{1, 2}, 3}}, pathing::CooperativeStatus::Windowed, true));
    } else if constexpr (std::is_same_v<F, DetourIfAny>) {  // refers to the request's field
      const_cast<std::shared_ptr<const Detour>&>(f.detour) = std::make_shared<const Detour>();
    } else if constexpr (requires { f.push_back({}); }) {
      f.push_back({});
    } else if constexpr (requires { f.get(); }) {
      return false;  // owned subsystems (Physics, PathService): covered by their descriptions
    } else {
      Perturber inner;  // a described struct: change its first field
      describe(inner, f);
      return inner.changed;
    }
    return true;
  }
};

template <class T, class Hash>
void expectEveryFieldChangesTheHash(const char* name, Hash hash, std::size_t unchangeable = 0) {
  const T original{};
  const std::uint64_t base = hash(original);
  std::size_t skipped = 0;
  for (std::size_t k = 0; k < fieldCount<T>(); ++k) {
    T copy{};  // equal to `original`: WorldState cannot be copied
    Perturber p{k};
    describe(p, copy);
    if (!p.changed) {
      ++skipped;
      continue;
    }
    EXPECT_NE(hash(copy), base) << name << ": field " << k << " does not reach the hash";
  }
  EXPECT_EQ(skipped, unchangeable) << name;
}

template <class T>
std::uint64_t hashOf(const T& value) {
  StateHasher h;
  describe(h, value);
  return h.value();
}

TEST(StateDescription, EveryFieldReachesTheHash) {
  expectEveryFieldChangesTheHash<Unit>("Unit", hashOf<Unit>);
  expectEveryFieldChangesTheHash<Shot>("Shot", hashOf<Shot>);
  expectEveryFieldChangesTheHash<Command>("Command", hashOf<Command>);
  expectEveryFieldChangesTheHash<PathRequest>("PathRequest", hashOf<PathRequest>);
  expectEveryFieldChangesTheHash<Detour>("Detour", hashOf<Detour>);
  expectEveryFieldChangesTheHash<RunState>("RunState", hashOf<RunState>);
  expectEveryFieldChangesTheHash<TerrainEdit>("TerrainEdit", hashOf<TerrainEdit>);
  expectEveryFieldChangesTheHash<TerrainLog>("TerrainLog", hashOf<TerrainLog>);
  // Physics and the path service are owned through pointers: their own fields are described.
  expectEveryFieldChangesTheHash<WorldState>(
      "WorldState", [](const WorldState& s) { return hashState(s); }, 3);
}

TEST(StateDescription, OlderFormatsLeaveOutTheFieldsAddedSince) {
  // A replay of format 3 recorded hashes without cooperative movement's fields: they must not
  // reach its hash, and the fields it had must.
  Unit a;
  Unit b;
  b.waitedTicks = 5;
  b.plannedTicks = 7;
  const auto format3 = [](const Unit& u) {
    StateHasher h(3);
    describe(h, u);
    return h.value();
  };
  EXPECT_EQ(format3(a), format3(b));
  EXPECT_NE(hashOf(a), hashOf(b));
  b.hp = 1;
  EXPECT_NE(format3(a), format3(b));
}

TEST(StateDescription, Format5LeavesOutTheTerrainChanges) {
  // Replays of format 5 recorded hashes before terrain changes: the terrain log and the wrecks'
  // obstacles reach format 6's hash only.
  WorldState a;
  WorldState b;
  b.terrain.applied = 1;
  b.terrain.digest = 42;
  EXPECT_EQ(hashState(a, 5), hashState(b, 5));
  EXPECT_NE(hashState(a), hashState(b));
  Unit u;
  Unit wreck;
  wreck.wreckArea = {1, 2, 2, 2};
  const auto format5 = [](const Unit& x) {
    StateHasher h(5);
    describe(h, x);
    return h.value();
  };
  EXPECT_EQ(format5(u), format5(wreck));
  EXPECT_NE(hashOf(u), hashOf(wreck));
}

TEST(StateDescription, PositionsAreQuantisedTo1Over1024Cell) {
  Unit a;
  Unit b;
  b.position.x = 1e-5;  // float noise
  EXPECT_EQ(hashOf(a), hashOf(b));
  b.position.x = 1.0 / 512.0;
  EXPECT_NE(hashOf(a), hashOf(b));
}

}  // namespace
}  // namespace warpath::engine
