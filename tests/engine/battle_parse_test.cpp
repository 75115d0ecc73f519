// Battle scenario files: armour and weapons in unit types, the combat settings, reinforcement
// groups, orders of every kind, triggers, victory conditions and outcome expectations; and the
// errors for each, with the line they point at.

#include <gtest/gtest.h>

#include <string>

#include "engine/scenario.h"
#include "support/scenario_files.h"
#include "units/combat.h"

namespace warpath::engine {
namespace {

using units::ArmourClass;
using units::DamageKind;
using units::TargetMask;

const std::string kBattleInputFile =
    std::string(WARPATH_SOURCE_DIR) + "/scenarios/battle_input.yaml";

// 1-based line of the first occurrence of `needle` in `text` (0 when absent).
int lineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) return 0;
  int line = 1;
  for (std::size_t i = 0; i < at; ++i)
    line += text[i] == '\n' ? 1 : 0;
  return line;
}

// 1-based column of the first occurrence of `needle` on its line (0 when absent).
int columnOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) return 0;
  const std::size_t lineStart = text.rfind('\n', at);
  return static_cast<int>(at - (lineStart == std::string::npos ? 0 : lineStart + 1)) + 1;
}

std::string rectText(const pathing::CellRect& r) {
  return std::to_string(r.x) + "," + std::to_string(r.y) + " " + std::to_string(r.width) + "x" +
         std::to_string(r.height);
}

// Two teams on a 20x10 field with a pond; blue soldiers on the left, red soldiers and a red
// truck column (a reinforcement) on the right. `extra` is appended after the groups.
std::string battle(const std::string& extra, const std::string& unitTypes = "") {
  return "map:\n"
         "  rows:\n"
         "    - '....................'\n"
         "    - '....................'\n"
         "    - '....................'\n"
         "    - '....................'\n"
         "    - '........WW..........'\n"
         "    - '........WW..........'\n"
         "    - '....................'\n"
         "    - '....................'\n"
         "    - '....................'\n"
         "    - '....................'\n"
         "unit_types:\n"
         "  soldier:\n"
         "    size: 1\n"
         "    capability: [ground]\n"
         "    speed: 1.5\n"
         "    weapon: {kind: rifle, damage: 10, range: 5, cooldown: 1}\n"
         "  truck: {size: 1, capability: [ground], speed: 3}\n" +
         unitTypes +
         "duration: 60\n"
         "teams: [blue, red]\n"
         "groups:\n"
         "  - {name: b1, team: blue, type: soldier, count: 3, spawn: {x: 0, y: 0, w: 3, h: 3}}\n"
         "  - {name: b2, team: blue, type: truck, count: 2, spawn: {x: 0, y: 6, w: 3, h: 3}}\n"
         "  - {name: r1, team: red, type: soldier, count: 3, spawn: {x: 16, y: 0, w: 3, h: 3}}\n"
         "  - {name: r2, team: red, type: truck, count: 2, spawn: {x: 16, y: 6, w: 3, h: 3},\n"
         "     reinforcement: true}\n" +
         extra;
}

Scenario loadBattle(const std::string& text) {
  return testing::parsedScenario(text, kBattleInputFile);
}

Error battleErrorOf(const std::string& text) {
  return testing::scenarioError(text, kBattleInputFile);
}

// The error names the problem (`part` is in the message) at the line holding `where`.
void expectError(const std::string& text, const std::string& part, const std::string& where) {
  const Error e = battleErrorOf(text);
  EXPECT_NE(e.message.find(part), std::string::npos) << "message: " << e.message;
  EXPECT_EQ(e.line, lineOf(text, where)) << e.describe();
  EXPECT_GT(e.column, 0);
  EXPECT_EQ(e.describe().rfind(kBattleInputFile + ":" + std::to_string(e.line) + ":", 0), 0u)
      << e.describe();
}

const units::UnitType& typeNamed(const Scenario& s, const std::string& name) {
  for (const units::UnitType& t : s.catalogue) {
    if (t.name == name) return t;
  }
  ADD_FAILURE() << "no unit type " << name;
  return s.catalogue.front();
}

void expectSameWeapon(const units::Weapon& a, const units::Weapon& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.kind, b.kind) << a.name;
  EXPECT_EQ(a.damage, b.damage) << a.name;
  EXPECT_EQ(a.range, b.range) << a.name;
  EXPECT_EQ(a.cooldown, b.cooldown) << a.name;
  EXPECT_EQ(a.projectileSpeed, b.projectileSpeed) << a.name;
  EXPECT_EQ(a.targets, b.targets) << a.name;
  EXPECT_EQ(a.priority, b.priority) << a.name;
}

// ---- unit types -------------------------------------------------------------------------

