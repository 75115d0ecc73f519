#include "pathing/map_io.h"

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <ostream>
#include <system_error>
#include <tuple>
#include <utility>

#include "pathing/file_read.h"

namespace warpath::pathing {
namespace {

// Largest accepted width or height [Unit: cells]. Bounds what a header can make us
// allocate; the largest MovingAI maps are far smaller.
constexpr int kMaxDimension = 1 << 15;

// Longest piece of a line quoted in a message; whole 512-character rows would drown it.
constexpr std::size_t kMaxExcerpt = 40;

constexpr std::array<std::optional<Terrain>, 256> makeCharTable() {
  std::array<std::optional<Terrain>, 256> table{};
  table['.'] = Terrain::Ground;
  table['G'] = Terrain::Ground;
  table['S'] = Terrain::Swamp;
  table['T'] = Terrain::Trees;
  table['W'] = Terrain::Water;
  table['@'] = Terrain::Blocked;
  table['O'] = Terrain::Blocked;
  return table;
}
constexpr std::array<std::optional<Terrain>, 256> kCharTerrain = makeCharTable();

// Splits text into lines without copying; strips the '\r' of CRLF files. A final line
// without '\n' still counts; a final '\n' does not start another line.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : rest_(text) {}

  bool next(std::string_view& line) {
    if (rest_.empty()) return false;
    const std::size_t newline = rest_.find('\n');
    line = rest_.substr(0, newline);
    rest_ = newline == std::string_view::npos ? std::string_view{} : rest_.substr(newline + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++lineNumber_;
    return true;
  }
  // 1-based number of the line last returned; 0 before the first.
  int lineNumber() const { return lineNumber_; }

 private:
  std::string_view rest_;
  int lineNumber_ = 0;
};

// Locale-independent, unlike std::isspace.
constexpr bool isBlankChar(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

bool isBlank(std::string_view s) {
  for (char c : s) {
    if (!isBlankChar(c)) return false;
  }
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isBlankChar(s.front()))
    s.remove_prefix(1);
  while (!s.empty() && isBlankChar(s.back()))
    s.remove_suffix(1);
  return s;
}

// "key value" -> {"key", "value"}; the value is trimmed and may be empty.
std::pair<std::string_view, std::string_view> splitKey(std::string_view trimmed) {
  std::size_t end = 0;
  while (end < trimmed.size() && !isBlankChar(trimmed[end]))
    ++end;
  return {trimmed.substr(0, end), trim(trimmed.substr(end))};
}

// Joins the parts of a message. Chains of operator+ on temporaries would do as well, but
// trip a false -Wrestrict in GCC 12 at -O3.
std::string concat(std::initializer_list<std::string_view> parts) {
  std::size_t size = 0;
  for (std::string_view part : parts)
    size += part.size();
  std::string out;
  out.reserve(size);
  for (std::string_view part : parts)
    out.append(part);
  return out;
}

template <class Integer>
std::string str(Integer n) {
  return std::to_string(n);
}

// Text quoted in a message: shortened, control bytes shown as '?'.
std::string excerpt(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, kMaxExcerpt)) {
    const auto u = static_cast<unsigned char>(c);
    out += u < 0x20 || u >= 0x7F ? '?' : c;
  }
  if (s.size() > kMaxExcerpt) out += "...";
  return out;
}

std::string quoted(std::string_view s) {
  return concat({"'", excerpt(s), "'"});
}

std::string describeChar(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x21 && u < 0x7F) return std::string{'\'', c, '\''};
  constexpr std::string_view kHex = "0123456789abcdef";
  if (u == ' ') return "' ' (space)";
  return concat({"byte 0x", kHex.substr(u >> 4, 1), kHex.substr(u & 0xF, 1)});
}

enum class NumberStatus { Ok, Invalid, OutOfRange };

