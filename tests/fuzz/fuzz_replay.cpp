// libFuzzer harness: replay files (docs/replays.md) through engine::readReplay, as
// `rts replay info|verify|render` and `rts view` read them.
//
// Before the bytes are written to this process's scratch file, every record's two CRC-32s
// (header and payload) are recomputed, so mutations reach the record decoder instead of
// stopping at the checksum check; a record the file cuts short keeps its stored CRCs. A replay
// that reads is opened for playback (its embedded scenario parsed from the embedded files, its
// command stream checked against the scenario) and, when its map and unit count are small,
// played for a few ticks.
//
// To get the checksummed file for `rts replay info|verify` (a crash artifact is the raw
// input), run the harness on it with WARPATH_FUZZ_WRITE_REPLAY=FILE: the file is written there
// instead of the scratch file and kept.

#include <unistd.h>
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "engine/replay.h"
#include "fuzz_support.h"

namespace {

using namespace warpath;
namespace fs = std::filesystem;

constexpr std::size_t kFileHeader = 12;  // magic, version
constexpr std::size_t kRecordHead = 9;   // kind, payload length, CRC-32 of those 5 bytes
constexpr std::size_t kRecordTail = 4;   // CRC-32 of the payload

// Playback only for scenarios up to this size; a few ticks of each.
constexpr std::int64_t kMaxPlayCells = 128 * 128;
constexpr int kMaxPlayUnits = 300;
constexpr std::int64_t kPlayTicks = 3;

std::uint32_t getU32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i)
    v |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(b[at + i])) << (8 * i);
  return v;
}

void putU32(std::string& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i)
    b[at + i] = static_cast<char>(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::uint32_t crcOf(const std::string& b, std::size_t at, std::size_t size) {
  return static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(b.data() + at), static_cast<uInt>(size)));
}

void fixChecksums(std::string& b) {
  std::size_t at = kFileHeader;
  while (at < b.size() && b.size() - at >= kRecordHead) {
    putU32(b, at + 5, crcOf(b, at, 5));
    const std::size_t length = getU32(b, at + 1);
    if (b.size() - at - kRecordHead < length + kRecordTail) return;  // cut short
    putU32(b, at + kRecordHead + length, crcOf(b, at + kRecordHead, length));
    at += kRecordHead + length + kRecordTail;
  }
}

const fs::path& scratchFile() {
  static const fs::path file = [] {
    if (const char* keep = std::getenv("WARPATH_FUZZ_WRITE_REPLAY"); keep && *keep)
      return fs::path(keep);
    fs::path f = fs::temp_directory_path() /
                 ("warpath-fuzz-replay." + std::to_string(static_cast<long>(::getpid())));
    std::atexit([] {
      std::error_code ignored;
      fs::remove(scratchFile(), ignored);
    });
    return f;
  }();
  return file;
}

bool writeScratch(const std::string& bytes) {
  std::FILE* f = std::fopen(scratchFile().c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  return std::fclose(f) == 0 && ok;
}

void play(const engine::Replay& replay) {
  // The scenario is parsed once to see its size, then again by ReplayPlayback::open.
  const Result<engine::Scenario> scenario = engine::replayScenario(replay);
  if (!scenario.ok()) return;
  const pathing::GridMap& map = scenario.value().grid->map();
  int units = 0;
  for (const engine::GroupSpec& g : scenario.value().groups)
    units += static_cast<int>(g.anchors.size());
  if (std::int64_t{map.width()} * map.height() > kMaxPlayCells || units > kMaxPlayUnits) return;
  Result<engine::ReplayPlayback> playback =
      engine::ReplayPlayback::open(replay, "fuzz.replay");
  if (!playback.ok()) return;
  for (std::int64_t t = 0; t < kPlayTicks && !playback.value().done(); ++t) {
    if (playback.value().step()) break;  // a hash mismatch: expected for mutated replays
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > fuzz::kMaxInput) return -1;
  std::string bytes(fuzz::asText(data, size));
  fixChecksums(bytes);
  if (!writeScratch(bytes)) std::abort();  // the harness's own failure, not the reader's
  const Result<engine::Replay> loaded = engine::readReplay(scratchFile());
  if (!loaded.ok()) {
    if (loaded.error().describe().empty()) std::abort();
    return 0;
  }
  const engine::Replay& replay = loaded.value();
  for (std::size_t i = 1; i < replay.orders.size(); ++i) {
    if (replay.orders[i].tick < replay.orders[i - 1].tick) std::abort();
  }
  for (std::size_t i = 1; i < replay.hashes.size(); ++i) {
    if (replay.hashes[i].tick <= replay.hashes[i - 1].tick) std::abort();
  }
  (void)replay.lastTick();
  play(replay);
  return 0;
}
