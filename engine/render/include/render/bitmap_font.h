#pragma once
// A 5x7 bitmap font for the HUD (and the CLI's PNG plots), defined in code so pictures need no
// font files.

#include <array>
#include <cstdint>

namespace warpath::render {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = 6;  // [Unit: font pixels] one column of space

// Row r of the glyph has bit (4 - x) set when pixel x is lit. Lower-case letters use the
// upper-case glyphs; characters without a glyph show as '?'.
std::array<std::uint8_t, kGlyphHeight> glyphRows(char c);

}  // namespace warpath::render
