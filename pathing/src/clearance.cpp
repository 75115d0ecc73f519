#include "pathing/clearance.h"

#include <algorithm>

namespace warpath::pathing {

ClearanceField ClearanceField::compute(const GridMap& map, Capability capability) {
  ClearanceField field;
  field.capability_ = capability;
  field.width_ = map.width();
  field.height_ = map.height();
  field.values_.assign(map.cellCount(), 0);

  const std::size_t w = static_cast<std::size_t>(map.width());
  const std::span<const Terrain> terrain = map.cells();
  std::vector<Value>& cv = field.values_;
  for (int y = map.height() - 1; y >= 0; --y) {
    const std::size_t row = static_cast<std::size_t>(y) * w;
    const bool lastRow = y == map.height() - 1;
    for (int x = map.width() - 1; x >= 0; --x) {
      const std::size_t i = row + static_cast<std::size_t>(x);
      if (!capability.allows(terrain[i])) continue;
      const bool lastColumn = x == map.width() - 1;
      const Value east = lastColumn ? Value{0} : cv[i + 1];
      const Value south = lastRow ? Value{0} : cv[i + w];
      const Value southEast = (lastRow || lastColumn) ? Value{0} : cv[i + w + 1];
      const Value smallest = std::min({east, south, southEast});
      cv[i] = smallest == 0xFFFF ? smallest : static_cast<Value>(smallest + 1);
    }
  }
  return field;
}

}  // namespace warpath::pathing