// The whole text must be the number: "12abc", "", " 12" and "+12" are invalid.
NumberStatus parseInt(std::string_view text, int& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  if (ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
  if (ec != std::errc{} || ptr != end) return NumberStatus::Invalid;
  return NumberStatus::Ok;
}

NumberStatus parseDouble(std::string_view text, double& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  if (ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
  if (ec != std::errc{} || ptr != end) return NumberStatus::Invalid;
  return NumberStatus::Ok;
}

// A map width or height in [1, kMaxDimension]. Returns an error message, empty when fine.
std::string parseDimension(std::string_view name, std::string_view text, int& out) {
  if (text.empty()) return concat({"missing value after '", name, "'"});
  const NumberStatus status = parseInt(text, out);
  const bool negative = text.front() == '-';
  if (status == NumberStatus::Invalid || negative || (status == NumberStatus::Ok && out <= 0)) {
    return concat({name, " must be a positive integer, got ", quoted(text)});
  }
  if (status == NumberStatus::OutOfRange || out > kMaxDimension) {
    return concat({name, " ", excerpt(text), " is too large (maximum ", str(kMaxDimension), ")"});
  }
  return {};
}

// Reads everything left in the stream at once: splitting lines in memory is much faster
// than extracting them from the stream one by one. False on a read error.
bool readAll(std::istream& in, std::string& text) {
  std::array<char, 1 << 16> buffer;
  while (true) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    text.append(buffer.data(), static_cast<std::size_t>(in.gcount()));
    if (!in) break;
  }
  return !in.bad();
}

// Editors on Windows may prepend a UTF-8 byte-order mark.
std::string_view withoutBom(std::string_view text) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  return text;
}

std::string systemReason(int error) {
  return error != 0 ? concat({": ", std::generic_category().message(error)}) : std::string{};
}

class ErrorMaker {
 public:
  explicit ErrorMaker(std::string_view source) : source_(source) {}
  Error operator()(int line, std::string message) const {
    return Error{std::string(source_), line, 0, std::move(message)};
  }

 private:
  std::string_view source_;
};

}  // namespace

// The canonical character; '?' for a terrain the format cannot express, so that reading
// the file back fails loudly instead of turning it into something else.
char mapChar(Terrain t) {
  switch (t) {
    case Terrain::Ground:
      return '.';
    case Terrain::Swamp:
      return 'S';
    case Terrain::Trees:
      return 'T';
    case Terrain::Water:
      return 'W';
    case Terrain::Blocked:
      return '@';
  }
  return '?';
}

Result<GridMap> parseMap(std::istream& in, std::string_view sourceName) {
  std::string text;
  if (!readAll(in, text)) return ErrorMaker(sourceName)(0, "read error");
  return parseMap(std::string_view(text), sourceName);
}

