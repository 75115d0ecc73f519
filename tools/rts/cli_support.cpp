#include "rts/cli_support.h"

#include <charconv>

#include "pathing/map_io.h"

namespace warpath::tools {

std::optional<int> parseInt(std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

pathing::Cell parseCell(std::string_view text, std::string_view option) {
  const std::size_t comma = text.find(',');
  if (comma != std::string_view::npos) {
    const auto x = parseInt(text.substr(0, comma));
    const auto y = parseInt(text.substr(comma + 1));
    if (x && y) return {*x, *y};
  }
  throw BadInput{std::string(option) + ": expected X,Y (column,row), got '" + std::string(text) +
                 "'"};
}

pathing::GridMap loadMapOrThrow(const std::string& file) {
  auto loaded = pathing::loadMap(file);
  if (!loaded) throw BadInput{loaded.error().describe()};
  return std::move(loaded).value();
}

}  // namespace warpath::tools