TEST(BattleParse, BundledCatalogueHasTheDefaultArmourAndWeapons) {
  const Result<std::vector<units::UnitType>> r =
      loadCatalogue(std::string(WARPATH_SOURCE_DIR) + "/assets/units.yaml");
  ASSERT_TRUE(r.ok()) << r.error().describe();
  ASSERT_EQ(r.value().size(), 4u);
  for (const units::UnitType& t : r.value()) {
    ASSERT_TRUE(units::defaultArmourFor(t.name).has_value()) << t.name;
    EXPECT_EQ(t.armour, *units::defaultArmourFor(t.name)) << t.name;
    ASSERT_TRUE(t.weapon.has_value()) << t.name;
    expectSameWeapon(*t.weapon, *units::defaultWeaponFor(t.name));
  }
}

TEST(BattleParse, NewTypesWeaponDefaultsAndArmour) {
  const Scenario s = loadBattle(battle("",
                                       "  tank: {size: 2, capability: [ground], speed: 1}\n"
                                       "  sniper:\n"
                                       "    size: 1\n"
                                       "    capability: [ground]\n"
                                       "    speed: 1\n"
                                       "    armour: light\n"
                                       "    weapon:\n"
                                       "      name: long_rifle\n"
                                       "      kind: rifle\n"
                                       "      damage: 40\n"
                                       "      range: 12.5\n"
                                       "      cooldown: 4\n"
                                       "      projectile_speed: 30\n"
                                       "      targets: [infantry, light]\n"
                                       "      priority: {light: 0, infantry: 3}\n"));
  // A weapon on a new type: name from the kind, instant, every class, all ranks equal.
  const units::UnitType& soldier = typeNamed(s, "soldier");
  EXPECT_EQ(soldier.armour, ArmourClass::Infantry);  // no default for the name: infantry
  ASSERT_TRUE(soldier.weapon.has_value());
  EXPECT_EQ(soldier.weapon->name, "rifle");
  EXPECT_EQ(soldier.weapon->kind, DamageKind::Rifle);
  EXPECT_EQ(soldier.weapon->damage, 10);
  EXPECT_EQ(soldier.weapon->range, 5.0);
  EXPECT_EQ(soldier.weapon->cooldown, 1.0);
  EXPECT_EQ(soldier.weapon->projectileSpeed, 0.0);
  EXPECT_EQ(soldier.weapon->targets, TargetMask::all());
  EXPECT_EQ(soldier.weapon->priority, (std::array<std::uint8_t, 4>{0, 0, 0, 0}));
  // No weapon given: unarmed.
  EXPECT_FALSE(typeNamed(s, "truck").weapon.has_value());
  EXPECT_EQ(typeNamed(s, "truck").armour, ArmourClass::Infantry);
  // A new type named like a catalogue default gets that armour (but no weapon).
  EXPECT_EQ(typeNamed(s, "tank").armour, ArmourClass::Heavy);
  EXPECT_FALSE(typeNamed(s, "tank").weapon.has_value());
  // Every field given.
  const units::UnitType& sniper = typeNamed(s, "sniper");
  EXPECT_EQ(sniper.armour, ArmourClass::Light);
  ASSERT_TRUE(sniper.weapon.has_value());
  EXPECT_EQ(sniper.weapon->name, "long_rifle");
  EXPECT_EQ(sniper.weapon->damage, 40);
  EXPECT_EQ(sniper.weapon->range, 12.5);
  EXPECT_EQ(sniper.weapon->cooldown, 4.0);
  EXPECT_EQ(sniper.weapon->projectileSpeed, 30.0);
  EXPECT_EQ(sniper.weapon->targets, TargetMask::of({ArmourClass::Infantry, ArmourClass::Light}));
  EXPECT_EQ(sniper.weapon->priority, (std::array<std::uint8_t, 4>{3, 0, 0, 0}));
}

TEST(BattleParse, OverridingACatalogueWeaponChangesOnlyTheFieldsGiven) {
  const std::string text =
      "map: {rows: ['..........', '..........', '..........', '..........']}\n"
      "catalogue: ../assets/units.yaml\n"
      "unit_types:\n"
      "  tank: {weapon: {damage: 200, priority: {infantry: 5}}}\n"
      "  infantry: {weapon: none}\n"
      "  jeep: {armour: heavy}\n"
      "  amphibious: {weapon: {kind: rifle}}\n"
      "duration: 10\n"
      "teams: [blue]\n"
      "groups: []\n";
  const Scenario s = loadBattle(text);
  units::Weapon tankGun = *units::defaultWeaponFor("tank");
  tankGun.damage = 200;
  tankGun.priority[static_cast<std::size_t>(ArmourClass::Infantry)] = 5;
  ASSERT_TRUE(typeNamed(s, "tank").weapon.has_value());
  expectSameWeapon(*typeNamed(s, "tank").weapon, tankGun);
  EXPECT_EQ(typeNamed(s, "tank").armour, ArmourClass::Heavy);
  EXPECT_FALSE(typeNamed(s, "infantry").weapon.has_value());
  EXPECT_EQ(typeNamed(s, "jeep").armour, ArmourClass::Heavy);
  expectSameWeapon(*typeNamed(s, "jeep").weapon, *units::defaultWeaponFor("jeep"));
  // Changing the kind of an existing weapon keeps its name.
  units::Weapon lightGun = *units::defaultWeaponFor("amphibious");
  lightGun.kind = DamageKind::Rifle;
  expectSameWeapon(*typeNamed(s, "amphibious").weapon, lightGun);
}

