#pragma once
// The eight grid moves. Cardinal moves cost 1, diagonal moves √2; a diagonal move needs
// both cardinal two-step alternatives to be legal too (no corner cutting).

#include <array>
#include <cstdint>

namespace warpath::pathing {

inline constexpr double kSqrt2 = 1.4142135623730951;
inline constexpr int kDirectionCount = 8;

struct Direction {
  int dx;
  int dy;
  double cost;
  // For a diagonal, the two cardinal directions it passes between (else -1).
  int cardinalA;
  int cardinalB;
};

// 0..3 cardinal (N, E, S, W), 4..7 diagonal (NE, SE, SW, NW).
inline constexpr std::array<Direction, kDirectionCount> kDirections{{
    {0, -1, 1.0, -1, -1},
    {1, 0, 1.0, -1, -1},
    {0, 1, 1.0, -1, -1},
    {-1, 0, 1.0, -1, -1},
    {1, -1, kSqrt2, 0, 1},
    {1, 1, kSqrt2, 2, 1},
    {-1, 1, kSqrt2, 2, 3},
    {-1, -1, kSqrt2, 0, 3},
}};

constexpr bool isDiagonal(int direction) {
  return direction >= 4;
}

// The direction that undoes `direction` (N <-> S, E <-> W, NE <-> SW, SE <-> NW).
constexpr int oppositeDirection(int direction) {
  return direction < 4 ? (direction + 2) % 4 : 4 + (direction - 2) % 4;
}

// The direction of a single move from (0, 0) to (dx, dy); -1 when (dx, dy) is not one (0, 0
// or any component outside -1..1).
constexpr int directionOf(int dx, int dy) {
  for (int d = 0; d < kDirectionCount; ++d) {
    if (kDirections[static_cast<std::size_t>(d)].dx == dx &&
        kDirections[static_cast<std::size_t>(d)].dy == dy)
      return d;
  }
  return -1;
}

// Octile distance: the exact cost between two cells on an empty grid.
constexpr double octileDistance(int dx, int dy) {
  const int ax = dx < 0 ? -dx : dx;
  const int ay = dy < 0 ? -dy : dy;
  const int lo = ax < ay ? ax : ay;
  const int hi = ax < ay ? ay : ax;
  return static_cast<double>(hi - lo) + kSqrt2 * static_cast<double>(lo);
}

}  // namespace warpath::pathing
