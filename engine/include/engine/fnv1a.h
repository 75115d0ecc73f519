#pragma once

#include <cstdint>

namespace warpath::engine {

// Byte-wise FNV-1a, little-endian bytes of each value: the digests of paths and plans and the
// format-2 state hash are defined by it, so their values must never change.
class Fnv1a {
 public:
  void add(std::uint64_t value, int bytes = 8) {
    for (int i = 0; i < bytes; ++i) {
      hash_ ^= (value >> (8 * i)) & 0xFFu;
      hash_ *= 0x100000001B3ull;
    }
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xCBF29CE484222325ull;
};

}  // namespace warpath::engine