Result<GridMap> parseMap(std::string_view text, std::string_view sourceName) {
  const ErrorMaker error(sourceName);
  LineReader lines(withoutBom(text));
  std::string_view line;

  // Header: type, height and width in any order (blank lines allowed), then "map".
  bool typeSeen = false;
  std::optional<int> height;
  std::optional<int> width;
  int mapLine = 0;
  while (mapLine == 0 && lines.next(line)) {
    const std::string_view trimmed = trim(line);
    if (trimmed.empty()) continue;
    const auto [key, value] = splitKey(trimmed);
    const int at = lines.lineNumber();
    if (key == "type") {
      if (typeSeen) return error(at, "duplicate 'type' line in header");
      if (value != "octile") {
        return error(
            at, concat({"unsupported map type ", quoted(value), " (only 'octile' is supported)"}));
      }
      typeSeen = true;
    } else if (key == "height" || key == "width") {
      std::optional<int>& slot = key == "height" ? height : width;
      if (slot) return error(at, concat({"duplicate '", key, "' line in header"}));
      int parsed = 0;
      if (std::string problem = parseDimension(key, value, parsed); !problem.empty()) {
        return error(at, std::move(problem));
      }
      slot = parsed;
    } else if (key == "map") {
      if (!value.empty())
        return error(at, concat({"unexpected text after 'map': ", quoted(value)}));
      mapLine = at;
    } else if (!typeSeen && !height && !width) {
      return error(at,
                   concat({"missing map header: expected 'type octile', found ", quoted(trimmed)}));
    } else if (typeSeen && height && width) {
      return error(at, concat({"missing 'map' line after the header, found ", quoted(trimmed)}));
    } else {
      return error(at, concat({"unexpected line in map header: ", quoted(trimmed),
                               " (expected 'type', 'height', 'width' or 'map')"}));
    }
  }
  // Problems noticed at the end of the file point at the line after the last one.
  const int where = mapLine != 0 ? mapLine : lines.lineNumber() + 1;
  if (mapLine == 0 && !typeSeen && !height && !width) {
    return error(where, "empty file: expected a map header starting with 'type octile'");
  }
  if (!typeSeen) return error(where, "missing 'type octile' line in header");
  if (!height) return error(where, "missing 'height' line in header");
  if (!width) return error(where, "missing 'width' line in header");
  if (mapLine == 0) return error(where, "missing 'map' line after the header");

  // Validate every row before allocating, so a bogus header cannot make us allocate a
  // huge grid for a short file.
  const int rows = *height;
  const int columns = *width;
  std::vector<std::string_view> rowText;
  rowText.reserve(static_cast<std::size_t>(rows));
  for (int y = 0; y < rows; ++y) {
    const std::string expectedRows = concat({"expected ", str(rows), " rows, found ", str(y)});
    if (!lines.next(line)) return error(lines.lineNumber() + 1, expectedRows);
    const int at = lines.lineNumber();
    if (line.size() != static_cast<std::size_t>(columns)) {
      // Trailing blank lines where rows should be mean the rows are missing, not short.
      LineReader rest = lines;
      std::string_view later;
      bool onlyBlanksFollow = isBlank(line);
      while (onlyBlanksFollow && rest.next(later))
        onlyBlanksFollow = isBlank(later);
      if (onlyBlanksFollow) return error(at, expectedRows);
      return error(at, concat({"row y=", str(y), " has ", str(line.size()),
                               " characters, expected ", str(columns), ": ", quoted(line)}));
    }
    for (std::size_t x = 0; x < line.size(); ++x) {
      if (!kCharTerrain[static_cast<unsigned char>(line[x])]) {
        return error(at, concat({"unknown map character ", describeChar(line[x]), " at x=", str(x),
                                 " (column ", str(x + 1), ") of row y=", str(y)}));
      }
    }
    rowText.push_back(line);
  }
  while (lines.next(line)) {
    if (!isBlank(line)) {
      return error(lines.lineNumber(),
                   concat({"extra data after the ", str(rows), " map rows: ", quoted(line)}));
    }
  }

  GridMap map(columns, rows);
  for (int y = 0; y < rows; ++y) {
    const std::string_view row = rowText[static_cast<std::size_t>(y)];
    for (int x = 0; x < columns; ++x) {
      map.set({x, y}, *kCharTerrain[static_cast<unsigned char>(row[static_cast<std::size_t>(x)])]);
    }
  }
  return map;
}

Result<GridMap> loadMap(const std::filesystem::path& file) {
  const Result<std::string> text = readFileCapped(file, kMapFileLimit);
  if (!text) return text.error();
  return parseMap(std::string_view(text.value()), file.string());
}

void writeMap(const GridMap& map, std::ostream& out) {
  // std::to_string, not operator<<, so an imbued locale cannot add digit separators.
  out << "type octile\nheight " << std::to_string(map.height()) << "\nwidth "
      << std::to_string(map.width()) << "\nmap\n";
  std::string row(static_cast<std::size_t>(map.width()) + 1, '\n');
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      row[static_cast<std::size_t>(x)] = mapChar(map.at({x, y}));
    }
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
}

Status saveMap(const GridMap& map, const std::filesystem::path& file) {
  errno = 0;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) {
    return Error{"", 0, 0,
                 concat({"cannot open '", file.string(), "' for writing", systemReason(errno)})};
  }
  writeMap(map, out);
  errno = 0;
  out.close();
  if (!out)
    return Error{"", 0, 0, concat({"cannot write '", file.string(), "'", systemReason(errno)})};
  return Status::success();
}

Result<std::vector<ScenQuery>> parseScen(std::istream& in, std::string_view sourceName) {
  std::string text;
  if (!readAll(in, text)) return ErrorMaker(sourceName)(0, "read error");
  return parseScen(std::string_view(text), sourceName);
}

