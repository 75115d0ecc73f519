#pragma once
// Terrain kinds and capabilities (the set of terrains an agent may stand on).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "pathing/enum_names.h"
#include "pathing/error.h"

namespace warpath::pathing {

// One byte per cell. Values 0..7 are traversable kinds, so that a capability fits a
// bitmask of 8 bits; Blocked is never traversable. Room remains for Road, Shallows, ...
enum class Terrain : std::uint8_t {
  Ground = 0,
  Swamp = 1,
  Trees = 2,
  Water = 3,
  Blocked = 0xFF,
};

inline constexpr int kTraversableTerrainSlots = 8;

constexpr bool isTraversable(Terrain t) {
  return static_cast<std::uint8_t>(t) < kTraversableTerrainSlots;
}

// Names, in terrain order; the traversable kinds first.
inline constexpr EnumNames<Terrain, 5> kTerrainNames{{{
    {Terrain::Ground, "ground"},
    {Terrain::Swamp, "swamp"},
    {Terrain::Trees, "trees"},
    {Terrain::Water, "water"},
    {Terrain::Blocked, "blocked"},
}}};

// Lower-case name from kTerrainNames ("ground", …, "blocked"; "?" for a value not in it).
std::string_view terrainName(Terrain t);
// kTerrainNames' names, ignoring case.
std::optional<Terrain> terrainFromName(std::string_view name);
// The names of the traversable terrains in kTerrainNames, e.g. "ground, swamp, trees, water":
// what a capability may list.
std::string traversableTerrainNames(std::string_view separator = ", ");

// The set of terrains an agent may stand on, as a bitmask over traversable kinds.
class Capability {
 public:
  constexpr Capability() = default;
  constexpr static Capability fromMask(std::uint8_t mask) { return Capability(mask); }
  constexpr static Capability of(std::initializer_list<Terrain> terrains) {
    std::uint8_t mask = 0;
    for (Terrain t : terrains)
      mask |= bit(t);
    return Capability(mask);
  }

  constexpr std::uint8_t mask() const { return mask_; }
  constexpr bool empty() const { return mask_ == 0; }
  constexpr bool allows(Terrain t) const { return (mask_ & bit(t)) != 0; }
  // True when every terrain of this capability is also in `other` (this ⊆ other).
  constexpr bool isSubsetOf(Capability other) const { return (mask_ & ~other.mask_) == 0; }
  constexpr Capability operator|(Capability other) const {
    return Capability(static_cast<std::uint8_t>(mask_ | other.mask_));
  }
  constexpr bool operator==(const Capability&) const = default;
  constexpr auto operator<=>(const Capability&) const = default;

  // Comma-separated terrain names in terrain order, e.g. "ground,swamp"; "none" if empty.
  std::string toString() const;

 private:
  constexpr explicit Capability(std::uint8_t mask) : mask_(mask) {}
  constexpr static std::uint8_t bit(Terrain t) {
    return static_cast<std::uint8_t>(isTraversable(t) ? (1u << static_cast<unsigned>(t)) : 0u);
  }
  std::uint8_t mask_ = 0;
};

// Parses "ground,swamp" (names, case-insensitive, comma-separated, no duplicates needed).
// Fails (an Error with the message only) on an unknown or empty name.
Result<Capability> parseCapability(std::string_view text);

// The MovingAI benchmark's movement classes: an agent may move only between cells of the
// same class, {Ground, Swamp}, {Water} or {Trees}. Empty for Blocked.
Capability movingAiClassOf(Terrain t);

}  // namespace warpath::pathing
