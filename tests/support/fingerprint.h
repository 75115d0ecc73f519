#pragma once
// A fingerprint of test results, for pins: FNV-1a over 64-bit words and cells, so a change that
// picks another of several equally good answers shows as a different value.

#include <cstdint>

#include "pathing/grid_map.h"

namespace warpath::testing {

struct Fingerprint {
  std::uint64_t value = 14695981039346656037ull;
  void add(std::uint64_t word) {
    for (int i = 0; i < 8; ++i) {
      value ^= (word >> (8 * i)) & 0xFFu;
      value *= 1099511628211ull;
    }
  }
  void add(pathing::Cell c) {
    add(static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.x)) << 32 |
        static_cast<std::uint32_t>(c.y));
  }
};

}  // namespace warpath::testing
