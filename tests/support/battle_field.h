#pragma once
// The small open field the battle tests fight on, as scenario YAML: a 24×12 map of ground and
// two armed types, `vet` (40 hp) and `recruit` (30 hp), carrying the same rifle (10 damage,
// range 5, one shot a second, instant).

#include <string>

namespace warpath::testing {

inline std::string openFieldMap() {
  std::string rows;
  for (int y = 0; y < 12; ++y)
    rows += std::string(y == 0 ? "" : ", ") + "'" + std::string(24, '.') + "'";
  return "map: {rows: [" + rows + "]}\n";
}

inline const char* const kRiflemenTypes =
    "  vet: {size: 1, capability: [ground], speed: 2, hp: 40,\n"
    "        weapon: {kind: rifle, damage: 10, range: 5, cooldown: 1}}\n"
    "  recruit: {size: 1, capability: [ground], speed: 2, hp: 30,\n"
    "            weapon: {kind: rifle, damage: 10, range: 5, cooldown: 1}}\n";

// A skirmish on that field, from `groups:` on: four recruits a side attack-move through each
// other's start; two red vets come in (a reinforcement with an attack order on blue) when red
// is down to two; either side wins by eliminating the other. `triggers` are added to the
// scenario's own.
inline std::string skirmishForces(const std::string& triggers = "") {
  return "groups:\n"
         "  - {name: b, team: blue, type: recruit, count: 4, spawn: {x: 0, y: 3, w: 2, h: 6}}\n"
         "  - {name: r, team: red, type: recruit, count: 4, spawn: {x: 22, y: 3, w: 2, h: 6}}\n"
         "  - {name: r2, team: red, type: vet, count: 2, spawn: {x: 22, y: 0, w: 2, h: 1},\n"
         "     reinforcement: true}\n"
         "orders:\n"
         "  - {at: 0, group: b, order: attack_move, move_to: {x: 20, y: 3, w: 4, h: 6}}\n"
         "  - {at: 0, group: r, order: attack_move, move_to: {x: 0, y: 3, w: 3, h: 6}}\n"
         "triggers:\n"
         "  - {name: help, when: {team_below: {team: red, count: 3}},\n"
         "     do: [{reinforce: r2}, {order: attack, group: r2, target: b}]}\n" +
         triggers + "victory:\n  - eliminate: blue\n  - eliminate: red\n";
}

}  // namespace warpath::testing
