#pragma once
// Shared by the fuzz harnesses: the input cap and a deterministic source of extra choices
// (agent size, capability, start and goal) drawn from the input itself, so the same input
// always does the same work and a crash reproduces from its file alone.

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace warpath::fuzz {

// Inputs above this are skipped: the parsers' cost is linear in the input and large inputs only
// slow the fuzzer down (libFuzzer's -max_len keeps it well below this anyway).
inline constexpr std::size_t kMaxInput = std::size_t{1} << 20;

// The extra work after a successful parse (searches, grids) only on maps up to this many
// cells, e.g. 256x256. [Unit: cells]
inline constexpr std::int64_t kMaxExtraCells = 256 * 256;

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// SplitMix64 seeded with the input's FNV-1a hash.
class Choices {
 public:
  explicit Choices(std::string_view input) {
    std::uint64_t h = 1469598103934665603ull;
    for (char c : input) {
      h ^= static_cast<std::uint8_t>(c);
      h *= 1099511628211ull;
    }
    state_ = h;
  }
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform enough in [0, n) for n >= 1.
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }

 private:
  std::uint64_t state_ = 0;
};

}  // namespace warpath::fuzz
