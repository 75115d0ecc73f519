#pragma once
// A small, fast, fully specified PRNG (SplitMix64). The standard distributions are
// implementation-defined, so everything that must be reproducible draws from this instead.

#include <cstdint>

namespace warpath::pathing {

class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) : state_(seed) {}

  constexpr std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, bound) for bound >= 1 (Lemire's multiply-shift; bias < 2^-32 for our sizes).
  constexpr std::uint32_t below(std::uint32_t bound) {
    return static_cast<std::uint32_t>(((next() >> 32) * bound) >> 32);
  }
  // Uniform in [lo, hi], inclusive.
  constexpr int between(int lo, int hi) {
    return lo + static_cast<int>(below(static_cast<std::uint32_t>(hi - lo + 1)));
  }
  // The whole generator state, for the world's state hash.
  constexpr std::uint64_t state() const { return state_; }
  // Uniform in [0, 1).
  constexpr double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

}  // namespace warpath::pathing
