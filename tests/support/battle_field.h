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

}  // namespace warpath::testing
