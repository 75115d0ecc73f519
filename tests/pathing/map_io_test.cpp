#include "pathing/map_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "pathing/file_read.h"

namespace warpath::pathing {
namespace {

namespace fs = std::filesystem;

const fs::path kFixtures = WARPATH_FIXTURES_DIR;

constexpr std::string_view kHeader3x2 = "type octile\nheight 2\nwidth 3\nmap\n";

Result<GridMap> parseMapText(const std::string& text) {
  std::istringstream in(text);
  return parseMap(in, "test.map");
}

Result<std::vector<ScenQuery>> parseScenText(const std::string& text) {
  std::istringstream in(text);
  return parseScen(in, "test.scen");
}

// The error of a parse that must fail; records a test failure if it succeeded.
Error mapError(const std::string& text) {
  Result<GridMap> result = parseMapText(text);
  if (result) {
    ADD_FAILURE() << "parsed although it should not:\n" << text;
    return {};
  }
  EXPECT_EQ(result.error().file, "test.map");
  return result.error();
}

Error scenError(const std::string& text) {
  Result<std::vector<ScenQuery>> result = parseScenText(text);
  if (result) {
    ADD_FAILURE() << "parsed although it should not:\n" << text;
    return {};
  }
  EXPECT_EQ(result.error().file, "test.scen");
  return result.error();
}

std::string mapText(const GridMap& map) {
  std::ostringstream out;
  writeMap(map, out);
  return out.str();
}

GridMap randomMap(int width, int height, unsigned seed) {
  constexpr Terrain kKinds[] = {Terrain::Ground, Terrain::Swamp, Terrain::Trees, Terrain::Water,
                                Terrain::Blocked};
  std::mt19937 rng(seed);
  GridMap map(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      map.set({x, y}, kKinds[rng() % 5]);
  }
  return map;
}

std::string fixture(const char* name) {
  return (kFixtures / name).string();
}

// A unique scratch path per test, so tests may run in parallel processes.
fs::path scratchPath(const std::string& suffix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return fs::path(::testing::TempDir()) /
         ("warpath_" + std::string(info->test_suite_name()) + "_" + info->name() + suffix);
}

// ---------------------------------------------------------------------------------------
// Error

TEST(ErrorTest, DescribeWithAndWithoutLine) {
  EXPECT_EQ((Error{"a.map", 7, 0, "bad row"}).describe(), "a.map:7: bad row");
  EXPECT_EQ((Error{"a.map", 0, 0, "cannot open file"}).describe(), "a.map: cannot open file");
  EXPECT_EQ((Error{"", 3, 0, "bad row"}).describe(), "line 3: bad row");
  EXPECT_EQ((Error{"", 0, 0, "bad"}).describe(), "bad");
  EXPECT_EQ((Error{"s.yaml", 4, 9, "bad key"}).describe(), "s.yaml:4:9: bad key");
}

TEST(ErrorTest, ResultAndStatus) {
  const Result<int> good = 3;
  ASSERT_TRUE(good);
  EXPECT_EQ(good.value(), 3);
  EXPECT_TRUE(good.status());
  const Result<int> bad = Error{"f", 0, 0, "no"};
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().describe(), "f: no");
  EXPECT_EQ(bad.status().error().message, "no");
  EXPECT_TRUE(Status::success().ok());
  const Status failed = Error{"", 0, 0, "broken"};
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().describe(), "broken");
}

// ---------------------------------------------------------------------------------------
// parseMap: valid input

TEST(ParseMapTest, ReadsEveryTerrainCharacter) {
  Result<GridMap> map = parseMapText(
      "type octile\nheight 2\nwidth 4\nmap\n"
      ".GST\n"
      "W@O.\n");
  ASSERT_TRUE(map) << map.error().describe();
  const GridMap& m = map.value();
  EXPECT_EQ(m.width(), 4);
  EXPECT_EQ(m.height(), 2);
  EXPECT_EQ(m.at({0, 0}), Terrain::Ground);
  EXPECT_EQ(m.at({1, 0}), Terrain::Ground);
  EXPECT_EQ(m.at({2, 0}), Terrain::Swamp);
  EXPECT_EQ(m.at({3, 0}), Terrain::Trees);
  EXPECT_EQ(m.at({0, 1}), Terrain::Water);
  EXPECT_EQ(m.at({1, 1}), Terrain::Blocked);
  EXPECT_EQ(m.at({2, 1}), Terrain::Blocked);
  EXPECT_EQ(m.at({3, 1}), Terrain::Ground);
}

TEST(ParseMapTest, XIsColumnAndYIsRow) {
  Result<GridMap> map = parseMapText("type octile\nheight 3\nwidth 2\nmap\n.@\n..\nT.\n");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_EQ(map.value().at({1, 0}), Terrain::Blocked);
  EXPECT_EQ(map.value().at({0, 2}), Terrain::Trees);
}

