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

CellRect ClearanceField::update(const GridMap& map, CellRect area) {
  // A cell's value depends on its east, south and south-east neighbours only, so a change
  // spreads up and left; rows are redone from the area's bottom up, each from the right end of
  // what may differ leftward until a value outside that span comes out unchanged.
  const int w = width_;
  const std::size_t stride = static_cast<std::size_t>(w);
  const std::span<const Terrain> terrain = map.cells();
  int minX = w;
  int maxX = -1;
  int minY = height_;
  int maxY = -1;
  int belowLo = 0;  // columns that changed in the row below: [belowLo, belowHi]
  int belowHi = -1;
  for (int y = area.y + area.height - 1; y >= 0; --y) {
    const bool inArea = y >= area.y;
    int lo = w;
    int hi = -1;
    if (inArea) {
      lo = area.x;
      hi = area.x + area.width - 1;
    }
    if (belowHi >= 0) {
      lo = std::min(lo, std::max(0, belowLo - 1));
      hi = std::max(hi, belowHi);
    }
    if (hi < 0) break;  // nothing below changed and the area is passed
    const std::size_t row = static_cast<std::size_t>(y) * stride;
    const bool lastRow = y == height_ - 1;
    int changedLo = w;
    int changedHi = -1;
    for (int x = hi; x >= 0; --x) {
      const std::size_t i = row + static_cast<std::size_t>(x);
      Value v = 0;
      if (capability_.allows(terrain[i])) {
        const bool lastColumn = x == w - 1;
        const Value east = lastColumn ? Value{0} : values_[i + 1];
        const Value south = lastRow ? Value{0} : values_[i + stride];
        const Value southEast = (lastRow || lastColumn) ? Value{0} : values_[i + stride + 1];
        const Value smallest = std::min({east, south, southEast});
        v = smallest == 0xFFFF ? smallest : static_cast<Value>(smallest + 1);
      }
      if (v != values_[i]) {
        values_[i] = v;
        changedLo = x;
        changedHi = std::max(changedHi, x);
      } else if (x < lo) {
        break;  // left of what may differ, and unchanged: the rest of the row is too
      }
    }
    belowLo = changedLo;
    belowHi = changedHi;
    if (changedHi >= 0) {
      minX = std::min(minX, changedLo);
      maxX = std::max(maxX, changedHi);
      minY = std::min(minY, y);
      maxY = std::max(maxY, y);
    } else if (!inArea) {
      break;
    }
  }
  if (maxX < 0) return {area.x, area.y, 0, 0};
  return {minX, minY, maxX - minX + 1, maxY - minY + 1};
}

}  // namespace warpath::pathing