TEST(BattleParse, WeaponAndArmourErrors) {
  const auto withSoldierWeapon = [](const std::string& weapon) {
    std::string text = battle("");
    const std::string old = "    weapon: {kind: rifle, damage: 10, range: 5, cooldown: 1}\n";
    text.replace(text.find(old), old.size(), "    weapon: " + weapon + "\n");
    return text;
  };
  expectError(withSoldierWeapon("{kind: laser, damage: 10, range: 5, cooldown: 1}"),
              "unknown damage kind 'laser' (rifle, machine_gun, cannon, light_gun)", "laser");
  expectError(withSoldierWeapon("{kind: rifle, damage: 10, range: 5}"),
              "a new unit type 'soldier' weapon needs 'cooldown'", "weapon:");
  expectError(withSoldierWeapon("{kind: rifle, damage: 10, range: 0, cooldown: 1}"),
              "unit type 'soldier' weapon range must be greater than 0", "weapon:");
  expectError(withSoldierWeapon("{kind: rifle, damage: -1, range: 5, cooldown: 1}"),
              "weapon damage must be between 0 and", "weapon:");
  expectError(withSoldierWeapon("{kind: rifle, damage: 1, range: 5, cooldown: 1, reach: 3}"),
              "unknown key 'reach' in unit type 'soldier' weapon", "weapon:");
  expectError(withSoldierWeapon("{kind: rifle, damage: 1, range: 5, cooldown: 1, targets: []}"),
              "targets must name at least one armour class", "weapon:");
  expectError(
      withSoldierWeapon("{kind: rifle, damage: 1, range: 5, cooldown: 1, targets: [walls]}"),
      "unknown armour class 'walls'", "weapon:");
  expectError(
      withSoldierWeapon("{kind: rifle, damage: 1, range: 5, cooldown: 1, priority: {heavy: 300}}"),
      "priority rank must be between 0 and 255", "weapon:");
  expectError(withSoldierWeapon("rifle"), "weapon must be 'none' or a mapping", "weapon:");
  expectError(battle("", "  knight: {size: 1, capability: [ground], speed: 1, armour: plate}\n"),
              "unknown armour class 'plate' (infantry, light, heavy, amphibious)", "plate");
}

// ---- combat settings ----------------------------------------------------------------------

TEST(BattleParse, CombatSettings) {
  const Scenario defaults = loadBattle(battle(""));
  const CombatSettings d;
  EXPECT_TRUE(defaults.settings.combat.enabled);
  EXPECT_EQ(defaults.settings.combat.wreckSeconds, d.wreckSeconds);
  EXPECT_EQ(defaults.settings.combat.sight.maxTreeCells, d.sight.maxTreeCells);
  EXPECT_EQ(defaults.settings.combat.scanEveryTicks, d.scanEveryTicks);
  EXPECT_EQ(defaults.settings.combat.armour, units::defaultArmourTable());

  const Scenario s = loadBattle(
      battle("combat:\n"
             "  enabled: false\n"
             "  wreck_seconds: 0\n"
             "  sight_through_trees: -1\n"
             "  scan_every: 3\n"
             "  armour: {cannon: {infantry: 10, heavy: 120}, rifle: {amphibious: 0}}\n"));
  const CombatSettings& c = s.settings.combat;
  EXPECT_FALSE(c.enabled);
  EXPECT_EQ(c.wreckSeconds, 0.0);
  EXPECT_EQ(c.sight.maxTreeCells, -1);
  EXPECT_EQ(c.scanEveryTicks, 3);
  units::ArmourTable table = units::defaultArmourTable();
  table[static_cast<std::size_t>(DamageKind::Cannon)][0] = 10;
  table[static_cast<std::size_t>(DamageKind::Cannon)][2] = 120;
  table[static_cast<std::size_t>(DamageKind::Rifle)][3] = 0;
  EXPECT_EQ(c.armour, table);
}

