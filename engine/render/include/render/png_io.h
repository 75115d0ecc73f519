#pragma once
// PNG frames through libpng. Frames are written as 8-bit RGB (alpha dropped: frames are
// opaque) with fast settings by default: no row filters and zlib level 1, which on flat-coloured
// frames costs a fraction of the default settings' time for files ~1.5x larger.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "pathing/error.h"
#include "render/image.h"

namespace warpath::render {

struct PngOptions {
  int compressionLevel = 1;  // [Limit: 0..9] zlib level
  bool filterRows = false;   // libpng's adaptive row filters: smaller files, slower
};

// The PNG file's bytes. Fails on an empty image.
Result<std::vector<std::uint8_t>> encodePng(const Image& image, const PngOptions& options = {});
// Writes `bytes` to `file` (replacing it); fails naming the file when it cannot be written.
Status writeFile(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes);
Status writePng(const std::filesystem::path& file, const Image& image,
                const PngOptions& options = {});
// Any PNG libpng reads, converted to RGBA8: at most kPngFileLimit bytes, at most 8192x8192.
Result<Image> readPng(const std::filesystem::path& file);

// "frame_000123.png": the name of tick `tick`'s frame, zero-padded to six digits.
std::string frameFileName(std::int64_t tick);

}  // namespace warpath::render
