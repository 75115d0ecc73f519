#pragma once
// An RGBA8 image, rows top to bottom, 4 bytes a pixel: what the renderer produces and the PNG
// and GIF writers consume.

#include <cstdint>
#include <vector>

namespace warpath::render {

struct Rgba {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  std::uint8_t a = 255;
  constexpr bool operator==(const Rgba&) const = default;
};

struct Image {
  int width = 0;                     // [Unit: pixels]
  int height = 0;                    // [Unit: pixels]
  std::vector<std::uint8_t> pixels;  // width * height * 4 bytes, RGBA, top row first

  Image() = default;
  // [Limit: width, height >= 0]
  Image(int w, int h, Rgba fill = {})
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4) {
    for (std::size_t i = 0; i < pixels.size(); i += 4) {
      pixels[i] = fill.r;
      pixels[i + 1] = fill.g;
      pixels[i + 2] = fill.b;
      pixels[i + 3] = fill.a;
    }
  }

  // [Limit: 0 <= x < width, 0 <= y < height]
  Rgba at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                           static_cast<std::size_t>(x)) *
                          4;
    return {pixels[i], pixels[i + 1], pixels[i + 2], pixels[i + 3]};
  }
  bool operator==(const Image&) const = default;
};

}  // namespace warpath::render