TEST(BattleParse, CombatSettingsErrors) {
  expectError(battle("combat: {armour: {rifle: {heavy: 1001}}}\n"),
              "armour percent rifle vs heavy must be between 0 and 1000", "1001");
  expectError(battle("combat: {armour: {laser: {heavy: 10}}}\n"), "unknown damage kind 'laser'",
              "laser");
  expectError(battle("combat: {armour: {rifle: {walls: 10}}}\n"), "unknown armour class 'walls'",
              "walls");
  expectError(battle("combat: {enabled: maybe}\n"), "combat enabled must be true or false",
              "maybe");
  expectError(battle("combat: {scan_every: 0}\n"), "scan_every must be between 1 and",
              "scan_every");
  expectError(battle("combat: {sight_through_trees: -2}\n"),
              "sight_through_trees must be between -1 and", "sight_through_trees");
  expectError(battle("combat: {wreck_seconds: -1}\n"), "wreck_seconds must be between 0 and",
              "wreck_seconds");
  expectError(battle("combat: {wrecks: 3}\n"), "unknown key 'wrecks' in combat", "wrecks");
}

TEST(BattleParse, TravelScenariosHaveCombatOff) {
  for (const char* name : {"demo", "stress_2000"}) {
    const Result<Scenario> r =
        loadScenario(std::string(WARPATH_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
    ASSERT_TRUE(r.ok()) << r.error().describe();
    EXPECT_FALSE(r.value().settings.combat.enabled) << name;
    EXPECT_TRUE(r.value().catalogue[0].weapon.has_value()) << name;
  }
}

// ---- groups and orders ---------------------------------------------------------------------

TEST(BattleParse, ReinforcementGroups) {
  const Scenario s = loadBattle(battle(""));
  ASSERT_EQ(s.groups.size(), 4u);
  EXPECT_FALSE(s.groups[0].reinforcement);
  EXPECT_TRUE(s.groups[3].reinforcement);
  EXPECT_EQ(s.groups[3].anchors.size(), 2u);  // chosen at load like any group's
  // Its spawn cells may not overlap another group's.
  std::string text = battle("");
  const std::string old = "spawn: {x: 16, y: 6, w: 3, h: 3},\n     reinforcement: true}";
  text.replace(text.find(old), old.size(),
               "spawn: {x: 16, y: 0, w: 3, h: 1},\n     reinforcement: true}");
  expectError(text, "has room for only 0 of 2 truck", "{x: 16, y: 0, w: 3, h: 1}");
  std::string often = battle("");
  often.replace(often.find("reinforcement: true"), 19, "reinforcement: often");
  expectError(often, "reinforcement must be true or false", "often");
}

TEST(BattleParse, OrdersOfEveryKind) {
  const Scenario s = loadBattle(battle(
      "orders:\n"
      "  - {at: 1, group: b1, move_to: {x: 10, y: 0, w: 2, h: 2}}\n"
      "  - {at: 2, group: [b1, b2], order: attack_move, move_to: {x: 12, y: 0, w: 4, h: 4}}\n"
      "  - {when: {arrived: b1, fraction: 0.5}, group: b1, order: attack, target: [r1, r2]}\n"
      "  - {at: 3, group: r1, order: attack, target: b2}\n"
      "  - {at: 4, group: r1, order: hold}\n"
      "  - {at: 5, group: [r1, r2], order: stop}\n"));
  ASSERT_EQ(s.triggers.size(), 6u);
  for (std::size_t i = 0; i < s.triggers.size(); ++i) {
    EXPECT_EQ(s.triggers[i].name, "order " + std::to_string(i + 1));
    ASSERT_EQ(s.triggers[i].actions.size(), 1u);
    EXPECT_EQ(s.triggers[i].actions[0].kind, ActionKind::Order);
  }
  const ActionSpec& move = s.triggers[0].actions[0];
  EXPECT_EQ(s.triggers[0].kind, TriggerKind::At);
  EXPECT_EQ(s.triggers[0].at, 1.0);
  EXPECT_EQ(move.order, OrderKind::Move);
  EXPECT_EQ(move.groups, std::vector<int>{0});
  EXPECT_EQ(rectText(move.area), "10,0 2x2");
  const ActionSpec& attackMove = s.triggers[1].actions[0];
  EXPECT_EQ(attackMove.order, OrderKind::AttackMove);
  EXPECT_EQ(attackMove.groups, (std::vector<int>{0, 1}));
  EXPECT_EQ(rectText(attackMove.area), "12,0 4x4");
  EXPECT_EQ(s.triggers[2].kind, TriggerKind::Arrived);
  EXPECT_EQ(s.triggers[2].group, 0);
  EXPECT_EQ(s.triggers[2].fraction, 0.5);
  EXPECT_EQ(s.triggers[2].actions[0].order, OrderKind::Attack);
  EXPECT_EQ(s.triggers[2].actions[0].targetGroups, (std::vector<int>{2, 3}));
  EXPECT_EQ(s.triggers[3].actions[0].targetGroups, std::vector<int>{1});
  EXPECT_EQ(s.triggers[4].actions[0].order, OrderKind::Hold);
  EXPECT_EQ(s.triggers[4].actions[0].groups, std::vector<int>{2});
  EXPECT_EQ(s.triggers[5].actions[0].order, OrderKind::Stop);
  EXPECT_EQ(s.triggers[5].actions[0].groups, (std::vector<int>{2, 3}));
}

TEST(BattleParse, OrderErrors) {
  const std::string own =
      battle("orders:\n  - {at: 1, group: b1, order: attack, target: [r1, b2]}\n");
  expectError(own, "attack target 'b2' is on team 'blue', the team of ordered group 'b1'",
              "target: [r1, b2]");
  EXPECT_EQ(battleErrorOf(own).column, columnOf(own, "b2]"));  // at `b2` in the list
  expectError(battle("orders:\n  - {at: 1, group: [b1, r1], order: attack, target: r2}\n"),
              "attack target 'r2' is on team 'red', the team of ordered group 'r1'", "target: r2");
  expectError(battle("orders:\n  - {at: 1, group: b1, order: charge, move_to: {x: 1, y: 1, w: 1, "
                     "h: 1}}\n"),
              "unknown order 'charge' (expected stop, move, attack_move, attack or hold)",
              "charge");
  expectError(battle("orders:\n  - {at: 1, group: b1, order: attack_move}\n"),
              "order 'attack_move' needs 'move_to'", "attack_move");
  expectError(battle("orders:\n  - {at: 1, group: b1, order: attack}\n"),
              "order 'attack' needs 'target'", "order: attack");
  expectError(battle("orders:\n  - {at: 1, group: b1, order: attack, target: r1,\n"
                     "     move_to: {x: 1, y: 1, w: 1, h: 1}}\n"),
              "order 'attack' takes 'target', not 'move_to'", "move_to");
  expectError(battle("orders:\n  - {at: 1, group: b1, target: r1}\n"),
              "order 'move' takes 'move_to', not 'target'", "target");
  expectError(battle("orders:\n  - {at: 1, group: b1, order: hold, target: r1}\n"),
              "order 'hold' takes neither 'move_to' nor 'target'", "target");
  expectError(battle("orders:\n  - {at: 1, group: [b1, b1], order: stop}\n"),
              "group 'b1' named twice", "[b1, b1]");
  // Move targets are still checked reachable: the truck cannot stand in the pond.
  expectError(battle("orders:\n  - {at: 1, group: b2, move_to: {x: 8, y: 4, w: 2, h: 2}}\n"),
              "goal area 8,4 2x2 has no cell where a truck", "move_to");
}

// ---- triggers ------------------------------------------------------------------------------

TEST(BattleParse, TriggersOfEveryKind) {
  const Scenario s = loadBattle(
      battle("orders:\n"
             "  - {at: 0, group: b1, order: attack_move, move_to: {x: 14, y: 0, w: 4, h: 4}}\n"
             "triggers:\n"
             "  - name: red calls for help\n"
             "    when: {team_below: {team: red, count: 3}}\n"
             "    do:\n"
             "      - {reinforce: r2}\n"
             "      - {order: attack, group: r2, target: [b1, b2]}\n"
             "  - when: {at: 30}\n"
             "    do: [{order: hold, group: [b1, b2]}]\n"
             "  - when: {arrived: {group: b1, fraction: 0.75}}\n"
             "    do: [{order: move, group: b2, move_to: {x: 10, y: 8, w: 2, h: 2}}]\n"
             "  - when: {enters: {group: b1, area: {x: 14, y: 0, w: 6, h: 10}, count: 2}}\n"
             "    do: [{end_battle: blue}]\n"
             "  - name: last stand\n"
             "    when: {dies: {group: r1}}\n"
             "    do: [{order: stop, group: r1}, {end_battle: none}]\n"));
  ASSERT_EQ(s.triggers.size(), 6u);
  EXPECT_EQ(s.triggers[0].name, "order 1");  // orders come first
  const TriggerSpec& help = s.triggers[1];
  EXPECT_EQ(help.name, "red calls for help");
  EXPECT_EQ(help.kind, TriggerKind::TeamBelow);
  EXPECT_EQ(help.team, 1);
  EXPECT_EQ(help.count, 3);
  ASSERT_EQ(help.actions.size(), 2u);
  EXPECT_EQ(help.actions[0].kind, ActionKind::Reinforce);
  EXPECT_EQ(help.actions[0].group, 3);
  EXPECT_EQ(help.actions[1].kind, ActionKind::Order);
  EXPECT_EQ(help.actions[1].order, OrderKind::Attack);
  EXPECT_EQ(help.actions[1].groups, std::vector<int>{3});
  EXPECT_EQ(help.actions[1].targetGroups, (std::vector<int>{0, 1}));

  EXPECT_EQ(s.triggers[2].name, "trigger 2");  // numbered within triggers:
  EXPECT_EQ(s.triggers[2].kind, TriggerKind::At);
  EXPECT_EQ(s.triggers[2].at, 30.0);
  EXPECT_EQ(s.triggers[2].actions[0].order, OrderKind::Hold);
  EXPECT_EQ(s.triggers[2].actions[0].groups, (std::vector<int>{0, 1}));

  EXPECT_EQ(s.triggers[3].kind, TriggerKind::Arrived);
  EXPECT_EQ(s.triggers[3].group, 0);
  EXPECT_EQ(s.triggers[3].fraction, 0.75);
  EXPECT_EQ(rectText(s.triggers[3].actions[0].area), "10,8 2x2");

  EXPECT_EQ(s.triggers[4].kind, TriggerKind::Enters);
  EXPECT_EQ(s.triggers[4].group, 0);
  EXPECT_EQ(rectText(s.triggers[4].area), "14,0 6x10");
  EXPECT_EQ(s.triggers[4].count, 2);
  EXPECT_EQ(s.triggers[4].actions[0].kind, ActionKind::EndBattle);
  EXPECT_EQ(s.triggers[4].actions[0].team, 0);

  EXPECT_EQ(s.triggers[5].name, "last stand");
  EXPECT_EQ(s.triggers[5].kind, TriggerKind::Dies);
  EXPECT_EQ(s.triggers[5].group, 2);
  EXPECT_EQ(s.triggers[5].count, 1);  // the default
  EXPECT_EQ(s.triggers[5].actions[1].kind, ActionKind::EndBattle);
  EXPECT_EQ(s.triggers[5].actions[1].team, -1);
}

TEST(BattleParse, TriggerErrors) {
  expectError(battle("triggers:\n"
                     "  - when: {at: 5, dies: {group: r1}}\n"
                     "    do: [{end_battle: none}]\n"),
              "a trigger's 'when' has 2 conditions; give exactly one of", "{at: 5");
  expectError(battle("triggers:\n"
                     "  - when: {at: 5}\n"
                     "    do: [{reinforce: r1}]\n"),
              "group 'r1' is not a reinforcement group", "r1}]");
  expectError(battle("triggers:\n"
                     "  - when: {at: 5}\n"
                     "    do: [{reinforce: r2}]\n"
                     "  - when: {at: 9}\n"
                     "    do: [{end_battle: none}, {reinforce: r2}]\n"),
              "group 'r2' is already brought in by trigger 'trigger 1'", "none}, {reinforce");
  expectError(battle("triggers:\n"
                     "  - when: {at: 5}\n"
                     "    do: [{order: attack, group: r2, target: r1}]\n"),
              "attack target 'r1' is on team 'red'", "target: r1");
  expectError(battle("triggers:\n"
                     "  - when: {at: 5}\n"
                     "    do: [{reinforce: r2, end_battle: red}]\n"),
              "an action is exactly one of", "{reinforce: r2, end");
  expectError(battle("triggers:\n"
                     "  - when: {at: 5}\n"
                     "    do: [{group: b1, move_to: {x: 1, y: 1, w: 1, h: 1}}]\n"),
              "an action is exactly one of", "group: b1");
  expectError(battle("triggers:\n"
                     "  - when: {at: 5}\n"
                     "    do: [{end_battle: green}]\n"),
              "unknown team 'green' in end_battle (known: blue, red; or none)", "green");
  expectError(battle("triggers:\n"
                     "  - when: {at: 5}\n"
                     "    do: []\n"),
              "a trigger's 'do' must be a non-empty list of actions", "do:");
  expectError(battle("triggers:\n"
                     "  - when: {sunset: 5}\n"
                     "    do: [{end_battle: none}]\n"),
              "unknown trigger condition 'sunset' (expected at, arrived, team_below, enters or "
              "dies)",
              "sunset");
  expectError(battle("triggers:\n"
                     "  - when: {dies: {group: r1, count: 4}}\n"
                     "    do: [{end_battle: blue}]\n"),
              "dies count (group 'r1') must be between 1 and 3", "count: 4");
  expectError(battle("triggers:\n"
                     "  - when: {team_below: {team: red}}\n"
                     "    do: [{end_battle: blue}]\n"),
              "team_below needs 'count'", "team_below");
  expectError(battle("triggers:\n"
                     "  - {name: go, when: {at: 1}, do: [{end_battle: none}]}\n"
                     "  - {name: go, when: {at: 2}, do: [{end_battle: none}]}\n"),
              "trigger name 'go' used twice", "go, when: {at: 2}");
  expectError(battle("triggers:\n"
                     "  - {when: {at: 1}, then: [{end_battle: none}]}\n"),
              "unknown key 'then' in a trigger", "then");
}

// ---- terrain that changes ------------------------------------------------------------------

TEST(BattleParse, SetTerrainActions) {
  const Scenario plain = loadBattle(battle(""));
  EXPECT_FALSE(plain.settings.terrainChanges);  // runs share the scenario's grid
  EXPECT_TRUE(plain.settings.combat.wrecksBlock);
  const Scenario s =
      loadBattle(battle("combat: {wrecks_block: false}\n"
                        "triggers:\n"
                        "  - when: {at: 5}\n"
                        "    do:\n"
                        "      - {set_terrain: {area: {x: 8, y: 4, w: 2, h: 2}, "
                        "terrain: ground}}\n"
                        "      - {set_terrain: {area: {x: 0, y: 9, w: 20, h: 1}, "
                        "terrain: blocked}}\n"));
  EXPECT_FALSE(s.settings.combat.wrecksBlock);
  EXPECT_TRUE(s.settings.terrainChanges);  // each run gets a grid of its own
  ASSERT_EQ(s.triggers.size(), 1u);
  ASSERT_EQ(s.triggers[0].actions.size(), 2u);
  const ActionSpec& bridge = s.triggers[0].actions[0];
  EXPECT_EQ(bridge.kind, ActionKind::SetTerrain);
  EXPECT_EQ(rectText(bridge.area), "8,4 2x2");
  EXPECT_EQ(bridge.terrain, pathing::Terrain::Ground);
  EXPECT_EQ(s.triggers[0].actions[1].terrain, pathing::Terrain::Blocked);
}

TEST(BattleParse, SetTerrainErrors) {
  const auto action = [](const std::string& body) {
    return battle(
        "triggers:\n"
        "  - when: {at: 5}\n"
        "    do:\n"
        "      - " +
        body + "\n");
  };
  expectError(action("{set_terrain: {area: {x: 1, y: 1, w: 2, h: 2}, terrain: lava}}"),
              "unknown terrain 'lava' (ground, swamp, trees, water, blocked)", "lava");
  expectError(action("{set_terrain: {area: {x: 19, y: 1, w: 2, h: 2}, terrain: water}}"),
              "set_terrain area w must be between 1 and 1", "w: 2");
  expectError(action("{set_terrain: {area: {x: 25, y: 1, w: 1, h: 1}, terrain: water}}"),
              "set_terrain area x must be between 0 and 19", "x: 25");
  expectError(action("{set_terrain: {terrain: water}}"), "set_terrain needs 'area'",
              "{terrain: water}");
  expectError(action("{set_terrain: {area: {x: 1, y: 1, w: 1, h: 1}}}"),
              "set_terrain needs 'terrain'", "{area:");
  expectError(action("{set_terrain: {area: {x: 1, y: 1, w: 1}, terrain: water}}"),
              "set_terrain area needs 'h'", "{x: 1, y: 1, w: 1}");
  expectError(action("{set_terrain: {area: {x: 1, y: 1, w: 1, h: 1}, terrain: water, "
                     "depth: 3}}"),
              "unknown key 'depth' in set_terrain", "depth");
  expectError(action("{set_terrain: water}"), "set_terrain", "{set_terrain: water}");
  expectError(battle("combat: {wrecks_block: sometimes}\n"), "wrecks_block must be true or false",
              "sometimes");
}

// ---- victory and expectations --------------------------------------------------------------

TEST(BattleParse, VictoryConditions) {
  const Scenario s =
      loadBattle(battle("victory:\n"
                        "  - eliminate: blue\n"
                        "  - hold: {team: red, area: {x: 8, y: 2, w: 4, h: 4}, seconds: 30}\n"
                        "  - exit: {team: red, area: {x: 0, y: 0, w: 2, h: 10}, count: 5}\n"));
  ASSERT_EQ(s.victory.size(), 3u);
  EXPECT_EQ(s.victory[0].kind, VictoryKind::Eliminate);
  EXPECT_EQ(s.victory[0].team, 0);
  EXPECT_EQ(s.victory[0].text, "blue eliminates the others");
  EXPECT_EQ(s.victory[1].kind, VictoryKind::HoldArea);
  EXPECT_EQ(s.victory[1].team, 1);
  EXPECT_EQ(rectText(s.victory[1].area), "8,2 4x4");
  EXPECT_EQ(s.victory[1].seconds, 30.0);
  EXPECT_EQ(s.victory[1].text, "red holds 8,2 4x4 for 30s");
  EXPECT_EQ(s.victory[2].kind, VictoryKind::Exit);
  EXPECT_EQ(s.victory[2].count, 5);  // reinforcements count
  EXPECT_EQ(rectText(s.victory[2].area), "0,0 2x10");
  EXPECT_EQ(s.victory[2].text, "5 of red exit at 0,0 2x10");
}

TEST(BattleParse, VictoryErrors) {
  expectError(battle("victory:\n  - conquer: blue\n"),
              "unknown victory condition 'conquer' (expected eliminate, hold or exit)", "conquer");
  expectError(battle("victory:\n  - {eliminate: blue, hold: {team: red}}\n"),
              "a victory condition is exactly one of", "eliminate");
  expectError(battle("victory:\n  - exit: {team: red, area: {x: 0, y: 0, w: 2, h: 2}, count: 6}\n"),
              "exit count 6 is more than team 'red' has (5 units", "count: 6");
  expectError(battle("victory:\n  - hold: {team: red, area: {x: 0, y: 0, w: 2, h: 2}}\n"),
              "hold needs 'seconds'", "hold:");
  expectError(battle("victory:\n  - eliminate: green\n"), "unknown team 'green'", "green");
}

TEST(BattleParse, OutcomeExpectations) {
  const Scenario s =
      loadBattle(battle("expectations:\n"
                        "  - winner: blue\n"
                        "  - winner: none\n"
                        "  - losses: {team: blue, type: soldier, at_most: 3}\n"
                        "  - kills: {team: red, at_least: 2}\n"
                        "  - damage_dealt: {at_least: 100}\n"
                        "  - damage_taken: {type: truck, at_most: 50}\n"
                        "  - shots_fired: {team: blue, at_least: 1}\n"
                        "  - alive: {team: red, type: truck, at_most: 0}\n"
                        "  - arrival_rate: {team: blue, type: soldier, at_least: 0.5, by: 40}\n"));
  ASSERT_EQ(s.expectations.size(), 9u);
  EXPECT_EQ(s.expectations[0].kind, ExpectationKind::Winner);
  EXPECT_EQ(s.expectations[0].team, 0);
  EXPECT_EQ(s.expectations[0].text, "winner == blue");
  EXPECT_EQ(s.expectations[1].team, -1);
  EXPECT_EQ(s.expectations[1].text, "winner == none");
  const Expectation& losses = s.expectations[2];
  EXPECT_EQ(losses.kind, ExpectationKind::Stat);
  EXPECT_EQ(losses.stat, StatKind::Losses);
  EXPECT_TRUE(losses.atMost);
  EXPECT_EQ(losses.threshold, 3.0);
  EXPECT_EQ(losses.team, 0);
  EXPECT_EQ(losses.type, 0);
  EXPECT_EQ(losses.text, "losses(blue, soldier) <= 3");
  EXPECT_EQ(s.expectations[3].stat, StatKind::Kills);
  EXPECT_FALSE(s.expectations[3].atMost);
  EXPECT_EQ(s.expectations[3].text, "kills(red, *) >= 2");
  EXPECT_EQ(s.expectations[4].stat, StatKind::DamageDealt);
  EXPECT_EQ(s.expectations[4].text, "damage_dealt(*, *) >= 100");
  EXPECT_EQ(s.expectations[5].stat, StatKind::DamageTaken);
  EXPECT_EQ(s.expectations[5].text, "damage_taken(*, truck) <= 50");
  EXPECT_EQ(s.expectations[6].stat, StatKind::ShotsFired);
  EXPECT_EQ(s.expectations[7].stat, StatKind::Alive);
  EXPECT_EQ(s.expectations[7].text, "alive(red, truck) <= 0");
  EXPECT_EQ(s.expectations[8].text, "arrival_rate(blue, soldier) >= 0.5 by 40s");
  for (StatKind k : {StatKind::Kills, StatKind::Losses, StatKind::DamageDealt,
                     StatKind::DamageTaken, StatKind::ShotsFired, StatKind::Alive}) {
    EXPECT_FALSE(toString(k).empty());
    EXPECT_NE(toString(k), "?");
  }
  EXPECT_EQ(toString(StatKind::DamageDealt), "damage_dealt");
}

TEST(BattleParse, OutcomeExpectationErrors) {
  expectError(battle("expectations:\n  - losses: {team: blue, at_most: 3, at_least: 1}\n"),
              "losses needs exactly one of 'at_most' and 'at_least'", "losses");
  expectError(battle("expectations:\n  - kills: {team: blue}\n"),
              "kills needs exactly one of 'at_most' and 'at_least'", "kills");
  expectError(battle("expectations:\n  - winner: green\n"),
              "unknown team 'green' in winner (known: blue, red; or none)", "green");
  expectError(battle("expectations:\n  - alive: {team: blue, at_most: -1}\n"),
              "at_most must be between 0 and", "-1");
  expectError(battle("expectations:\n  - casualties: {team: blue, at_most: 1}\n"),
              "unknown expectation 'casualties' (expected arrival_rate, arrival_time, max_stuck, "
              "winner, delay, max_wait, max_deadlocks, kills, losses, damage_dealt, damage_taken, "
              "shots_fired or alive)",
              "casualties");
}

TEST(BattleParse, NoneIsNotATeamName) {
  std::string text = battle("");
  text.replace(text.find("teams: [blue, red]"), 18, "teams: [blue, none]");
  expectError(text, "'none' cannot name a team", "teams:");
}

}  // namespace
}  // namespace warpath::engine
