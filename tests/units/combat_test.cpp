// Combat rules: damage and armour arithmetic, line of sight, target choice and two duels whose
// outcome is worked out by hand.

#include "units/combat.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "support/enum_round_trip.h"

namespace warpath::units {
namespace {

using pathing::Cell;
using pathing::GridMap;
using pathing::Terrain;

Weapon weaponOf(const char* type) {
  return defaultWeaponFor(type).value();
}
ArmourClass armourOf(const char* type) {
  return defaultArmourFor(type).value();
}

Combatant unit(std::uint32_t id, int team, ArmourClass armour, int size, Vec2 centre,
               int hp = 100) {
  return {id, team, armour, size, centre, hp};
}

// ---- damage and armour --------------------------------------------------------------------

TEST(Damage, FloorOfPercentWithAScratchOfOne) {
  EXPECT_EQ(damageDealt(150, 150), 225);
  EXPECT_EQ(damageDealt(8, 125), 10);
  EXPECT_EQ(damageDealt(8, 35), 2);   // 2.8 floors to 2
  EXPECT_EQ(damageDealt(10, 5), 1);   // 0.5 would floor to 0: a hit always scratches
  EXPECT_EQ(damageDealt(10, 0), 0);   // immune
  EXPECT_EQ(damageDealt(0, 100), 0);  // a weapon without damage
  EXPECT_EQ(damageDealt(2'000'000'000, 150), 2'147'483'647);  // clamped, no overflow
}

TEST(Damage, HitPointsNeverGoBelowZero) {
  EXPECT_EQ(applyDamage(100, 30), 70);
  EXPECT_EQ(applyDamage(30, 30), 0);
  EXPECT_EQ(applyDamage(10, 225), 0);
}

TEST(Damage, DefaultTableMatchesTheRolesOfTheUnits) {
  const ArmourTable table = defaultArmourTable();
  const auto dealt = [&](const char* shooter, const char* target) {
    return damageDealt(weaponOf(shooter), armourOf(target), table);
  };
  // Rifles hurt infantry and barely scratch tanks.
  EXPECT_EQ(dealt("infantry", "infantry"), 10);
  EXPECT_EQ(dealt("infantry", "tank"), 1);
  // The tank gun is deadly to vehicles, much less so to infantry.
  EXPECT_EQ(dealt("tank", "jeep"), 225);
  EXPECT_EQ(dealt("tank", "tank"), 150);
  EXPECT_EQ(dealt("tank", "amphibious"), 187);  // 150 · 1.25 = 187.5
  EXPECT_EQ(dealt("tank", "infantry"), 60);
  // The jeep's machine gun is best against infantry.
  EXPECT_EQ(dealt("jeep", "infantry"), 10);
  EXPECT_EQ(dealt("jeep", "jeep"), 4);  // 4.8
  EXPECT_EQ(dealt("jeep", "tank"), 1);
  // The amphibious gun is light: a tank shrugs it off.
  EXPECT_EQ(dealt("amphibious", "infantry"), 12);
  EXPECT_EQ(dealt("amphibious", "tank"), 1);

  // Per second, the machine gun out-damages the rifle against infantry.
  const double mgPerSecond = dealt("jeep", "infantry") / weaponOf("jeep").cooldown;
  const double riflePerSecond = dealt("infantry", "infantry") / weaponOf("infantry").cooldown;
  EXPECT_GT(mgPerSecond, 3 * riflePerSecond);
  // The tank gun is the slowest weapon.
  for (const char* t : {"infantry", "jeep", "amphibious"})
    EXPECT_GT(weaponOf("tank").cooldown, weaponOf(t).cooldown) << t;
}

TEST(Damage, DefaultsForEveryCatalogueTypeAndNoOther) {
  for (const char* t : {"infantry", "jeep", "tank", "amphibious"}) {
    ASSERT_TRUE(defaultWeaponFor(t)) << t;
    ASSERT_TRUE(defaultArmourFor(t)) << t;
    EXPECT_EQ(problemWith(*defaultWeaponFor(t)), "") << t;
  }
  EXPECT_FALSE(defaultWeaponFor("zeppelin"));
  EXPECT_FALSE(defaultArmourFor("zeppelin"));
}

TEST(Damage, NamesRoundTrip) {
  for (int i = 0; i < kArmourClasses; ++i) {
    const auto a = static_cast<ArmourClass>(i);
    EXPECT_EQ(armourClassFromName(armourClassName(a)), a);
  }
  for (int i = 0; i < kDamageKinds; ++i) {
    const auto k = static_cast<DamageKind>(i);
    EXPECT_EQ(damageKindFromName(damageKindName(k)), k);
  }
  EXPECT_EQ(armourClassName(ArmourClass::Heavy), "heavy");
  EXPECT_EQ(damageKindName(DamageKind::MachineGun), "machine_gun");
  EXPECT_FALSE(armourClassFromName("Heavy"));
  EXPECT_FALSE(damageKindFromName("laser"));
  EXPECT_EQ(armourClassName(static_cast<ArmourClass>(kArmourClasses)), "?");
}

TEST(Damage, NameTablesCoverEveryValue) {
  testing::expectRoundTrip(kArmourClassNames, {ArmourClass::Infantry, ArmourClass::Light,
                                               ArmourClass::Heavy, ArmourClass::Amphibious});
  testing::expectRoundTrip(kDamageKindNames, {DamageKind::Rifle, DamageKind::MachineGun,
                                              DamageKind::Cannon, DamageKind::LightGun});
  EXPECT_EQ(kArmourClassNames.list(), "infantry, light, heavy, amphibious");
  EXPECT_EQ(kDamageKindNames.list(), "rifle, machine_gun, cannon, light_gun");
}

TEST(Damage, WeaponProblemsAreNamed) {
  Weapon w = weaponOf("infantry");
  w.range = 0.0;
  EXPECT_EQ(problemWith(w), "range must be positive");
  w = weaponOf("infantry");
  w.cooldown = -1.0;
  EXPECT_EQ(problemWith(w), "cooldown must be positive");
  w = weaponOf("infantry");
  w.projectileSpeed = -2.0;
  EXPECT_EQ(problemWith(w), "projectile_speed must be 0 (instant) or positive");
  w = weaponOf("infantry");
  w.targets = {};
  EXPECT_EQ(problemWith(w), "targets must name at least one armour class");
  w = weaponOf("infantry");
  w.damage = -1;
  EXPECT_EQ(problemWith(w), "damage must not be negative");
}

TEST(Timing, CooldownAndFlightInWholeTicks) {
  Weapon w = weaponOf("jeep");
  EXPECT_EQ(cooldownTicks(w, 30.0),
            9);  // rounded, not ceiled: a 0.3 s·30 product a hair above 9 is still 9
  EXPECT_EQ(cooldownTicks(weaponOf("tank"), 30.0), 90);
  w.cooldown = 0.001;
  EXPECT_EQ(cooldownTicks(w, 30.0), 1);                        // never twice in one tick
  EXPECT_EQ(travelTicks(weaponOf("infantry"), 5.0, 30.0), 0);  // instant
  EXPECT_EQ(travelTicks(weaponOf("tank"), 5.0, 30.0), 10);     // 5 cells at 15 cells/s
  EXPECT_EQ(travelTicks(weaponOf("tank"), 0.0, 30.0), 1);      // point blank lands next tick
}

TEST(Range, MeasuredBetweenFootprintEdges) {
  const Combatant tank = unit(1, 0, ArmourClass::Heavy, 3, {4.5, 4.5});
  // Infantry 5 cells right of the tank's right edge (x = 6): centre 11.5, left edge 11.
  const Combatant inf = unit(2, 1, ArmourClass::Infantry, 1, {11.5, 4.5});
  EXPECT_DOUBLE_EQ(gapSquared(tank, inf), 25.0);
  EXPECT_DOUBLE_EQ(gapSquared(inf, tank), 25.0);
  Weapon rifle = weaponOf("infantry");  // range 5
  EXPECT_TRUE(inRange(rifle, inf, tank));
  rifle.range = 4.99;
  EXPECT_FALSE(inRange(rifle, inf, tank));
  // Diagonal: 3 and 4 cells apart on each axis is a gap of 5.
  const Combatant diag = unit(3, 1, ArmourClass::Infantry, 1, {6.0 + 3.0 + 0.5, 6.0 + 4.0 + 0.5});
  EXPECT_DOUBLE_EQ(gapSquared(tank, diag), 25.0);
  // Overlapping or touching footprints are at gap 0.
  EXPECT_EQ(gapSquared(tank, unit(4, 1, ArmourClass::Infantry, 1, {6.5, 4.5})), 0.0);
}

// ---- line of sight ------------------------------------------------------------------------

TEST(LineOfSight, ClearOnOpenGroundAndToItself) {
  const GridMap map(10, 10);
  EXPECT_TRUE(lineOfSight(map, Cell{0, 0}, Cell{9, 9}));
  EXPECT_TRUE(lineOfSight(map, Cell{9, 0}, Cell{0, 7}));
  EXPECT_TRUE(lineOfSight(map, Cell{3, 3}, Cell{3, 3}));
}

TEST(LineOfSight, BlockedCellsOnTheSegmentStopIt) {
  GridMap map(10, 10);
  map.set({5, 4}, Terrain::Blocked);
  EXPECT_FALSE(lineOfSight(map, Cell{0, 4}, Cell{9, 4}));
  EXPECT_TRUE(lineOfSight(map, Cell{0, 3}, Cell{9, 3}));
  // Water and swamp do not hide anything.
  map.set({5, 4}, Terrain::Water);
  map.set({6, 4}, Terrain::Swamp);
  EXPECT_TRUE(lineOfSight(map, Cell{0, 4}, Cell{9, 4}));
}

TEST(LineOfSight, SupercoverVisitsEveryCellTheSegmentCrosses) {
  // Centre (0.5, 0.5) to (4.5, 1.5) crosses row 1 at x = 2.5: cells (0,0) (1,0) (2,0) (2,1)
  // (3,1) (4,1).
  for (const Cell wall : {Cell{1, 0}, Cell{2, 0}, Cell{2, 1}, Cell{3, 1}}) {
    GridMap map(6, 3);
    map.set(wall, Terrain::Blocked);
    EXPECT_FALSE(lineOfSight(map, Cell{0, 0}, Cell{4, 1})) << wall.x << "," << wall.y;
    EXPECT_FALSE(lineOfSight(map, Cell{4, 1}, Cell{0, 0})) << wall.x << "," << wall.y;
  }
  for (const Cell off : {Cell{1, 1}, Cell{3, 0}, Cell{0, 1}, Cell{4, 0}}) {
    GridMap map(6, 3);
    map.set(off, Terrain::Blocked);
    EXPECT_TRUE(lineOfSight(map, Cell{0, 0}, Cell{4, 1})) << off.x << "," << off.y;
    EXPECT_TRUE(lineOfSight(map, Cell{4, 1}, Cell{0, 0})) << off.x << "," << off.y;
  }
}

TEST(LineOfSight, ExactDiagonalSqueezesPastOneCornerButNotTwo) {
  GridMap map(5, 5);
  map.set({1, 0}, Terrain::Blocked);  // touches the segment (0,0)→(3,3) only at a corner
  EXPECT_TRUE(lineOfSight(map, Cell{0, 0}, Cell{3, 3}));
  EXPECT_TRUE(lineOfSight(map, Cell{3, 3}, Cell{0, 0}));
  map.set({0, 1}, Terrain::Blocked);  // both sides of that corner: a closed diagonal wall
  EXPECT_FALSE(lineOfSight(map, Cell{0, 0}, Cell{3, 3}));
  EXPECT_FALSE(lineOfSight(map, Cell{3, 3}, Cell{0, 0}));
  // A block on the diagonal itself always hides.
  GridMap onLine(5, 5);
  onLine.set({2, 2}, Terrain::Blocked);
  EXPECT_FALSE(lineOfSight(onLine, Cell{0, 0}, Cell{3, 3}));
  // A 2:1 line never passes exactly through a corner: (1,0) lies on it and hides.
  GridMap twoOne(6, 4);
  twoOne.set({1, 0}, Terrain::Blocked);
  EXPECT_FALSE(lineOfSight(twoOne, Cell{0, 0}, Cell{4, 2}));
}

TEST(LineOfSight, EndCellsNeverBlock) {
  GridMap map(6, 6);
  map.set({0, 0}, Terrain::Trees);
  map.set({5, 5}, Terrain::Blocked);
  SightRules noTrees;
  noTrees.maxTreeCells = 0;
  EXPECT_TRUE(lineOfSight(map, Cell{0, 0}, Cell{5, 5}, noTrees));
  EXPECT_TRUE(lineOfSight(map, Cell{5, 5}, Cell{0, 0}, noTrees));
}

TEST(LineOfSight, TreesThinSightUpToTheConfiguredDepth) {
  GridMap map(10, 3);
  map.set({3, 1}, Terrain::Trees);
  map.set({4, 1}, Terrain::Trees);
  EXPECT_TRUE(lineOfSight(map, Cell{0, 1}, Cell{9, 1}));  // two trees: default depth 2
  map.set({5, 1}, Terrain::Trees);
  EXPECT_FALSE(lineOfSight(map, Cell{0, 1}, Cell{9, 1}));  // three: hidden
  EXPECT_TRUE(lineOfSight(map, Cell{0, 1}, Cell{4, 1}));   // into the edge: one tree between
  SightRules open;
  open.maxTreeCells = -1;
  EXPECT_TRUE(lineOfSight(map, Cell{0, 1}, Cell{9, 1}, open));
  map.set({7, 1}, Terrain::Blocked);
  EXPECT_FALSE(lineOfSight(map, Cell{0, 1}, Cell{9, 1}, open));  // walls still stop it
  SightRules dense;
  dense.maxTreeCells = 0;
  EXPECT_FALSE(lineOfSight(map, Cell{0, 1}, Cell{4, 1}, dense));
}

TEST(LineOfSight, OffTheMapIsBlocked) {
  const GridMap map(4, 4);
  EXPECT_FALSE(lineOfSight(map, Cell{-3, 1}, Cell{2, 1}));
}

TEST(LineOfSight, SymmetricOnRandomMaps) {
  std::mt19937 rng(6);
  std::uniform_int_distribution<int> coord(0, 15);
  std::uniform_int_distribution<int> terrain(0, 9);
  int blocked = 0;
  int clear = 0;
  for (int round = 0; round < 20; ++round) {
    GridMap map(16, 16);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const int r = terrain(rng);
        map.set({x, y}, r == 0 ? Terrain::Blocked : r == 1 ? Terrain::Trees : Terrain::Ground);
      }
    for (int q = 0; q < 200; ++q) {
      const Cell a{coord(rng), coord(rng)};
      const Cell b{coord(rng), coord(rng)};
      const bool ab = lineOfSight(map, a, b);
      ASSERT_EQ(ab, lineOfSight(map, b, a)) << a.x << "," << a.y << " " << b.x << "," << b.y;
      (ab ? clear : blocked)++;
    }
  }
  EXPECT_GT(blocked, 100);  // the maps are neither empty nor solid
  EXPECT_GT(clear, 100);
}

// ---- targeting ----------------------------------------------------------------------------

TEST(Targeting, NearestEnemyInRangeAndSightTiesByIdInAnyOrder) {
  const GridMap map(20, 20);
  const Weapon rifle = weaponOf("infantry");
  const Combatant me = unit(5, 0, ArmourClass::Infantry, 1, {10.5, 10.5});
  // Two enemies at the same gap (3, on opposite sides): id 7 wins over id 9.
  std::vector<Combatant> cs = {
      me,
      unit(9, 1, ArmourClass::Infantry, 1, {14.5, 10.5}),
      unit(7, 1, ArmourClass::Infantry, 1, {6.5, 10.5}),
      unit(2, 0, ArmourClass::Infantry, 1, {11.5, 10.5}),  // a friend, nearer
      unit(3, 1, ArmourClass::Infantry, 1, {17.5, 10.5}),  // out of range (gap 6)
  };
  EXPECT_EQ(acquireTarget(rifle, me, cs, map), 7u);
  std::reverse(cs.begin(), cs.end());
  EXPECT_EQ(acquireTarget(rifle, me, cs, map), 7u);
  // A nearer enemy beats the id order.
  cs.push_back(unit(12, 1, ArmourClass::Infantry, 1, {10.5, 12.5}));
  EXPECT_EQ(acquireTarget(rifle, me, cs, map), 12u);
  // Dead enemies are not targets.
  cs.back().hp = 0;
  EXPECT_EQ(acquireTarget(rifle, me, cs, map), 7u);
  // A dead shooter picks nothing.
  Combatant ghost = me;
  ghost.hp = 0;
  EXPECT_FALSE(acquireTarget(rifle, ghost, cs, map));
}

TEST(Targeting, PriorityBeatsDistance) {
  const GridMap map(20, 20);
  const Weapon gun = weaponOf("tank");  // vehicles before infantry
  const Combatant tank = unit(1, 0, ArmourClass::Heavy, 3, {5.5, 5.5});
  const std::vector<Combatant> cs = {
      unit(2, 1, ArmourClass::Infantry, 1, {8.5, 5.5}),  // gap 1
      unit(3, 1, ArmourClass::Light, 2, {13.0, 5.5}),    // gap 5
      unit(4, 1, ArmourClass::Heavy, 3, {5.5, 14.5}),    // gap 6
  };
  EXPECT_EQ(acquireTarget(gun, tank, cs, map), 3u);
  // Within rank 0 the jeep (gap 5) beats the tank (gap 6); with all ranks equal the infantry,
  // nearest, wins.
  Weapon flat = gun;
  flat.priority = {};
  EXPECT_EQ(acquireTarget(flat, tank, cs, map), 2u);
}

TEST(Targeting, OnlyClassesTheWeaponTargets) {
  const GridMap map(20, 20);
  Weapon antiTank = weaponOf("infantry");
  antiTank.targets = TargetMask::of({ArmourClass::Heavy, ArmourClass::Light});
  const Combatant me = unit(1, 0, ArmourClass::Infantry, 1, {2.5, 2.5});
  const std::vector<Combatant> cs = {
      unit(2, 1, ArmourClass::Infantry, 1, {3.5, 2.5}),
      unit(3, 1, ArmourClass::Heavy, 3, {7.5, 3.5}),
  };
  EXPECT_EQ(acquireTarget(antiTank, me, cs, map), 3u);
  antiTank.targets = TargetMask::of({ArmourClass::Amphibious});
  EXPECT_FALSE(acquireTarget(antiTank, me, cs, map));
}

TEST(Targeting, HiddenNearestGivesWayToAVisibleOne) {
  GridMap map(20, 20);
  map.set({8, 10}, Terrain::Blocked);
  const Weapon rifle = weaponOf("infantry");
  const Combatant me = unit(1, 0, ArmourClass::Infantry, 1, {10.5, 10.5});
  const std::vector<Combatant> cs = {
      unit(2, 1, ArmourClass::Infantry, 1, {6.5, 10.5}),   // gap 3, behind the wall
      unit(3, 1, ArmourClass::Infantry, 1, {10.5, 14.5}),  // gap 3, id larger, in sight
      unit(4, 1, ArmourClass::Infantry, 1, {15.5, 10.5}),  // gap 4
  };
  EXPECT_EQ(acquireTarget(rifle, me, cs, map), 3u);
  EXPECT_FALSE(canEngage(rifle, me, cs[0], map));
  EXPECT_TRUE(canEngage(rifle, me, cs[1], map));
}

TEST(Targeting, RetargetOnlyWhenTheTargetDiesLeavesRangeOrHides) {
  GridMap map(20, 20);
  const Weapon rifle = weaponOf("infantry");
  const Combatant me = unit(1, 0, ArmourClass::Infantry, 1, {10.5, 10.5});
  std::vector<Combatant> cs = {
      me, unit(2, 1, ArmourClass::Infantry, 1, {14.5, 10.5}),  // gap 3: the current target
      unit(3, 1, ArmourClass::Infantry, 1, {10.5, 15.5}),      // gap 4
  };
  std::optional<std::uint32_t> target = chooseTarget(rifle, me, std::nullopt, cs, map);
  EXPECT_EQ(target, 2u);
  // A nearer enemy walks up: the gunner keeps firing at its target.
  cs.push_back(unit(4, 1, ArmourClass::Infantry, 1, {11.5, 11.5}));
  EXPECT_EQ(chooseTarget(rifle, me, target, cs, map), 2u);
  // The target dies: the nearest (4) is taken.
  cs[1].hp = 0;
  target = chooseTarget(rifle, me, target, cs, map);
  EXPECT_EQ(target, 4u);
  // It walks out of range: back to 3.
  cs[3].centre = {18.5, 18.5};
  target = chooseTarget(rifle, me, target, cs, map);
  EXPECT_EQ(target, 3u);
  // A wall goes up between: nothing left to shoot.
  map.set({10, 13}, Terrain::Blocked);
  target = chooseTarget(rifle, me, target, cs, map);
  EXPECT_FALSE(target);
  // A target id no longer among the candidates (removed from the world) is dropped.
  map.set({10, 13}, Terrain::Ground);
  EXPECT_EQ(chooseTarget(rifle, me, 99u, cs, map), 3u);
}

// ---- duels --------------------------------------------------------------------------------

// The firing convention the engine will follow within one tick t: every living unit whose
// weapon is ready (t >= readyTick) and has a target fires, in id order, and its weapon is ready
// again at t + cooldownTicks; then every shot due at or before t lands, in the order fired. A
// shot lands at t + travelTicks (same tick when instant), even if its shooter has died.
struct Fighter {
  Combatant c;
  Weapon weapon;
  std::int64_t readyTick = 0;
  std::optional<std::uint32_t> target;
  std::optional<std::int64_t> diedAt;
};

struct Shot {
  std::int64_t landTick = 0;
  std::uint32_t target = 0;
  int damage = 0;
};

void fight(std::vector<Fighter>& fighters, const GridMap& map, std::int64_t ticks) {
  constexpr double kTicksPerSecond = 30.0;
  const ArmourTable table = defaultArmourTable();
  std::vector<Shot> inFlight;
  for (std::int64_t t = 0; t < ticks; ++t) {
    std::vector<Combatant> snapshot;
    for (const Fighter& f : fighters)
      snapshot.push_back(f.c);
    for (Fighter& f : fighters) {
      if (!f.c.alive()) continue;
      f.target = chooseTarget(f.weapon, f.c, f.target, snapshot, map);
      if (!f.target || t < f.readyTick) continue;
      const Combatant& victim = *std::find_if(
          snapshot.begin(), snapshot.end(), [&](const Combatant& c) { return c.id == *f.target; });
      const double gap = std::sqrt(gapSquared(f.c, victim));
      inFlight.push_back({t + travelTicks(f.weapon, gap, kTicksPerSecond), victim.id,
                          damageDealt(f.weapon, victim.armour, table)});
      f.readyTick = t + cooldownTicks(f.weapon, kTicksPerSecond);
    }
    std::vector<Shot> later;
    for (const Shot& s : inFlight) {
      if (s.landTick > t) {
        later.push_back(s);
        continue;
      }
      for (Fighter& f : fighters)
        if (f.c.id == s.target && f.c.alive()) {
          f.c.hp = applyDamage(f.c.hp, s.damage);
          if (!f.c.alive()) f.diedAt = t;
        }
    }
    inFlight = std::move(later);
  }
}

TEST(Duel, JeepOutgunsRiflemanAtTick81) {
  // Jeep (id 1, 200 hp, machine gun: 8 · 125% = 10 per shot on infantry, every 0.3 s = 9
  // ticks) against a rifleman (id 2, 100 hp, rifle: 10 · 40% = 4 per shot on light armour,
  // every 30 ticks), gap 4: both in range (6 and 5). The jeep fires at ticks 0, 9, …, 81; its
  // tenth shot, at tick 81, takes the last 10 hp. The rifleman fires at 0, 30 and 60: the jeep
  // is left with 200 − 3·4 = 188 hp.
  const GridMap map(20, 10);
  std::vector<Fighter> f = {
      {unit(1, 0, armourOf("jeep"), 2, {3.0, 5.0}, 200), weaponOf("jeep"), 0, std::nullopt,
       std::nullopt},
      {unit(2, 1, armourOf("infantry"), 1, {8.5, 5.5}, 100), weaponOf("infantry"), 0, std::nullopt,
       std::nullopt},
  };
  ASSERT_DOUBLE_EQ(gapSquared(f[0].c, f[1].c), 16.0);
  fight(f, map, 200);
  EXPECT_FALSE(f[0].diedAt);
  EXPECT_EQ(f[0].c.hp, 188);
  EXPECT_EQ(f[1].diedAt, 81);
  EXPECT_EQ(f[1].c.hp, 0);
}

TEST(Duel, TankShellInFlightKillsTheJeepAtTick10) {
  // Tank (id 1, 800 hp, gun: 150 · 150% = 225 on light armour, shells at 15 cells/s, every
  // 90 ticks) against a jeep (id 2, 200 hp, machine gun: 8 · 10% = 0.8, scratching for 1 on
  // heavy armour, every 9 ticks), gap 5. The shell fired at tick 0 flies 5/15 s = 10 ticks and
  // lands at tick 10, killing the jeep outright; meanwhile the jeep fired at 0 and 9: the tank
  // keeps 798 hp. The same fight behind a wall: no one fires.
  GridMap map(20, 10);
  const auto duel = [&] {
    return std::vector<Fighter>{
        {unit(1, 0, armourOf("tank"), 3, {4.5, 4.5}, 800), weaponOf("tank"), 0, std::nullopt,
         std::nullopt},
        {unit(2, 1, armourOf("jeep"), 2, {12.0, 4.0}, 200), weaponOf("jeep"), 0, std::nullopt,
         std::nullopt},
    };
  };
  std::vector<Fighter> f = duel();
  ASSERT_DOUBLE_EQ(gapSquared(f[0].c, f[1].c), 25.0);
  fight(f, map, 120);
  EXPECT_EQ(f[1].diedAt, 10);
  EXPECT_FALSE(f[0].diedAt);
  EXPECT_EQ(f[0].c.hp, 798);

  for (int y = 0; y < 10; ++y)
    map.set({8, y}, Terrain::Blocked);
  std::vector<Fighter> walled = duel();
  fight(walled, map, 120);
  EXPECT_EQ(walled[0].c.hp, 800);
  EXPECT_EQ(walled[1].c.hp, 200);
}

}  // namespace
}  // namespace warpath::units
