#include "pathing/terrain.h"

#include <cctype>

namespace warpath::pathing {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view terrainName(Terrain t) {
  return kTerrainNames.name(t);
}

std::optional<Terrain> terrainFromName(std::string_view name) {
  std::string lower(name);
  for (char& c : lower)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return kTerrainNames.parse(lower);
}

std::string traversableTerrainNames(std::string_view separator) {
  std::string out;
  for (const auto& row : kTerrainNames.rows()) {
    if (!isTraversable(row.value)) continue;
    if (!out.empty()) out.append(separator);
    out.append(row.name);
  }
  return out;
}

std::string Capability::toString() const {
  std::string out;
  for (const auto& row : kTerrainNames.rows()) {
    if (!allows(row.value)) continue;
    if (!out.empty()) out += ',';
    out += row.name;
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
        error.message.append(name).append("' is not a traversable terrain (");
        error.message.append(traversableTerrainNames()).append(")");
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
