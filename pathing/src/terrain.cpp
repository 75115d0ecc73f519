#include "pathing/terrain.h"

#include <array>
#include <cctype>

namespace warpath::pathing {
namespace {

struct NamedTerrain {
  std::string_view name;
  Terrain terrain;
};
constexpr std::array<NamedTerrain, 5> kNames{{
    {"ground", Terrain::Ground},
    {"swamp", Terrain::Swamp},
    {"trees", Terrain::Trees},
    {"water", Terrain::Water},
    {"blocked", Terrain::Blocked},
}};

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  }
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view terrainName(Terrain t) {
  for (const auto& entry : kNames) {
    if (entry.terrain == t) return entry.name;
  }
  return "unknown";
}

std::optional<Terrain> terrainFromName(std::string_view name) {
  for (const auto& entry : kNames) {
    if (equalsIgnoreCase(name, entry.name)) return entry.terrain;
  }
  return std::nullopt;
}

std::string Capability::toString() const {
  std::string out;
  for (const auto& entry : kNames) {
    if (!allows(entry.terrain)) continue;
    if (!out.empty()) out += ',';
    out += entry.name;
  }
  return out.empty() ? "none" : out;
}

Result<Capability> parseCapability(std::string_view text) {
  Capability result;
  while (true) {
    const std::size_t comma = text.find(',');
    const std::string_view name = trim(text.substr(0, comma));
    const std::optional<Terrain> terrain = terrainFromName(name);
    if (!terrain || !isTraversable(*terrain)) {
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + string chains.
      Error error;
      error.message.assign(name.empty() ? "empty terrain name in capability" : "'");
      if (!name.empty()) {
        error.message.append(name).append(
            "' is not a traversable terrain (ground, swamp, trees, water)");
      }
      return error;
    }
    result = result | Capability::of({*terrain});
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return result;
}

Capability movingAiClassOf(Terrain t) {
  switch (t) {
    case Terrain::Ground:
    case Terrain::Swamp:
      return Capability::of({Terrain::Ground, Terrain::Swamp});
    case Terrain::Water:
      return Capability::of({Terrain::Water});
    case Terrain::Trees:
      return Capability::of({Terrain::Trees});
    case Terrain::Blocked:
      break;
  }
  return {};
}

}  // namespace warpath::pathing