Result<std::vector<ScenQuery>> parseScen(std::string_view text, std::string_view sourceName) {
  const ErrorMaker error(sourceName);
  LineReader lines(withoutBom(text));
  std::string_view line;

  // The first non-blank line is the version: "version 1", "version 1.0", any spelling of 1.
  bool versionSeen = false;
  while (!versionSeen && lines.next(line)) {
    const std::string_view trimmed = trim(line);
    if (trimmed.empty()) continue;
    const auto [key, value] = splitKey(trimmed);
    const int at = lines.lineNumber();
    if (key != "version") {
      return error(
          at, concat({"missing 'version' line: expected 'version 1', found ", quoted(trimmed)}));
    }
    if (value.empty()) return error(at, "missing version number after 'version'");
    double version = 0.0;
    if (parseDouble(value, version) != NumberStatus::Ok || version != 1.0) {
      return error(at, concat({"unsupported scenario version ", quoted(value),
                               " (only version 1 is supported)"}));
    }
    versionSeen = true;
  }
  if (!versionSeen) return error(lines.lineNumber() + 1, "empty file: expected 'version 1'");

  constexpr std::size_t kFields = 9;
  constexpr std::array<std::string_view, kFields> kNames = {
      "bucket",  "map",    "map width", "map height",    "start x",
      "start y", "goal x", "goal y",    "optimal length"};

  std::vector<ScenQuery> queries;
  while (lines.next(line)) {
    if (isBlank(line)) continue;
    const int at = lines.lineNumber();

    // Fields are separated by runs of tabs or spaces ("version 1" files use tabs).
    std::array<std::string_view, kFields> fields;
    std::size_t count = 0;
    for (std::size_t i = 0; i < line.size();) {
      if (isBlankChar(line[i])) {
        ++i;
        continue;
      }
      std::size_t end = i;
      while (end < line.size() && !isBlankChar(line[end]))
        ++end;
      if (count < kFields) fields[count] = line.substr(i, end - i);
      ++count;
      i = end;
    }
    if (count != kFields) {
      return error(at, concat({"expected 9 fields (bucket, map, map width, map height, start x, "
                               "start y, goal x, goal y, optimal length), found ",
                               str(count)}));
    }

    ScenQuery query;
    query.line = at;
    query.mapName = std::string(fields[1]);
    const std::array<std::pair<std::size_t, int*>, 5> integers = {{{0, &query.bucket},
                                                                   {4, &query.start.x},
                                                                   {5, &query.start.y},
                                                                   {6, &query.goal.x},
                                                                   {7, &query.goal.y}}};
    for (const auto& [index, target] : integers) {
      const std::string_view name = kNames[index];
      switch (parseInt(fields[index], *target)) {
        case NumberStatus::Ok:
          break;
        case NumberStatus::Invalid:
          return error(at, concat({name, " must be an integer, got ", quoted(fields[index])}));
        case NumberStatus::OutOfRange:
          return error(at, concat({name, " is out of range: ", quoted(fields[index])}));
      }
    }
    for (const auto& [index, target] : {std::pair{std::size_t{2}, &query.mapWidth},
                                        std::pair{std::size_t{3}, &query.mapHeight}}) {
      if (std::string problem = parseDimension(kNames[index], fields[index], *target);
          !problem.empty()) {
        return error(at, std::move(problem));
      }
    }

    // Coordinates must lie inside the map the line itself declares.
    const std::array<std::tuple<std::size_t, int, int, const char*>, 4> coordinates = {{
        {4, query.start.x, query.mapWidth, "map width"},
        {5, query.start.y, query.mapHeight, "map height"},
        {6, query.goal.x, query.mapWidth, "map width"},
        {7, query.goal.y, query.mapHeight, "map height"},
    }};
    for (const auto& [index, value, limit, limitName] : coordinates) {
      if (value < 0 || value >= limit) {
        return error(at, concat({kNames[index], " ", str(value), " is outside 0..", str(limit - 1),
                                 " (", limitName, " ", str(limit), ")"}));
      }
    }

    const std::string_view lengthText = fields[8];
    switch (parseDouble(lengthText, query.optimalLength)) {
      case NumberStatus::Ok:
        break;
      case NumberStatus::Invalid:
        return error(at, concat({"optimal length must be a number, got ", quoted(lengthText)}));
      case NumberStatus::OutOfRange:
        return error(at, concat({"optimal length is out of range: ", quoted(lengthText)}));
    }
    if (!std::isfinite(query.optimalLength)) {
      return error(at, concat({"optimal length must be finite, got ", quoted(lengthText)}));
    }
    if (query.optimalLength < 0.0) {
      return error(at, concat({"optimal length must not be negative, got ", quoted(lengthText)}));
    }
    queries.push_back(std::move(query));
  }
  return queries;
}

