#pragma once
// Animated GIFs through giflib. Every frame is quantised to one fixed palette (the renderer's
// colours exactly, then a colour cube; see palette.h) by a lookup table, so the same frames
// always give the same file.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "pathing/error.h"
#include "render/image.h"

namespace warpath::render {

// Maps colours to the nearest entry of a palette (squared RGB distance on 5 bits a channel;
// colours equal to an entry map to that entry).
class PaletteQuantizer {
 public:
  explicit PaletteQuantizer(std::span<const Rgba> palette);  // [Limit: 1..256 entries]
  std::uint8_t indexOf(Rgba c) const {
    return lut_[static_cast<std::size_t>((c.r >> 3) << 10 | (c.g >> 3) << 5 | (c.b >> 3))];
  }

 private:
  std::vector<std::uint8_t> lut_;
};

class GifWriter {
 public:
  // Opens `file` for frames of width x height pixels shown `delayCentiseconds` each, looping
  // forever. Fails naming the file when it cannot be created.
  static Result<GifWriter> open(const std::filesystem::path& file, int width, int height,
                                int delayCentiseconds);

  GifWriter(GifWriter&&) noexcept;
  GifWriter& operator=(GifWriter&&) noexcept;
  ~GifWriter();  // closes the file if close() was not called, ignoring errors

  // [Limit: the image has the size given to open()]
  Status addFrame(const Image& image);
  // Finishes the file; further frames fail.
  Status close();
  int frameCount() const;

 private:
  struct Impl;
  explicit GifWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace warpath::render
