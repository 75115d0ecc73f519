#pragma once
// Handles instead of pointers (DESIGN.md §6). A handle names a slot and, where slots may be
// reused, the generation of what lives there, so that a stale handle never reaches a newer
// occupant. Every lookup by handle is checked: World::find returns null for a handle it does
// not know, and the phases' internal lookups check index and generation as an invariant.

#include <cstdint>

namespace warpath::engine {

// A unit: an index into the world's unit storage and the generation of the unit in that slot.
// Slots are not reused today (a dead unit keeps its slot for its statistics), so the first and
// only generation is 0; replays record both numbers.
struct UnitId {
  static constexpr std::uint32_t kNone = UINT32_MAX;
  std::uint32_t index = kNone;
  std::uint32_t generation = 0;

  constexpr bool valid() const { return index != kNone; }
  constexpr bool operator==(const UnitId&) const = default;
};

// A physics body (engine/physics.h): an index into the body table. Bodies are never reused, so
// an index names one body for the whole run; a removed body's handle stays readable.
struct BodyId {
  static constexpr std::uint32_t kNone = UINT32_MAX;
  std::uint32_t index = kNone;

  constexpr bool valid() const { return index != kNone; }
  constexpr bool operator==(const BodyId&) const = default;
};

}  // namespace warpath::engine
