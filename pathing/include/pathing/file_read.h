#pragma once
// The one way the program reads a file (maps, .scen files, scenario and catalogue YAML,
// replays, PNG images): never throws, refuses what is not a regular file, and caps how much it
// reads (checked with stat before reading, and again while reading). Errors are "FILE: problem":
//   FILE: no such file            FILE: is a directory          FILE: not a regular file
//   FILE: cannot read: <reason>   FILE: larger than the 64 MiB limit for maps
// The caps and why they are what they are: docs/scenarios.md ("Limits").

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "pathing/error.h"

namespace warpath {

inline constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

// How much of one kind of file may be read. [Unit: bytes]
struct FileLimit {
  std::uint64_t maxBytes = 0;
  std::string_view kind;  // "maps", as in "larger than the 64 MiB limit for maps"
};

// MovingAI .map files: 64 MiB holds an 8000x8000 map; the largest bundled and shared maps
// (512x512) are 257 KiB, MovingAI's largest (1024x1024 street maps) 1 MiB.
inline constexpr FileLimit kMapFileLimit{64 * kMiB, "maps"};
// MovingAI .scen files: the shared ones are under 100 KiB, MovingAI's largest a few MiB.
inline constexpr FileLimit kScenFileLimit{64 * kMiB, "scen files"};
// Scenario and catalogue YAML: the bundled ones are under 3 KiB. yaml-cpp holds about 450 bytes
// per node, so 256 KiB of the densest YAML (`[1,1,1,...]`, 130,000 nodes) stays near 60 MB;
// inline maps up to about 500x500 cells fit (larger maps belong in a .map file).
inline constexpr FileLimit kYamlFileLimit{256 * 1024, "scenario and catalogue files"};
// Replays embed the scenario, its map and catalogue (at most 64 MiB + 2 x 256 KiB) and add 29
// bytes per recorded state hash and 40 + 8 per unit per order: the bundled battles record
// 0.1-1 MiB; 256 MiB leaves room for hours of a 2,000-unit run hashed every tick.
inline constexpr FileLimit kReplayFileLimit{256 * kMiB, "replays"};
// PNG images read back (golden images in tests, frames): 64 MiB.
inline constexpr FileLimit kPngFileLimit{64 * kMiB, "PNG images"};

// The message of the error for a missing file, for callers that word that case themselves.
inline constexpr std::string_view kNoSuchFile = "no such file";

// A regular file opened for reading, at most `limit.maxBytes` of it. Movable, not copyable.
class CappedFile {
 public:
  // Checks the path with stat (exists, is a regular file, within the limit) and opens it.
  static Result<CappedFile> open(const std::filesystem::path& file, FileLimit limit);

  // The size stat reported when opened. [Unit: bytes]
  std::uint64_t size() const { return size_; }
  // Bytes read so far. [Unit: bytes]
  std::uint64_t offset() const { return offset_; }
  // Appends up to `count` bytes to `out`; fewer only at the end of the file. Fails on a read
  // error, or when reading would pass the limit.
  Result<std::size_t> read(std::string& out, std::size_t count);
  // Everything left, within the limit.
  Status readRest(std::string& out);

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  CappedFile(std::string name, std::unique_ptr<std::FILE, Closer> in, std::uint64_t size,
             FileLimit limit)
      : name_(std::move(name)), in_(std::move(in)), size_(size), limit_(limit) {}
  Error tooLarge() const;

  std::string name_;
  std::unique_ptr<std::FILE, Closer> in_;
  std::uint64_t size_ = 0;
  std::uint64_t offset_ = 0;
  FileLimit limit_;
};

// "64 MiB", "256 KiB" or "100 bytes".
std::string describeSize(std::uint64_t bytes);
// "FILE: larger than the 64 MiB limit for maps".
Error fileTooLarge(const std::string& file, FileLimit limit);

// The whole of a regular file, at most `limit.maxBytes`.
Result<std::string> readFileCapped(const std::filesystem::path& file, FileLimit limit);

}  // namespace warpath
