#include "rts/cli_support.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "pathing/map_io.h"

namespace warpath::tools {

std::optional<int> parseInt(std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

CLI::Validator wholeNumberIn(std::int64_t lo, std::int64_t hi) {
  const std::string range = std::to_string(lo) + " and " + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        std::int64_t value = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < lo ||
            value > hi)
          return "must be a whole number between " + range + ", got '" + text + "'";
        return {};
      },
      "INT in " + std::to_string(lo) + ".." + std::to_string(hi));
}

CLI::Validator positiveNumberUpTo(double hi) {
  std::ostringstream bound;
  bound << std::fixed << std::setprecision(hi == std::floor(hi) ? 0 : 3) << hi;
  const std::string limit = bound.str();
  return CLI::Validator(
      [hi, limit](std::string& text) -> std::string {
        double value = 0.0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
            !(value > 0.0 && value <= hi))
          return "must be a number greater than 0 and at most " + limit + ", got '" + text + "'";
        return {};
      },
      "NUMBER in (0, " + limit + "]");
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

void prepareOutputPath(const std::string& file, const std::string& option) {
  if (file.empty()) return;
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  std::error_code error;
  if (!parent.empty()) std::filesystem::create_directories(parent, error);
  if (error) {
    throw BadInput{option + ": cannot create the folder '" + parent.string() +
                   "': " + error.message()};
  }
}

pathing::GridMap loadMapOrThrow(const std::string& file) {
  auto loaded = pathing::loadMap(file);
  if (!loaded) throw BadInput{loaded.error().describe()};
  return std::move(loaded).value();
}

}  // namespace warpath::tools