Result<std::vector<ScenQuery>> loadScen(const std::filesystem::path& file) {
  const Result<std::string> text = readFileCapped(file, kScenFileLimit);
  if (!text) return text.error();
  return parseScen(std::string_view(text.value()), file.string());
}

Result<TerrainCosts> parseCostTable(std::string_view text, std::string_view sourceName) {
  const ErrorMaker error(sourceName);
  LineReader lines(withoutBom(text));
  std::string_view line;
  TerrainCosts costs;
  std::array<int, kTraversableTerrainSlots> setOn{};  // the line that set each terrain's cost
  bool any = false;
  while (lines.next(line)) {
    const std::string_view trimmed = trim(line);
    if (trimmed.empty()) continue;
    const int at = lines.lineNumber();
    const auto [key, value] = splitKey(trimmed);
    if (key.size() != 1) {
      return error(at, concat({"expected one map character then its cost, found ", quoted(key)}));
    }
    const std::optional<Terrain> terrain = kCharTerrain[static_cast<unsigned char>(key[0])];
    if (!terrain) return error(at, concat({"unknown map character ", quoted(key)}));
    if (value.empty()) return error(at, concat({"missing cost after ", quoted(key)}));
    double cost = 0.0;
    if (parseDouble(value, cost) != NumberStatus::Ok || !(cost >= 0.0)) {
      return error(
          at, concat({"cost of ", quoted(key), " must be a number >= 0, found ", quoted(value)}));
    }
    any = true;
    if (!isTraversable(*terrain)) {
      if (cost != 0.0) {
        return error(at, concat({quoted(key), " is blocked terrain: its cost must be 0, found ",
                                 quoted(value)}));
      }
      continue;
    }
    const auto slot = static_cast<std::size_t>(*terrain);
    if (setOn[slot] != 0 && costs.perCell[slot] != cost) {
      return error(
          at, concat({quoted(key), " is ", std::string(terrainName(*terrain)), ", whose cost line ",
                      str(setOn[slot]), " already set to ", str(costs.perCell[slot])}));
    }
    costs.perCell[slot] = cost;
    setOn[slot] = at;
  }
  if (!any) return error(lines.lineNumber(), "empty cost table: expected lines 'CHARACTER COST'");
  return costs;
}

Result<TerrainCosts> loadCostTable(const std::filesystem::path& file) {
  const Result<std::string> text = readFileCapped(file, kScenFileLimit);
  if (!text) return text.error();
  return parseCostTable(std::string_view(text.value()), file.string());
}

Status checkScenAgainstMap(const std::vector<ScenQuery>& queries, const GridMap& map,
                           std::string_view scenName) {
  const auto size = [](int w, int h) { return concat({str(w), "x", str(h)}); };
  const std::string mapSize = size(map.width(), map.height());
  for (const ScenQuery& q : queries) {
    const auto fail = [&](std::string message) {
      return Error{std::string(scenName), q.line, 0, std::move(message)};
    };
    if (q.mapWidth != map.width() || q.mapHeight != map.height()) {
      return fail(concat(
          {"query declares a ", size(q.mapWidth, q.mapHeight), " map but the map is ", mapSize}));
    }
    for (const auto& [what, cell] : {std::pair{"start", q.start}, std::pair{"goal", q.goal}}) {
      if (!map.contains(cell)) {
        return fail(concat(
            {what, " (", str(cell.x), ", ", str(cell.y), ") is outside the ", mapSize, " map"}));
      }
    }
  }
  return Status::success();
}

}  // namespace warpath::pathing
