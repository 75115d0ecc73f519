#pragma once
// Unit handles: an index into the world's unit storage and the generation of the unit that
// lives there, so that a stale handle never reaches a newer unit in a reused slot.

#include <cstdint>

namespace warpath::engine {

struct UnitId {
  static constexpr std::uint32_t kNone = UINT32_MAX;
  std::uint32_t index = kNone;
  std::uint32_t generation = 0;

  constexpr bool valid() const { return index != kNone; }
  constexpr bool operator==(const UnitId&) const = default;
};

}  // namespace warpath::engine
