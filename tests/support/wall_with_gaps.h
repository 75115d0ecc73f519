#pragma once
// The map the congestion and level tests route crowds on: open ground cut by a wall with a
// narrow and a wider gap.

#include <gtest/gtest.h>

#include <string>

#include "pathing/grid_map.h"
#include "pathing/map_io.h"

namespace warpath::testing {

// width x height: a wall across columns wallX to wallX + 3 with a gap 2 cells wide (rows 6-7)
// and one 3 wide (rows wideGapTop to wideGapTop + 2).
inline pathing::GridMap wallWithTwoGaps(int width, int height, int wallX, int wideGapTop) {
  std::string text = "type octile\nheight " + std::to_string(height) + "\nwidth " +
                     std::to_string(width) + "\nmap\n";
  for (int y = 0; y < height; ++y) {
    const bool gap = y == 6 || y == 7 || (y >= wideGapTop && y <= wideGapTop + 2);
    std::string row(static_cast<std::size_t>(width), '.');
    for (int x = wallX; x <= wallX + 3; ++x)
      if (!gap) row[static_cast<std::size_t>(x)] = '@';
    text += row + "\n";
  }
  auto map = pathing::parseMap(text, "inline");
  EXPECT_TRUE(map.ok());
  return map.value();
}

}  // namespace warpath::testing
