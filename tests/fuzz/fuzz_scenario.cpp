// libFuzzer harness: a scenario YAML and the files it names, through
// engine::parseScenario(text, path, FileReader) as `rts run` and replay playback call it.
//
// Input: the scenario text, then any number of files, each introduced by a line "==> NAME":
//
//   name: fuzz
//   map: ../assets/maps/pass.map
//   catalogue: ../assets/units.yaml
//   ...
//   ==> pass.map
//   type octile
//   ...
//   ==> units.yaml
//   unit_types: ...
//
// The scenario is read as /fuzz/scenarios/fuzz.yaml. A file it asks for gets the first unused
// section whose NAME is the requested file's name, else the next unused section in order (so a
// mutated file name still finds contents), else nothing ("not found"). Nothing is read from
// disk. With WARPATH_FUZZ_WRITE_SCENARIO=DIR, the scenario and each file handed out are also
// written under DIR (DIR/scenarios/fuzz.yaml, files at the paths they were asked for), so an
// input reproduces with `rts run DIR/scenarios/fuzz.yaml`. A scenario that loads is checked for
// what the loader promises: every unit placed where its type can stand, inside its spawn area, no
// more than the group's count.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scenario.h"
#include "fuzz_support.h"

namespace {

using namespace warpath;

struct Section {
  std::string_view name;
  std::string_view contents;
  bool used = false;
};

constexpr std::string_view kHeader = "\n==> ";
constexpr std::string_view kScenarioPath = "/fuzz/scenarios/fuzz.yaml";

// WARPATH_FUZZ_WRITE_SCENARIO: writes `contents` as `file` (a path under /fuzz) under that
// folder; paths that would leave it are skipped.
void writeOut(const std::filesystem::path& file, std::string_view contents) {
  static const char* const dir = std::getenv("WARPATH_FUZZ_WRITE_SCENARIO");
  if (!dir || !*dir) return;
  namespace fs = std::filesystem;
  const fs::path relative = file.lexically_normal().lexically_relative("/fuzz");
  if (relative.empty() || *relative.begin() == "..") return;
  const fs::path target = fs::path(dir) / relative;
  std::error_code ignored;
  fs::create_directories(target.parent_path(), ignored);
  std::ofstream(target, std::ios::binary) << contents;
}

// Splits the input into the scenario text (returned) and the file sections.
std::string_view split(std::string_view input, std::vector<Section>& sections) {
  std::size_t at = input.find(kHeader);
  const std::string_view scenario = input.substr(0, at);
  while (at != std::string_view::npos) {
    const std::size_t nameAt = at + kHeader.size();
    const std::size_t eol = input.find('\n', nameAt);
    const std::size_t next = eol == std::string_view::npos ? eol : input.find(kHeader, eol);
    Section s;
    s.name = input.substr(nameAt, (eol == std::string_view::npos ? input.size() : eol) - nameAt);
    if (eol != std::string_view::npos) {
      const std::size_t begin = eol + 1;
      s.contents =
          input.substr(begin, (next == std::string_view::npos ? input.size() : next + 1) - begin);
    }
    sections.push_back(s);
    at = next;
  }
  return scenario;
}

void checkLoaded(const engine::Scenario& s) {
  const pathing::GridMap& map = s.grid->map();
  for (const engine::GroupSpec& g : s.groups) {
    if (g.type < 0 || static_cast<std::size_t>(g.type) >= s.catalogue.size()) std::abort();
    if (g.team < 0 || static_cast<std::size_t>(g.team) >= s.teams.size()) std::abort();
    if (static_cast<int>(g.anchors.size()) > g.count) std::abort();
    const pathing::Agent agent = s.catalogue[static_cast<std::size_t>(g.type)].agent();
    for (const pathing::Cell& c : g.anchors) {
      if (!map.contains(c) || !s.grid->canStand(agent, c)) std::abort();
      if (c.x < g.spawn.x || c.y < g.spawn.y || c.x >= g.spawn.x + g.spawn.width ||
          c.y >= g.spawn.y + g.spawn.height)
        std::abort();
    }
  }
  for (const engine::VictorySpec& v : s.victory)
    (void)engine::describe(v, s.teams);
  (void)s.durationTicks();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > fuzz::kMaxInput) return -1;
  std::vector<Section> sections;
  const std::string_view text = split(fuzz::asText(data, size), sections);
  const engine::FileReader files =
      [&sections](const std::filesystem::path& file, FileLimit) -> Result<std::string> {
    const std::string name = file.filename().string();
    for (Section& s : sections) {
      if (!s.used && s.name == name) {
        s.used = true;
        writeOut(file, s.contents);
        return std::string(s.contents);
      }
    }
    for (Section& s : sections) {
      if (!s.used) {
        s.used = true;
        writeOut(file, s.contents);
        return std::string(s.contents);
      }
    }
    return Error{file.string(), 0, 0, "no such file"};
  };
  writeOut(kScenarioPath, text);
  const Result<engine::Scenario> loaded =
      engine::parseScenario(text, kScenarioPath, files);
  if (!loaded.ok()) {
    if (loaded.error().describe().empty()) std::abort();
    return 0;
  }
  checkLoaded(loaded.value());
  return 0;
}