TEST(ParseMapTest, AcceptsCrlfLineEndings) {
  Result<GridMap> map = parseMapText("type octile\r\nheight 2\r\nwidth 3\r\nmap\r\n.@T\r\nWS.\r\n");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_EQ(map.value(), parseMapText(std::string(kHeader3x2) + ".@T\nWS.\n").value());
}

TEST(ParseMapTest, AcceptsMissingFinalNewline) {
  Result<GridMap> map = parseMapText(std::string(kHeader3x2) + "...\n.@.");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_EQ(map.value().at({1, 1}), Terrain::Blocked);
}

TEST(ParseMapTest, AcceptsHeaderKeysInAnyOrder) {
  for (const char* header :
       {"type octile\nheight 2\nwidth 3\nmap\n", "type octile\nwidth 3\nheight 2\nmap\n",
        "height 2\nwidth 3\ntype octile\nmap\n"}) {
    SCOPED_TRACE(header);
    Result<GridMap> map = parseMapText(std::string(header) + "...\n...\n");
    ASSERT_TRUE(map) << map.error().describe();
    EXPECT_EQ(map.value().width(), 3);
    EXPECT_EQ(map.value().height(), 2);
  }
}

TEST(ParseMapTest, ToleratesBlankLinesAndSpacesInHeader) {
  Result<GridMap> map =
      parseMapText("\ntype   octile  \n\n  height\t2\nwidth 3 \r\n\nmap  \n...\n...\n");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_EQ(map.value().width(), 3);
}

TEST(ParseMapTest, AcceptsTrailingBlankLines) {
  Result<GridMap> map = parseMapText(std::string(kHeader3x2) + "...\n...\n\n  \n\t\r\n\n");
  ASSERT_TRUE(map) << map.error().describe();
}

TEST(ParseMapTest, IgnoresUtf8ByteOrderMark) {
  Result<GridMap> map = parseMapText("\xEF\xBB\xBF" + std::string(kHeader3x2) + "...\n...\n");
  ASSERT_TRUE(map) << map.error().describe();
}

TEST(ParseMapTest, AcceptsLargestDimension) {
  Result<GridMap> map =
      parseMapText("type octile\nheight 1\nwidth 32768\nmap\n" + std::string(32768, '.') + "\n");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_EQ(map.value().width(), 32768);
}

// ---------------------------------------------------------------------------------------
// parseMap: header errors

TEST(ParseMapErrorTest, EmptyInput) {
  for (const char* text : {"", "\n\n", "  \r\n"}) {
    SCOPED_TRACE(text);
    const Error e = mapError(text);
    EXPECT_EQ(e.message, "empty file: expected a map header starting with 'type octile'");
  }
  EXPECT_EQ(mapError("").line, 1);
  EXPECT_EQ(mapError("\n\n").line, 3);
}

TEST(ParseMapErrorTest, MissingHeader) {
  const Error e = mapError("...\n...\n");
  EXPECT_EQ(e.line, 1);
  EXPECT_EQ(e.message, "missing map header: expected 'type octile', found '...'");
}

TEST(ParseMapErrorTest, MissingTypeLine) {
  const Error e = mapError("height 2\nwidth 3\nmap\n...\n...\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.message, "missing 'type octile' line in header");
}

TEST(ParseMapErrorTest, UnsupportedType) {
  const Error e = mapError("type tile\nheight 2\nwidth 3\nmap\n...\n...\n");
  EXPECT_EQ(e.line, 1);
  EXPECT_EQ(e.message, "unsupported map type 'tile' (only 'octile' is supported)");
  EXPECT_EQ(mapError("type\nheight 2\nwidth 3\nmap\n").message,
            "unsupported map type '' (only 'octile' is supported)");
  EXPECT_EQ(mapError("type Octile\n").message,
            "unsupported map type 'Octile' (only 'octile' is supported)");
}

TEST(ParseMapErrorTest, MissingHeightOrWidth) {
  Error e = mapError("type octile\nwidth 3\nmap\n...\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.message, "missing 'height' line in header");
  e = mapError("type octile\nheight 2\nmap\n...\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.message, "missing 'width' line in header");
}

TEST(ParseMapErrorTest, HeaderEndsEarly) {
  // The file ends inside the header: the error points at the line after the last one.
  Error e = mapError("type octile\nheight 2\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.message, "missing 'width' line in header");
  e = mapError("type octile\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.message, "missing 'height' line in header");
}

TEST(ParseMapErrorTest, DuplicateHeaderKey) {
  EXPECT_EQ(mapError("type octile\nheight 2\nheight 2\n").message,
            "duplicate 'height' line in header");
  EXPECT_EQ(mapError("type octile\nwidth 2\nwidth 3\n").message,
            "duplicate 'width' line in header");
  const Error e = mapError("type octile\ntype octile\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.message, "duplicate 'type' line in header");
}

TEST(ParseMapErrorTest, BadDimension) {
  struct Case {
    const char* value;
    const char* message;
  };
  const Case cases[] = {
      {"abc", "height must be a positive integer, got 'abc'"},
      {"12abc", "height must be a positive integer, got '12abc'"},
      {"-3", "height must be a positive integer, got '-3'"},
      {"0", "height must be a positive integer, got '0'"},
      {"+5", "height must be a positive integer, got '+5'"},
      {"2.5", "height must be a positive integer, got '2.5'"},
      {"2 3", "height must be a positive integer, got '2 3'"},
      {"0x10", "height must be a positive integer, got '0x10'"},
      {"-99999999999999999999", "height must be a positive integer, got '-99999999999999999999'"},
      {"32769", "height 32769 is too large (maximum 32768)"},
      {"100000", "height 100000 is too large (maximum 32768)"},
      {"99999999999999999999", "height 99999999999999999999 is too large (maximum 32768)"},
      {"", "missing value after 'height'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.value);
    const Error e = mapError("type octile\nheight " + std::string(c.value) + "\nwidth 3\nmap\n");
    EXPECT_EQ(e.line, 2);
    EXPECT_EQ(e.message, c.message);
  }
  const Error e = mapError("type octile\nheight 2\nwidth x\nmap\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.message, "width must be a positive integer, got 'x'");
}

TEST(ParseMapErrorTest, MissingMapLine) {
  // Rows right after the header.
  Error e = mapError("type octile\nheight 2\nwidth 3\n...\n...\n");
  EXPECT_EQ(e.line, 4);
  EXPECT_EQ(e.message, "missing 'map' line after the header, found '...'");
  // The file ends after the header.
  e = mapError("type octile\nheight 2\nwidth 3\n");
  EXPECT_EQ(e.line, 4);
  EXPECT_EQ(e.message, "missing 'map' line after the header");
}

TEST(ParseMapErrorTest, UnexpectedHeaderLine) {
  const Error e = mapError("type octile\nheight 2\nlength 3\nmap\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.message,
            "unexpected line in map header: 'length 3' (expected 'type', 'height', 'width' or "
            "'map')");
  EXPECT_EQ(mapError("type octile\nheight 2\nwidth 3\nmap please\n").message,
            "unexpected text after 'map': 'please'");
}

// ---------------------------------------------------------------------------------------
// parseMap: row errors

TEST(ParseMapErrorTest, RowTooShortOrTooLong) {
  Error e = mapError(std::string(kHeader3x2) + "...\n..\n");
  EXPECT_EQ(e.line, 6);
  EXPECT_EQ(e.message, "row y=1 has 2 characters, expected 3: '..'");
  e = mapError(std::string(kHeader3x2) + "....\n...\n");
  EXPECT_EQ(e.line, 5);
  EXPECT_EQ(e.message, "row y=0 has 4 characters, expected 3: '....'");
}

TEST(ParseMapErrorTest, TrailingSpaceMakesRowTooLong) {
  // Rows are exact; only '\r' is stripped, so trailing spaces are not silently dropped.
  EXPECT_EQ(mapError(std::string(kHeader3x2) + "... \n...\n").message,
            "row y=0 has 4 characters, expected 3: '... '");
}

TEST(ParseMapErrorTest, LongRowIsQuotedShortened) {
  const Error e = mapError("type octile\nheight 1\nwidth 100\nmap\n" + std::string(99, '.') + "\n");
  EXPECT_EQ(e.message,
            "row y=0 has 99 characters, expected 100: '" + std::string(40, '.') + "...'");
}

TEST(ParseMapErrorTest, BlankLineBetweenRows) {
  const Error e = mapError("type octile\nheight 3\nwidth 3\nmap\n...\n\n...\n");
  EXPECT_EQ(e.line, 6);
  EXPECT_EQ(e.message, "row y=1 has 0 characters, expected 3: ''");
}

TEST(ParseMapErrorTest, FewerRowsThanHeight) {
  Error e = mapError("type octile\nheight 4\nwidth 3\nmap\n...\n...\n");
  EXPECT_EQ(e.line, 7);
  EXPECT_EQ(e.message, "expected 4 rows, found 2");
  // Trailing blank lines are not rows: same message, pointing at the first of them.
  e = mapError("type octile\nheight 4\nwidth 3\nmap\n...\n...\n\n\n");
  EXPECT_EQ(e.line, 7);
  EXPECT_EQ(e.message, "expected 4 rows, found 2");
  e = mapError(std::string(kHeader3x2));
  EXPECT_EQ(e.line, 5);
  EXPECT_EQ(e.message, "expected 2 rows, found 0");
}

TEST(ParseMapErrorTest, UnknownCharacter) {
  Error e = mapError(std::string(kHeader3x2) + "...\n.x.\n");
  EXPECT_EQ(e.line, 6);
  EXPECT_EQ(e.message, "unknown map character 'x' at x=1 (column 2) of row y=1");
  // Lower-case terrain letters are not MovingAI characters.
  EXPECT_EQ(mapError(std::string(kHeader3x2) + "..g\n...\n").message,
            "unknown map character 'g' at x=2 (column 3) of row y=0");
  EXPECT_EQ(mapError(std::string(kHeader3x2) + ". .\n...\n").message,
            "unknown map character ' ' (space) at x=1 (column 2) of row y=0");
  EXPECT_EQ(mapError(std::string(kHeader3x2) + "\t..\n...\n").message,
            "unknown map character byte 0x09 at x=0 (column 1) of row y=0");
  EXPECT_EQ(mapError(std::string(kHeader3x2) + "..\xC3\n...\n").message,
            "unknown map character byte 0xc3 at x=2 (column 3) of row y=0");
  EXPECT_EQ(mapError(std::string(kHeader3x2) + std::string("..\0\n...\n", 8)).message,
            "unknown map character byte 0x00 at x=2 (column 3) of row y=0");
}

TEST(ParseMapErrorTest, ExtraDataAfterRows) {
  Error e = mapError(std::string(kHeader3x2) + "...\n...\n...\n");
  EXPECT_EQ(e.line, 7);
  EXPECT_EQ(e.message, "extra data after the 2 map rows: '...'");
  e = mapError(std::string(kHeader3x2) + "...\n...\n\n\nthe end\n");
  EXPECT_EQ(e.line, 9);
  EXPECT_EQ(e.message, "extra data after the 2 map rows: 'the end'");
}

TEST(ParseMapErrorTest, StreamInFailStateReadsAsEmpty) {
  std::istringstream in(std::string(kHeader3x2) + "...\n...\n");
  in.setstate(std::ios::failbit);
  Result<GridMap> map = parseMap(in, "x.map");
  ASSERT_FALSE(map);
  EXPECT_EQ(map.error().line, 1);
}

// Truncations and random byte changes of a valid map never crash and always give either a
// map or an error with a message and a plausible line.
TEST(ParseMapErrorTest, NeverCrashesOnDamagedInput) {
  const std::string valid = mapText(randomMap(9, 7, 5));
  const int lineCount = 4 + 7 + 3;  // each changed byte may be a new '\n'
  const auto check = [&](const std::string& text) {
    Result<GridMap> map = parseMapText(text);
    if (map) {
      EXPECT_GT(map.value().width(), 0);
      EXPECT_EQ(map.value().cellCount(),
                static_cast<std::size_t>(map.value().width() * map.value().height()));
    } else {
      EXPECT_FALSE(map.error().message.empty());
      EXPECT_GE(map.error().line, 1);
      EXPECT_LE(map.error().line, lineCount + 1) << map.error().describe();
    }
  };
  for (std::size_t n = 0; n <= valid.size(); ++n)
    check(valid.substr(0, n));
  std::mt19937 rng(42);
  for (int i = 0; i < 3000; ++i) {
    std::string text = valid;
    for (int k = 0; k < 3; ++k)
      text[rng() % text.size()] = static_cast<char>(rng() % 256);
    check(text);
  }
}

// ---------------------------------------------------------------------------------------
// writeMap / saveMap / loadMap

TEST(WriteMapTest, WritesCanonicalText) {
  GridMap map(3, 2);
  map.set({1, 0}, Terrain::Swamp);
  map.set({2, 0}, Terrain::Trees);
  map.set({0, 1}, Terrain::Water);
  map.set({1, 1}, Terrain::Blocked);
  EXPECT_EQ(mapText(map), "type octile\nheight 2\nwidth 3\nmap\n.ST\nW@.\n");
}

TEST(WriteMapTest, AliasesBecomeCanonical) {
  Result<GridMap> map = parseMapText("type octile\nheight 1\nwidth 4\nmap\nG.O@\n");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_EQ(mapText(map.value()), "type octile\nheight 1\nwidth 4\nmap\n..@@\n");
}

TEST(WriteMapTest, RoundTripsRandomMultiTerrainMaps) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const GridMap original = randomMap(37 + static_cast<int>(seed), 23, seed);
    ASSERT_EQ(original.terrainsPresent(),
              Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees, Terrain::Water}));
    const std::string text = mapText(original);
    Result<GridMap> parsed = parseMapText(text);
    ASSERT_TRUE(parsed) << parsed.error().describe();
    EXPECT_EQ(parsed.value(), original);
    EXPECT_EQ(mapText(parsed.value()), text);
  }
}

TEST(WriteMapTest, SaveThenLoad) {
  const GridMap original = randomMap(20, 11, 9);
  const fs::path file = scratchPath(".map");
  Status saved = saveMap(original, file);
  ASSERT_TRUE(saved) << saved.error().describe();
  Result<GridMap> loaded = loadMap(file);
  ASSERT_TRUE(loaded) << loaded.error().describe();
  EXPECT_EQ(loaded.value(), original);
  // Saving again replaces the file instead of appending.
  const GridMap smaller = randomMap(3, 2, 10);
  saved = saveMap(smaller, file);
  ASSERT_TRUE(saved) << saved.error().describe();
  EXPECT_EQ(loadMap(file).value(), smaller);
  fs::remove(file);
}

TEST(WriteMapTest, SaveFailsWhenFileCannotBeOpened) {
  const fs::path file = scratchPath("_missing_dir") / "x.map";
  const Status saved = saveMap(GridMap(2, 2), file);
  ASSERT_FALSE(saved);
  EXPECT_EQ(saved.error().describe(),
            "cannot open '" + file.string() + "' for writing: No such file or directory");
}

TEST(LoadMapTest, LoadsFixture) {
  Result<GridMap> map = loadMap(kFixtures / "small.map");
  ASSERT_TRUE(map) << map.error().describe();
  EXPECT_EQ(map.value().width(), 6);
  EXPECT_EQ(map.value().height(), 4);
  EXPECT_EQ(mapText(map.value()),
            "type octile\nheight 4\nwidth 6\nmap\n...STW\n@@....\n.TTWW.\nSS@@..\n");
}

TEST(LoadMapTest, ErrorNamesFileAndLine) {
  Result<GridMap> map = loadMap(kFixtures / "bad_row_length.map");
  ASSERT_FALSE(map);
  EXPECT_EQ(map.error().file, fixture("bad_row_length.map"));
  EXPECT_EQ(map.error().line, 7);
  EXPECT_EQ(map.error().describe(),
            fixture("bad_row_length.map") + ":7: row y=2 has 5 characters, expected 6: '.TTWW'");
}

TEST(LoadMapTest, MissingFile) {
  const fs::path file = kFixtures / "does_not_exist.map";
  Result<GridMap> map = loadMap(file);
  ASSERT_FALSE(map);
  EXPECT_EQ(map.error().file, file.string());
  EXPECT_EQ(map.error().line, 0);
  EXPECT_EQ(map.error().describe(), file.string() + ": no such file");
}

TEST(LoadMapTest, DirectoryIsNotAFile) {
  Result<GridMap> map = loadMap(kFixtures);
  ASSERT_FALSE(map);
  EXPECT_EQ(map.error().line, 0);
  EXPECT_EQ(map.error().describe(), kFixtures.string() + ": is a directory");
}

TEST(LoadMapTest, SpecialFileIsRefusedAtOnce) {
  // /dev/zero never ends; it is refused before anything is read.
  Result<GridMap> map = loadMap("/dev/zero");
  ASSERT_FALSE(map);
  EXPECT_EQ(map.error().describe(), "/dev/zero: not a regular file");
}

TEST(LoadMapTest, OversizedFileIsRefusedBeforeReading) {
  // A sparse file: 65 MiB on paper, nothing on disk; stat says it is too large.
  const fs::path file = scratchPath(".map");
  { std::ofstream create(file); }
  fs::resize_file(file, kMapFileLimit.maxBytes + 1);
  Result<GridMap> map = loadMap(file);
  ASSERT_FALSE(map);
  EXPECT_EQ(map.error().describe(), file.string() + ": larger than the 64 MiB limit for maps");
  fs::remove(file);
}

TEST(ReadFileCappedTest, StopsAtTheCapWhileReading) {
  // A file within the cap reads whole; the cap is also enforced on the bytes actually read.
  const fs::path file = scratchPath(".txt");
  { std::ofstream(file) << "0123456789"; }
  const Result<std::string> whole = readFileCapped(file, {10, "tests"});
  ASSERT_TRUE(whole) << whole.error().describe();
  EXPECT_EQ(whole.value(), "0123456789");
  const Result<std::string> capped = readFileCapped(file, {9, "tests"});
  ASSERT_FALSE(capped);
  EXPECT_EQ(capped.error().describe(), file.string() + ": larger than the 9 bytes limit for tests");
  Result<CappedFile> opened = CappedFile::open(file, {10, "tests"});
  ASSERT_TRUE(opened);
  std::string head;
  ASSERT_TRUE(opened.value().read(head, 4));
  EXPECT_EQ(head, "0123");
  fs::remove(file);
  // /proc files are regular but stat gives them size 0: the cap stops the read itself.
  const Result<std::string> proc = readFileCapped("/proc/self/maps", {16, "tests"});
  ASSERT_FALSE(proc);
  EXPECT_EQ(proc.error().describe(), "/proc/self/maps: larger than the 16 bytes limit for tests");
  const Result<std::string> gone = readFileCapped(file, {10, "tests"});
  ASSERT_FALSE(gone);
  EXPECT_EQ(gone.error().describe(), file.string() + ": no such file");
}

// ---------------------------------------------------------------------------------------
// parseScen: valid input

TEST(ParseScenTest, ReadsTabSeparatedVersion1) {
  Result<std::vector<ScenQuery>> scen = parseScenText(
      "version 1\n"
      "0\tmaps/dao/arena.map\t49\t49\t1\t11\t1\t12\t1\n"
      "3\tmaps/dao/arena.map\t49\t49\t1\t13\t4\t12\t3.41421\n");
  ASSERT_TRUE(scen) << scen.error().describe();
  const std::vector<ScenQuery>& q = scen.value();
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].bucket, 0);
  EXPECT_EQ(q[0].mapName, "maps/dao/arena.map");
  EXPECT_EQ(q[0].mapWidth, 49);
  EXPECT_EQ(q[0].mapHeight, 49);
  EXPECT_EQ(q[0].start, (Cell{1, 11}));
  EXPECT_EQ(q[0].goal, (Cell{1, 12}));
  EXPECT_EQ(q[0].optimalLength, 1.0);
  EXPECT_EQ(q[0].line, 2);
  EXPECT_EQ(q[1].bucket, 3);
  EXPECT_EQ(q[1].start, (Cell{1, 13}));
  EXPECT_EQ(q[1].goal, (Cell{4, 12}));
  EXPECT_DOUBLE_EQ(q[1].optimalLength, 3.41421);
  EXPECT_EQ(q[1].line, 3);
}

TEST(ParseScenTest, ReadsSpaceSeparatedVersion1_0) {
  Result<std::vector<ScenQuery>> scen =
      parseScenText("version 1.0\n61 maps/bgmaps/AR0011SR.map 512 300 210 295 87 201 244.95\n");
  ASSERT_TRUE(scen) << scen.error().describe();
  ASSERT_EQ(scen.value().size(), 1u);
  const ScenQuery& q = scen.value()[0];
  EXPECT_EQ(q.bucket, 61);
  EXPECT_EQ(q.mapWidth, 512);
  EXPECT_EQ(q.mapHeight, 300);
  EXPECT_EQ(q.start, (Cell{210, 295}));
  EXPECT_EQ(q.goal, (Cell{87, 201}));
  EXPECT_DOUBLE_EQ(q.optimalLength, 244.95);
}

TEST(ParseScenTest, AcceptsAnySpellingOfVersionOne) {
  for (const char* version :
       {"version 1", "version 1.0", "version 1.00", "version\t1", "  version 1  ", "version 01",
        "version 1e0", "version 1\r", "\n\n version 1"}) {
    SCOPED_TRACE(version);
    Result<std::vector<ScenQuery>> scen = parseScenText(std::string(version) + "\n");
    ASSERT_TRUE(scen) << scen.error().describe();
    EXPECT_TRUE(scen.value().empty());
  }
}

TEST(ParseScenTest, SkipsBlankLinesAndKeepsLineNumbers) {
  Result<std::vector<ScenQuery>> scen = parseScenText(
      "version 1\r\n"
      "\r\n"
      "0\ta.map\t4\t4\t0\t0\t1\t1\t1.41421\r\n"
      "   \t \n"
      "\r\n"
      "1 a.map\t4 4  3\t3 0 0\t4.24264  \n"
      "\n");
  ASSERT_TRUE(scen) << scen.error().describe();
  ASSERT_EQ(scen.value().size(), 2u);
  EXPECT_EQ(scen.value()[0].line, 3);
  EXPECT_EQ(scen.value()[1].line, 6);
  EXPECT_EQ(scen.value()[1].start, (Cell{3, 3}));
  EXPECT_DOUBLE_EQ(scen.value()[1].optimalLength, 4.24264);
}

TEST(ParseScenTest, AcceptsZeroLengthAndEdgeCoordinates) {
  Result<std::vector<ScenQuery>> scen = parseScenText("version 1\n0 m 5 3 4 2 4 2 0\n");
  ASSERT_TRUE(scen) << scen.error().describe();
  EXPECT_EQ(scen.value()[0].start, (Cell{4, 2}));
  EXPECT_EQ(scen.value()[0].optimalLength, 0.0);
}

// ---------------------------------------------------------------------------------------
// parseScen: errors

constexpr std::string_view kVersion = "version 1\n";

TEST(ParseScenErrorTest, EmptyInput) {
  for (const char* text : {"", "\n", " \r\n\n"}) {
    SCOPED_TRACE(text);
    EXPECT_EQ(scenError(text).message, "empty file: expected 'version 1'");
  }
  EXPECT_EQ(scenError("").line, 1);
  EXPECT_EQ(scenError("\n\n").line, 3);
}

TEST(ParseScenErrorTest, MissingVersionLine) {
  Error e = scenError("0\ta.map\t4\t4\t0\t0\t1\t1\t1.41421\n");
  EXPECT_EQ(e.line, 1);
  EXPECT_EQ(e.message,
            "missing 'version' line: expected 'version 1', found '0?a.map?4?4?0?0?1?1?1.41421'");
  e = scenError("\nVersion 1\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.message, "missing 'version' line: expected 'version 1', found 'Version 1'");
}

TEST(ParseScenErrorTest, UnsupportedVersion) {
  for (const char* version : {"2", "1.5", "0", "abc", "1x", "1 0"}) {
    SCOPED_TRACE(version);
    const Error e = scenError("version " + std::string(version) + "\n");
    EXPECT_EQ(e.line, 1);
    EXPECT_EQ(e.message, "unsupported scenario version '" + std::string(version) +
                             "' (only version 1 is supported)");
  }
  EXPECT_EQ(scenError("version\n").message, "missing version number after 'version'");
}

TEST(ParseScenErrorTest, WrongFieldCount) {
  const std::string expected =
      "expected 9 fields (bucket, map, map width, map height, start x, start y, goal x, goal y, "
      "optimal length), found ";
  Error e = scenError(std::string(kVersion) + "0\ta.map\t4\t4\t0\t0\t1\t1\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.message, expected + "8");
  // A map path with a space splits into two fields.
  e = scenError(std::string(kVersion) + "\n0 my map.map 4 4 0 0 1 1 1.4\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.message, expected + "10");
  EXPECT_EQ(scenError(std::string(kVersion) + "0\n").message, expected + "1");
}

TEST(ParseScenErrorTest, NonNumericFieldIsNamed) {
  const char* names[] = {"bucket",  nullptr,   "map width", "map height",
                         "start x", "start y", "goal x",    "goal y"};
  for (std::size_t field = 0; field < 8; ++field) {
    if (!names[field]) continue;  // the map path is free text
    for (const char* bad : {"abc", "12abc", "1.5", "+1", "1,5"}) {
      std::vector<std::string> fields = {"0", "a.map", "4", "4", "0", "0", "1", "1", "1.41421"};
      fields[field] = bad;
      std::string line;
      for (const std::string& f : fields)
        line += f + "\t";
      SCOPED_TRACE(line);
      const Error e = scenError(std::string(kVersion) + line + "\n");
      EXPECT_EQ(e.line, 2);
      const std::string shown = bad;
      const std::string name = names[field];
      if (field == 2 || field == 3) {
        EXPECT_EQ(e.message, name + " must be a positive integer, got '" + shown + "'");
      } else {
        EXPECT_EQ(e.message, name + " must be an integer, got '" + shown + "'");
      }
    }
  }
}

TEST(ParseScenErrorTest, IntegerOutOfRange) {
  EXPECT_EQ(scenError(std::string(kVersion) + "99999999999 a 4 4 0 0 1 1 1\n").message,
            "bucket is out of range: '99999999999'");
  EXPECT_EQ(scenError(std::string(kVersion) + "0 a 4 4 0 -99999999999 1 1 1\n").message,
            "start y is out of range: '-99999999999'");
  EXPECT_EQ(scenError(std::string(kVersion) + "0 a 40000 4 0 0 1 1 1\n").message,
            "map width 40000 is too large (maximum 32768)");
}

TEST(ParseScenErrorTest, BadMapSize) {
  EXPECT_EQ(scenError(std::string(kVersion) + "0 a 0 4 0 0 1 1 1\n").message,
            "map width must be a positive integer, got '0'");
  EXPECT_EQ(scenError(std::string(kVersion) + "0 a 4 -4 0 0 1 1 1\n").message,
            "map height must be a positive integer, got '-4'");
}

TEST(ParseScenErrorTest, CoordinateOutsideDeclaredMap) {
  struct Case {
    const char* line;
    const char* message;
  };
  const Case cases[] = {
      {"0 a 5 3 -1 0 1 1 1", "start x -1 is outside 0..4 (map width 5)"},
      {"0 a 5 3 5 0 1 1 1", "start x 5 is outside 0..4 (map width 5)"},
      {"0 a 5 3 0 3 1 1 1", "start y 3 is outside 0..2 (map height 3)"},
      {"0 a 5 3 0 -2 1 1 1", "start y -2 is outside 0..2 (map height 3)"},
      {"0 a 5 3 0 0 7 1 1", "goal x 7 is outside 0..4 (map width 5)"},
      {"0 a 5 3 0 0 1 -1 1", "goal y -1 is outside 0..2 (map height 3)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.line);
    const Error e = scenError(std::string(kVersion) + "0 a 5 3 0 0 1 1 1\n" + c.line + "\n");
    EXPECT_EQ(e.line, 3);
    EXPECT_EQ(e.message, c.message);
  }
}

TEST(ParseScenErrorTest, BadOptimalLength) {
  struct Case {
    const char* value;
    const char* message;
  };
  const Case cases[] = {
      {"abc", "optimal length must be a number, got 'abc'"},
      {"1.5x", "optimal length must be a number, got '1.5x'"},
      {"0x1p3", "optimal length must be a number, got '0x1p3'"},
      {"-1", "optimal length must not be negative, got '-1'"},
      {"-0.01", "optimal length must not be negative, got '-0.01'"},
      {"inf", "optimal length must be finite, got 'inf'"},
      {"nan", "optimal length must be finite, got 'nan'"},
      {"-inf", "optimal length must be finite, got '-inf'"},
      {"1e999", "optimal length is out of range: '1e999'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.value);
    const Error e = scenError(std::string(kVersion) + "0 a 5 3 0 0 1 1 " + c.value + "\n");
    EXPECT_EQ(e.line, 2);
    EXPECT_EQ(e.message, c.message);
  }
}

TEST(ParseScenErrorTest, NeverCrashesOnDamagedInput) {
  const std::string valid =
      "version 1\n0\ta.map\t9\t7\t0\t0\t8\t6\t10.4853\n\n1\tb.map\t9\t7\t3\t3\t3\t4\t1\n";
  const auto check = [&](const std::string& text) {
    Result<std::vector<ScenQuery>> scen = parseScenText(text);
    if (scen) {
      for (const ScenQuery& q : scen.value()) {
        EXPECT_GE(q.start.x, 0);
        EXPECT_LT(q.goal.y, q.mapHeight);
        EXPECT_GE(q.optimalLength, 0.0);
      }
    } else {
      EXPECT_FALSE(scen.error().message.empty());
      EXPECT_GE(scen.error().line, 1);
      EXPECT_LE(scen.error().line, 5 + 2 + 1) << scen.error().describe();  // 2 possible '\n'
    }
  };
  for (std::size_t n = 0; n <= valid.size(); ++n)
    check(valid.substr(0, n));
  std::mt19937 rng(7);
  for (int i = 0; i < 3000; ++i) {
    std::string text = valid;
    for (int k = 0; k < 2; ++k)
      text[rng() % text.size()] = static_cast<char>(rng() % 256);
    check(text);
  }
}

// ---------------------------------------------------------------------------------------
// loadScen and checkScenAgainstMap

TEST(LoadScenTest, LoadsFixtureAndMatchesItsMap) {
  Result<std::vector<ScenQuery>> scen = loadScen(kFixtures / "small.map.scen");
  ASSERT_TRUE(scen) << scen.error().describe();
  ASSERT_EQ(scen.value().size(), 3u);
  EXPECT_EQ(scen.value()[2].line, 5);  // after a blank line
  EXPECT_EQ(scen.value()[2].start, (Cell{1, 2}));
  Result<GridMap> map = loadMap(kFixtures / "small.map");
  ASSERT_TRUE(map) << map.error().describe();
  const Status e = checkScenAgainstMap(scen.value(), map.value(), "small.map.scen");
  EXPECT_TRUE(e) << e.error().describe();
}

TEST(LoadScenTest, ErrorNamesFileAndLine) {
  Result<std::vector<ScenQuery>> scen = loadScen(kFixtures / "bad_coordinate.scen");
  ASSERT_FALSE(scen);
  EXPECT_EQ(scen.error().describe(),
            fixture("bad_coordinate.scen") + ":3: goal x 6 is outside 0..5 (map width 6)");
}

TEST(LoadScenTest, MissingFile) {
  const fs::path file = kFixtures / "does_not_exist.scen";
  Result<std::vector<ScenQuery>> scen = loadScen(file);
  ASSERT_FALSE(scen);
  EXPECT_EQ(scen.error().line, 0);
  EXPECT_EQ(scen.error().describe(), file.string() + ": no such file");
}

TEST(CheckScenTest, DeclaredSizeMustMatchMap) {
  Result<std::vector<ScenQuery>> scen = loadScen(kFixtures / "wrong_size.map.scen");
  ASSERT_TRUE(scen) << scen.error().describe();
  Result<GridMap> map = loadMap(kFixtures / "small.map");
  ASSERT_TRUE(map) << map.error().describe();
  const std::string scenName = fixture("wrong_size.map.scen");
  const Status e = checkScenAgainstMap(scen.value(), map.value(), scenName);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().describe(), scenName + ":3: query declares a 8x8 map but the map is 6x4");
}

TEST(CheckScenTest, CoordinatesMustBeInsideMap) {
  // Hand-made queries can bypass parseScen's own check.
  ScenQuery q;
  q.mapWidth = 6;
  q.mapHeight = 4;
  q.start = {5, 3};
  q.goal = {0, 0};
  q.line = 12;
  const GridMap map(6, 4);
  Status e = checkScenAgainstMap({q}, map, "s.scen");
  EXPECT_TRUE(e) << e.error().describe();
  EXPECT_TRUE(checkScenAgainstMap({}, map, "s.scen"));

  q.start = {6, 0};
  e = checkScenAgainstMap({q}, map, "s.scen");
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().describe(), "s.scen:12: start (6, 0) is outside the 6x4 map");

  q.start = {0, 0};
  q.goal = {-1, 2};
  e = checkScenAgainstMap({q, q}, map, "s.scen");
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().describe(), "s.scen:12: goal (-1, 2) is outside the 6x4 map");
}

}  // namespace
}  // namespace warpath::pathing
