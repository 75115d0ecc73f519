// Replays: record while running, read back, re-simulate; every way a file can be damaged is
// refused with a message naming the file and the problem; `rts run --replay` and
// `rts replay verify|info` end to end.

#include "engine/replay.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <zlib.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>

#include "engine/scenario_run.h"
#include "support/battle_field.h"
#include "support/rts_process.h"
#include "support/run_out.h"
#include "support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using namespace warpath::engine;

using warpath::Error;
using warpath::Result;
using warpath::Status;
using warpath::testing::rts;
using warpath::testing::RtsResult;

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

// The byte offset of every record (docs/replays.md: kind, length, header CRC, payload, CRC).
std::vector<std::size_t> recordOffsets(const std::string& bytes) {
  std::vector<std::size_t> at;
  for (std::size_t i = 12; i + 9 <= bytes.size();) {
    at.push_back(i);
    std::uint32_t length = 0;
    for (int b = 0; b < 4; ++b)
      length |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1 + b])) << (8 * b);
    i += 9 + length + 4;
  }
  return at;
}

std::uint32_t recordLength(const std::string& bytes, std::size_t record) {
  std::uint32_t length = 0;
  for (int b = 0; b < 4; ++b)
    length |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[record + 1 + b]))
              << (8 * b);
  return length;
}

// Writes `value` little-endian at byte `at` of the payload of the record at `record`, and puts
// the payload's CRC-32 right, so the change passes the checksums.
void rewritePayload(std::string& bytes, std::size_t record, std::size_t at, std::int64_t value) {
  for (int b = 0; b < 8; ++b)
    bytes[record + 9 + at + static_cast<std::size_t>(b)] =
        static_cast<char>(static_cast<std::uint64_t>(value) >> (8 * b));
  const std::uint32_t length = recordLength(bytes, record);
  const auto c = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + record + 9), length));
  for (int b = 0; b < 4; ++b)
    bytes[record + 9 + length + static_cast<std::size_t>(b)] = static_cast<char>(c >> (8 * b));
}

std::string idsText(const std::vector<UnitId>& ids) {
  std::string t;
  for (UnitId id : ids)
    t += (t.empty() ? "" : ",") + std::to_string(id.index) + "." + std::to_string(id.generation);
  return t;
}

// The command stream as text, for whole-entry comparisons with readable failures.
std::vector<std::string> describe(const std::vector<IssuedOrder>& orders) {
  std::vector<std::string> out;
  for (const IssuedOrder& o : orders) {
    const warpath::pathing::CellRect& a = o.command.area;
    out.push_back("tick " + std::to_string(o.tick) + " kind " +
                  std::to_string(static_cast<int>(o.kind)) + " group " + std::to_string(o.group) +
                  " " + std::string(toString(o.command.kind)) + " units [" +
                  idsText(o.command.units) + "] area " + std::to_string(a.x) + "," +
                  std::to_string(a.y) + " " + std::to_string(a.width) + "x" +
                  std::to_string(a.height) + " targets [" + idsText(o.command.targets) + "]");
  }
  return out;
}

// Four recruits a side attack-moving through each other on an open field; two red vets come in
// (a reinforcement with an attack order on blue) when red is down to two. `extra` is added to
// the triggers.
std::string battleScenario(const std::string& extra = "") {
  return "name: skirmish\n" + warpath::testing::openFieldMap() + "unit_types:\n" +
         warpath::testing::kRiflemenTypes +
         "duration: 60\n"
         "teams: [blue, red]\n" +
         warpath::testing::skirmishForces(extra) + "expectations:\n  - winner: red\n";
}

class Replays : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = warpath::testing::freshTestDir("warpath_replay_");
    // A map file and a catalogue beside the scenario, so the test can change and delete them.
    std::ofstream(dir_ / "small.map") << "type octile\nheight 8\nwidth 16\nmap\n"
                                         "................\n"
                                         "................\n"
                                         "......TTTT......\n"
                                         "......TTTT......\n"
                                         "......@@@@......\n"
                                         "................\n"
                                         "................\n"
                                         "................\n";
    fs::copy_file(fs::path(WARPATH_SOURCE_DIR) / "assets/units.yaml", dir_ / "units.yaml");
    // A triggered order: playback must give it at the recorded tick without re-deriving it.
    std::ofstream(dir_ / "s.yaml")
        << "name: small\nmap: small.map\ncatalogue: units.yaml\nseed: 7\nduration: 12\n"
           "teams: [blue, red]\n"
           "groups:\n"
           "  - {name: a, team: blue, type: infantry, count: 4, spawn: {x: 0, y: 0, w: 3, h: 4},"
           " goal: {x: 12, y: 0, w: 4, h: 4}}\n"
           "  - {name: b, team: red, type: jeep, count: 2, spawn: {x: 12, y: 5, w: 4, h: 3},"
           " goal: {x: 0, y: 5, w: 4, h: 3}}\n"
           "orders:\n"
           "  - when: {arrived: a, fraction: 0.5}\n"
           "    group: b\n"
           "    move_to: {x: 6, y: 6, w: 4, h: 2}\n"
           "expectations:\n  - max_stuck: 10\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path scenario() const { return dir_ / "s.yaml"; }

  // Records a replay in-process with hash interval `every`, stopping after `until` ticks.
  fs::path record(std::int64_t every, std::int64_t until = -1) {
    return recordFile(scenario(), every, until);
  }
  fs::path recordFile(const fs::path& scenarioFile, std::int64_t every, std::int64_t until = -1) {
    ReplaySource source;
    Result<Scenario> loaded = loadRecordedScenario(scenarioFile, source);
    EXPECT_TRUE(loaded.ok()) << loaded.error().describe();
    source.seed = loaded.value().settings.seed;
    source.hashEvery = every;
    const fs::path file = dir_ / "r.rpl";
    Result<ReplayWriter> writer = ReplayWriter::open(file, source);
    EXPECT_TRUE(writer.ok()) << writer.error().describe();
    ScenarioRun run(loaded.value());
    EXPECT_TRUE(writer.value().record(run));
    while (!run.done() && run.world().tick() != until) {
      run.step();
      EXPECT_TRUE(writer.value().record(run));
    }
    EXPECT_TRUE(writer.value().finish(run, run.done() ? ReplayEnd::Complete : ReplayEnd::Stopped));
    finalHash_ = run.stateHash();
    issued_ = run.issued().size();
    issuedOrders_ = run.issued();
    finalReport_ = run.report();
    return file;
  }

  std::string readError(const fs::path& file) {
    Result<Replay> r = readReplay(file);
    EXPECT_FALSE(r.ok());
    return r.ok() ? "" : r.error().describe();
  }

  fs::path dir_;
  std::uint64_t finalHash_ = 0;
  std::size_t issued_ = 0;
  std::vector<IssuedOrder> issuedOrders_;
  Report finalReport_;
};

TEST_F(Replays, RecordReadVerify) {
  const fs::path file = record(1);
  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok()) << replay.error().describe();
  EXPECT_EQ(replay.value().version, kReplayVersion);
  EXPECT_EQ(replay.value().source.seed, 7u);
  ASSERT_EQ(replay.value().source.files.size(), 2u);  // the map and the catalogue
  EXPECT_EQ(replay.value().source.files[0].contents, slurp(dir_ / "small.map"));
  EXPECT_EQ(replay.value().source.files[1].contents, slurp(dir_ / "units.yaml"));
  EXPECT_EQ(replay.value().hashes.size(), 360u);
  ASSERT_TRUE(replay.value().end);
  EXPECT_EQ(replay.value().end->reason, ReplayEnd::Complete);
  EXPECT_EQ(replay.value().end->last.hash, finalHash_);
  // Two group goals at tick 0 and the triggered order later.
  ASSERT_EQ(replay.value().orders.size(), 3u);
  EXPECT_EQ(issued_, 3u);
  EXPECT_GT(replay.value().orders[2].tick, 0);

  Result<ReplayPlayback> playback = ReplayPlayback::open(replay.value(), file.string());
  ASSERT_TRUE(playback.ok()) << playback.error().describe();
  const VerifyOutcome outcome = verifyReplay(playback.value());
  EXPECT_FALSE(outcome.mismatch);
  EXPECT_EQ(outcome.ticks, 360);
  EXPECT_EQ(outcome.hashes, 361);
  EXPECT_EQ(playback.value().run().stateHash(), finalHash_);
  ASSERT_EQ(playback.value().run().issued().size(), 3u);
  EXPECT_EQ(playback.value().run().issued()[2].tick, replay.value().orders[2].tick);
  // Verifying again restarts from tick 0 and agrees.
  EXPECT_FALSE(verifyReplay(playback.value()).mismatch);
}

TEST_F(Replays, ADifferentHashIsFoundAtItsTick) {
  const fs::path file = record(5);
  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok());
  EXPECT_EQ(replay.value().hashes.size(), 72u);
  replay.value().hashes[9].hash ^= 1;  // tick 50
  Result<ReplayPlayback> playback = ReplayPlayback::open(replay.value(), file.string());
  ASSERT_TRUE(playback.ok());
  const VerifyOutcome outcome = verifyReplay(playback.value());
  ASSERT_TRUE(outcome.mismatch);
  EXPECT_EQ(outcome.mismatch->tick, 50);
  EXPECT_EQ(outcome.mismatch->expected ^ 1, outcome.mismatch->actual);
}

TEST_F(Replays, PlaysBackAfterTheFilesChangeOrVanish) {
  const fs::path file = record(1);
  fs::remove(dir_ / "small.map");
  std::ofstream(dir_ / "units.yaml") << "unit_types: {}\n";
  std::ofstream(scenario()) << "garbage: [";
  const RtsResult r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("verified 360 ticks"), std::string::npos) << r.out;
}

TEST_F(Replays, ACorruptedByteIsRefused) {
  const fs::path file = record(1);
  const std::string good = slurp(file);
  const std::vector<std::size_t> records = recordOffsets(good);
  ASSERT_GT(records.size(), 100u);
  std::string bad = good;
  bad[records[50] + 12] ^= 0x10;  // inside a payload
  spit(file, bad);
  EXPECT_EQ(readError(file), file.string() + ": record at byte " + std::to_string(records[50]) +
                                 " is corrupted (checksum mismatch)");
  bad = good;
  bad[records[50] + 2] ^= 0x01;  // the length
  spit(file, bad);
  EXPECT_EQ(readError(file), file.string() + ": record at byte " + std::to_string(records[50]) +
                                 " is corrupted (header checksum mismatch)");
  const RtsResult r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("header checksum mismatch"), std::string::npos) << r.out;
}

TEST_F(Replays, TruncationInsideARecordIsRefused) {
  const fs::path file = record(1);
  const std::string good = slurp(file);
  const std::vector<std::size_t> records = recordOffsets(good);
  for (std::size_t cut : {records[40] + 3, records[40] + 15, good.size() - 1}) {
    spit(file, good.substr(0, cut));
    const std::string e = readError(file);
    EXPECT_NE(e.find(file.string() + ": truncated in the middle of a record at byte"),
              std::string::npos)
        << e;
  }
  spit(file, good.substr(0, 10));
  EXPECT_EQ(readError(file), file.string() + ": not a warpath replay (no WPREPLAY header)");
  spit(file, good.substr(0, 12));
  EXPECT_EQ(readError(file), file.string() + ": truncated: no scenario record");
}

// Cut at a record boundary, a replay is an interrupted run: it verifies up to its last hash.
TEST_F(Replays, TruncationBetweenRecordsVerifiesUpToTheLastTick) {
  const fs::path file = record(1);
  const std::string good = slurp(file);
  const std::vector<std::size_t> records = recordOffsets(good);
  spit(file, good.substr(0, records[200]));
  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok()) << replay.error().describe();
  EXPECT_FALSE(replay.value().end);
  const std::int64_t last = replay.value().lastTick();
  EXPECT_GT(last, 150);
  EXPECT_LT(last, 200);
  Result<ReplayPlayback> playback = ReplayPlayback::open(replay.value(), file.string());
  ASSERT_TRUE(playback.ok());
  const VerifyOutcome outcome = verifyReplay(playback.value());
  EXPECT_FALSE(outcome.mismatch);
  EXPECT_EQ(outcome.ticks, last);
  const RtsResult info = rts("replay info " + file.string());
  EXPECT_EQ(info.status, 0) << info.out;
  EXPECT_NE(info.out.find("status: interrupted (no end record"), std::string::npos) << info.out;
}

// A format-2 replay written by the release before the complete state hash (forest_battle,
// hashes every 30 ticks) still verifies: playback computes the hash that format recorded.
TEST_F(Replays, AFormat2ReplayOfThePreviousReleaseVerifies) {
  const std::string file =
      std::string(WARPATH_SOURCE_DIR) + "/tests/fixtures/forest_battle_format2.replay";
  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok()) << replay.error().describe();
  EXPECT_EQ(replay.value().version, 2u);
  const RtsResult r = rts("replay verify " + file);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("verified 1978 ticks, 66 state hashes match"), std::string::npos) << r.out;
}

// A scenario file copied into `dir` with its map and catalogue paths made absolute and `pathing`
// set to `settings`, loaded for recording.
Result<Scenario> copyWithPathing(const fs::path& dir, const fs::path& original,
                                 const std::string& settings, ReplaySource& source) {
  std::string text = slurp(original);
  // Paths in the file are relative to its folder.
  for (const std::string key : {"map: ", "catalogue: "}) {
    const std::size_t at = text.find(key) + key.size();
    const std::size_t end = text.find('\n', at);
    const fs::path resolved =
        (original.parent_path() / text.substr(at, end - at)).lexically_normal();
    text.replace(at, end - at, resolved.string());
  }
  text += "pathing: " + settings + "\n";
  const fs::path file = dir / ("copy_" + original.filename().string());
  spit(file, text);
  return loadRecordedScenario(file, source);
}

// Records `s` as replay format `format` (hashes laid out as that format's) until `lastTick` or
// its end, then checks that the file verifies as that format and does not read as the next
// (which plays the scenario back under a later default).
void expectVerifiesOnlyAsItsFormat(const Scenario& s, const ReplaySource& source,
                                   const fs::path& file, std::uint32_t format,
                                   std::int64_t lastTick) {
  {
    Result<ReplayWriter> writer = ReplayWriter::open(file, source, format);
    ASSERT_TRUE(writer.ok()) << writer.error().describe();
    ScenarioRun run(s);
    ASSERT_TRUE(writer.value().record(run));
    while (!run.done() && run.world().tick() < lastTick) {
      run.step();
      ASSERT_TRUE(writer.value().record(run));
    }
    ASSERT_TRUE(writer.value().finish(run, run.done() ? ReplayEnd::Complete : ReplayEnd::Stopped));
  }
  std::string bytes = slurp(file);
  ASSERT_EQ(static_cast<std::uint32_t>(bytes[8]), format);
  RtsResult r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 0) << r.out;
  bytes[8] = static_cast<char>(format + 1);
  spit(file, bytes);
  r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 1) << r.out;
}

// Format 6 was recorded when cooperative movement was off by default: a scenario that does not
// mention it plays back with it off, so such a file verifies. Read as format 7 (cooperation on
// by default) the same records do not.
TEST_F(Replays, AFormat6ReplayPlaysBackWithCooperationOff) {
  ReplaySource source;
  Result<Scenario> loaded = loadRecordedScenario(scenario(), source);
  ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
  Scenario s = std::move(loaded).value();
  ASSERT_TRUE(s.settings.pathing.cooperative);  // the default now
  rulesOfReplayFormat(s.settings.pathing, 6);
  ASSERT_FALSE(s.settings.pathing.cooperative);
  source.seed = s.settings.seed;
  expectVerifiesOnlyAsItsFormat(s, source, dir_ / "format6.rpl", 6, INT64_MAX);
}

TEST_F(Replays, WritesFormatsFrom3ToItsOwn) {
  ReplaySource source;
  // Formats before 3 hash another way, and none after this build's can be written.
  EXPECT_FALSE(ReplayWriter::open(dir_ / "x.rpl", source, 2).ok());
  EXPECT_FALSE(ReplayWriter::open(dir_ / "x.rpl", source, kReplayVersion + 1).ok());
  EXPECT_TRUE(ReplayWriter::open(dir_ / "x.rpl", source, kReplayVersion).ok());
}

// The rules that came with each format, written out here apart from rulesOfReplayFormat: each
// is on by default, set back for every format before its own and left on from its own on. (The
// runs below show that a format's rules part its runs from the next format's; this shows that
// none of the rules is left out.)
TEST_F(Replays, EachRuleIsSetBackForTheFormatsBeforeIt) {
  using Settings = PathServiceSettings;
  const std::vector<std::pair<bool Settings::*, std::uint32_t>> rules = {
      {&Settings::cooperative, 7},
      {&Settings::congestion, 8},
      {&Settings::slicedWindows, 9},
      {&Settings::nearestKeptOutFirst, 11},
      {&Settings::lanesThroughJunctions, 12},
      {&Settings::stepAsideToRoom, 12},
      {&Settings::jamDetours, 13},
      {&Settings::standingVehicleLanes, 14},
      {&Settings::parkWhenAreaFull, 15},
      {&Settings::oneWayPassages, 16},
      {&Settings::openDents, 17},
      {&Settings::laneApproaches, 18},
      {&Settings::queuesExcused, 19},
      {&Settings::widerLaneApproaches, 20},
      {&Settings::headOnKeepRight, 21},
      {&Settings::wideLaneDetours, 22},
      {&Settings::plannedTimeWithLanes, 22},
      {&Settings::headOnByIntent, 22},
      {&Settings::insideGoesFirst, 23},
      {&Settings::parkedMoveOn, 24},
      {&Settings::turnsWithinWaypoints, 25},
      {&Settings::lighterVehiclesStepAside, 26},
      {&Settings::turnAwayFromWalls, 26},
      {&Settings::keptOutBacksOut, 27},
      {&Settings::rewindPushedBack, 28},
      {&Settings::routeFromPlaceOnPath, 29},
      {&Settings::detoursToGoal, 30},
  };
  for (std::uint32_t format = kOldestReplayVersion; format <= kReplayVersion; ++format) {
    Settings set;
    rulesOfReplayFormat(set, format);
    for (std::size_t i = 0; i < rules.size(); ++i) {
      const auto& [rule, since] = rules[i];
      EXPECT_TRUE(Settings{}.*rule) << "rule " << i << " is on by default";
      EXPECT_EQ(set.*rule, format >= since) << "rule " << i << " at format " << format;
    }
    EXPECT_EQ(set.jumpSuccessors, format >= 10 ? warpath::pathing::JumpSuccessors::ForcedOnly
                                               : warpath::pathing::JumpSuccessors::EverySide)
        << format;
    EXPECT_EQ(set.keepOutExit, format >= 11 ? warpath::pathing::KeepOutExit::Stepwise
                                            : warpath::pathing::KeepOutExit::HighestLevel)
        << format;
  }
}

// A run recorded as an older format, with the rules of then, where the next format's rules part
// from them within its first `lastTick` ticks.
struct OlderFormat {
  std::uint32_t format;
  const char* scenario;   // under the source tree
  const char* pathing;    // `pathing:` settings of a copy of it, or null for the file itself
  std::uint64_t seed;     // 0: the file's own
  std::int64_t lastTick;  // INT64_MAX: the whole run
};

// Each format whose rules changed plays back as it was recorded, so a file of it verifies; read
// as the next format (whose rules differ) the same records do not. Where the runs part:
// - 7, congestion-aware routes: the two bridges' crowd queues at once;
// - 8, sliced window searches: at the door with a small budget windows pause within seconds;
// - 9, jump points taking every side turn (`algo: jps+`): the narrow pass picks other cells of
//   equal length within seconds;
// - 10, the kept-out rules: at seed 5 of the 4-wide corridor the red tank, waiting in the blue
//   tank's stream, steps out of it (or not) at 11.4 s; at the door the crowds wait from the start;
// - 11, lanes through junctions and stepping aside to the side with room: the crossroads' tanks
//   reach the crossing within 10 s;
// - 12, detours after a jam: in the narrow pass the first unit jams at about 28 s;
// - 13, stopped vehicles claiming their lane: the crossroads before 15 s;
// - 14, parking where one stands in a full goal area: the last three of twelve walkers sent to a
//   3x3 area;
// - 15, one-way passages: thirty walkers through a door, all one way;
// - 16, notches as chokepoints; 17, lanes ending at the mouth (the two-way bridge);
// - 18, queued windows counted toward the stuck flag: the door at seed 10, where a rifleman
//   queued behind its side's stream was flagged at 18.8 s;
// - 19, lanes held two footprints beyond a wide bridge; 20, vehicles pushing head on: 20 tanks a
//   side on a bridge 16 wide;
// - 21, dropping wide lanes: bridge16_mixed at seed 73, where four of blue's jeeps lost theirs;
// - 22, waiting inside the passage: three tanks a side through a 5-wide corridor at seed 4;
// - 23, parked teammates staying: `demo` at seed 22, red's tanks behind the first one parked;
// - 24, turning through waypoint centres: the two-way bridge at its own seed;
// - 25, only the lightest stepping aside: bridge16_mixed at seed 18, a red jeep meeting blue's
//   tanks leaving its goal area;
// - 26, waiting to be pushed inside a passage: three tanks a side through a 5-wide corridor at
//   seed 15, where blue's first, parked at the east mouth, is pushed back in by red's last;
// - 27, places on paths moving forward only: the same corridor at seed 165, where blue's last
//   tank is pushed back through the corridor by red's column.
// Format 28 has no row: its rule (a terrain change checked against a unit's path from its place
// on it) changes no bundled run (bridge_demolition at seeds 1-300 hashes the same either way);
// WorldTerrainChange.AUnitPushedBackRepathsForAChangeBehindItsWaypoint shows what it changes.
// - 29, a new goal cell before a detour, and no detour to the goal: `demo` at seed 156.
void PrintTo(const OlderFormat& f, std::ostream* out) {
  *out << "format " << f.format << ", " << f.scenario;
}

class OlderFormats : public Replays, public ::testing::WithParamInterface<OlderFormat> {};

TEST_P(OlderFormats, PlayBackWithTheRulesOfThen) {
  const OlderFormat& f = GetParam();
  ReplaySource source;
  const fs::path file = fs::path(WARPATH_SOURCE_DIR) / f.scenario;
  Result<Scenario> loaded = f.pathing != nullptr ? copyWithPathing(dir_, file, f.pathing, source)
                                                 : loadRecordedScenario(file, source);
  ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
  Scenario s = std::move(loaded).value();
  rulesOfReplayFormat(s.settings.pathing, f.format);
  if (f.seed != 0) s.settings.seed = f.seed;
  source.seed = s.settings.seed;
  expectVerifiesOnlyAsItsFormat(s, source, dir_ / "older.rpl", f.format, f.lastTick);
}

INSTANTIATE_TEST_SUITE_P(
    Replays, OlderFormats,
    ::testing::Values(
        OlderFormat{7, "scenarios/chokepoints/two_bridges.yaml", nullptr, 0, 300},
        OlderFormat{8, "scenarios/chokepoints/door_30v30.yaml", "{sliced: true, budget: 400}", 0,
                    300},
        OlderFormat{9, "scenarios/narrow_pass.yaml", "{algo: jps+}", 0, 300},
        OlderFormat{10, "scenarios/chokepoints/corridor_tanks_4.yaml", nullptr, 5, 400},
        OlderFormat{10, "scenarios/chokepoints/door_30v30.yaml", nullptr, 5, 600},
        OlderFormat{11, "scenarios/chokepoints/crossroads.yaml", nullptr, 0, 450},
        OlderFormat{12, "scenarios/narrow_pass.yaml", nullptr, 0, 900},
        OlderFormat{13, "scenarios/chokepoints/crossroads.yaml", nullptr, 0, 450},
        OlderFormat{14, "tests/fixtures/full_goal_area.yaml", nullptr, 0, INT64_MAX},
        OlderFormat{15, "tests/fixtures/one_way_door.yaml", nullptr, 0, 900},
        OlderFormat{16, "tests/fixtures/notched_edge.yaml", nullptr, 0, 600},
        OlderFormat{17, "scenarios/chokepoints/bridge_two_way.yaml", nullptr, 0, 600},
        OlderFormat{18, "scenarios/chokepoints/door_30v30.yaml", nullptr, 10, 600},
        OlderFormat{19, "scenarios/chokepoints/variations/bridge16_tanks.yaml", nullptr, 0, 600},
        OlderFormat{20, "scenarios/chokepoints/variations/bridge16_tanks.yaml", nullptr, 0, 900},
        OlderFormat{21, "scenarios/chokepoints/variations/bridge16_mixed.yaml", nullptr, 73, 300},
        OlderFormat{22, "scenarios/chokepoints/variations/corridor5_tanks_3v3.yaml", nullptr, 4,
                    2400},
        OlderFormat{23, "scenarios/demo.yaml", nullptr, 22, 2700},
        OlderFormat{24, "scenarios/chokepoints/bridge_two_way.yaml", nullptr, 0, 1500},
        OlderFormat{25, "scenarios/chokepoints/variations/bridge16_mixed.yaml", nullptr, 18, 600},
        OlderFormat{26, "scenarios/chokepoints/variations/corridor5_tanks_3v3.yaml", nullptr, 15,
                    2400},
        OlderFormat{27, "scenarios/chokepoints/variations/corridor5_tanks_3v3.yaml", nullptr, 165,
                    2400},
        OlderFormat{29, "scenarios/demo.yaml", nullptr, 156, 2700}),
    [](const ::testing::TestParamInfo<OlderFormat>& param) {
      // Format25_bridge16_mixed: the format and the scenario file's stem.
      return "Format" + std::to_string(param.param.format) + "_" +
             fs::path(param.param.scenario).stem().string();
    });

TEST_F(Replays, AnotherVersionIsRefused) {
  const fs::path file = record(1);
  std::string bytes = slurp(file);
  // Version 1 (move orders only, before battles): refused, saying what to do.
  bytes[8] = 1;
  spit(file, bytes);
  EXPECT_EQ(readError(file), file.string() +
                                 ": replay format version 1 is not supported (this build reads "
                                 "versions 2 to 30); it was written before battles were recorded: "
                                 "record it again with rts run --replay");
  RtsResult r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(file.string() + ": replay format version 1 is not supported"),
            std::string::npos)
      << r.out;
  bytes[8] = 31;
  spit(file, bytes);
  EXPECT_EQ(readError(file), file.string() +
                                 ": replay format version 31 is not supported (this build reads "
                                 "versions 2 to 30)");
  r = rts("replay info " + file.string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("version 31 is not supported"), std::string::npos) << r.out;
  EXPECT_EQ(rts("replay verify " + (dir_ / "none.rpl").string()).status, 2);
}

// A record whose checksums hold but whose hash differs: verify exits 1 naming the tick.
TEST_F(Replays, CliVerifyNamesTheFirstDifferingTick) {
  const fs::path file = (dir_ / "cli.rpl");
  RtsResult r = rts("run " + scenario().string() + " --quiet --replay " + file.string() +
                    " --replay-every 10");
  ASSERT_EQ(r.status, 0) << r.out;
  std::string bytes = slurp(file);
  // Records: scenario, two tick-0 orders, then hashes for ticks 10, 20, ...: the third is 30.
  const std::vector<std::size_t> records = recordOffsets(bytes);
  const std::size_t h = records[5];
  ASSERT_EQ(bytes[h], 'H');
  bytes[h + 9 + 8] ^= 0x01;  // the hash's low byte
  const std::uint32_t c = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + h + 9), 16));
  for (int b = 0; b < 4; ++b)
    bytes[h + 9 + 16 + static_cast<std::size_t>(b)] = static_cast<char>(c >> (8 * b));
  spit(file, bytes);
  r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find(file.string() + ": tick 30: state hash differs: expected "),
            std::string::npos)
      << r.out;
}

TEST_F(Replays, AnUntilRunLeavesAReplayThatVerifies) {
  const fs::path file = (dir_ / "until.rpl");
  RtsResult r = rts("run " + scenario().string() + " --quiet --until 100 --seed 99 --replay " +
                    file.string());
  ASSERT_EQ(r.status, 0) << r.out;
  r = rts("replay info " + file.string());
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("seed: 99\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ticks recorded: 100\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("status: stopped at a tick limit at tick 100"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("small.map (170 bytes)"), std::string::npos) << r.out;
  r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("verified 100 ticks, 101 state hashes match"), std::string::npos) << r.out;
}

// SIGINT between ticks: the run stops, the replay ends with an "interrupted" record and
// verifies. The signal is sent once the replay exists, i.e. after the handlers are installed.
TEST_F(Replays, AnInterruptedRunLeavesAReplayThatVerifies) {
  std::string text = slurp(scenario());
  text.replace(text.find("duration: 12"), 12, "duration: 100000");
  spit(dir_ / "long.yaml", text);
  const fs::path file = dir_ / "int.rpl";
  const std::string script = "'" + std::string(RTS_BINARY) + "' run '" +
                             (dir_ / "long.yaml").string() + "' --quiet --replay '" +
                             file.string() + "' & pid=$!; while [ ! -s '" + file.string() +
                             "' ]; do sleep 0.05; done; sleep 0.3; kill -INT $pid; wait $pid";
  const int raw = std::system(script.c_str());
  EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 1);  // interrupted: a partial run
  RtsResult r = rts("replay info " + file.string());
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("status: interrupted at tick"), std::string::npos) << r.out;
  r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 0) << r.out;
}

// Recording a replay changes nothing in the run.
TEST_F(Replays, RecordingDoesNotChangeTheRun) {
  record(3);
  Result<Scenario> plain = loadScenario(scenario());
  ASSERT_TRUE(plain.ok());
  ScenarioRun run(plain.value());
  warpath::testing::runOut(run);
  EXPECT_EQ(run.stateHash(), finalHash_);
}

// A battle: attack-move and attack orders (with targets), a reinforcement; the run ends when red
// has eliminated blue. Everything round-trips through the file and plays back to the same
// hashes, winner and statistics.
TEST_F(Replays, ABattleRecordsAndVerifies) {
  std::ofstream(dir_ / "battle.yaml") << battleScenario();
  const fs::path file = recordFile(dir_ / "battle.yaml", 1);
  EXPECT_EQ(finalReport_.winner, "red");
  EXPECT_GT(finalReport_.endTick, 0);
  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok()) << replay.error().describe();
  EXPECT_EQ(replay.value().version, kReplayVersion);
  EXPECT_EQ(describe(replay.value().orders), describe(issuedOrders_));
  ASSERT_EQ(replay.value().orders.size(), 4u);
  EXPECT_EQ(replay.value().orders[2].kind, IssuedKind::Reinforce);
  EXPECT_EQ(replay.value().orders[2].group, 2);
  EXPECT_EQ(replay.value().orders[3].command.kind, OrderKind::Attack);
  EXPECT_FALSE(replay.value().orders[3].command.targets.empty());  // blue's living units
  ASSERT_TRUE(replay.value().end);
  EXPECT_EQ(replay.value().end->reason, ReplayEnd::Complete);  // the battle ended
  EXPECT_EQ(replay.value().end->last.tick, finalReport_.endTick);

  Result<ReplayPlayback> playback = ReplayPlayback::open(replay.value(), file.string());
  ASSERT_TRUE(playback.ok()) << playback.error().describe();
  const VerifyOutcome outcome = verifyReplay(playback.value());
  EXPECT_FALSE(outcome.mismatch);
  EXPECT_EQ(outcome.ticks, finalReport_.endTick);
  const Report played = playback.value().run().report();
  EXPECT_EQ(played.winner, "red");
  EXPECT_EQ(played.victory, finalReport_.victory);
  EXPECT_EQ(played.endTick, finalReport_.endTick);
  EXPECT_EQ(played.battle, finalReport_.battle);
  EXPECT_TRUE(playback.value().done());

  const RtsResult info = rts("replay info " + file.string());
  EXPECT_EQ(info.status, 0) << info.out;
  EXPECT_NE(info.out.find("format version: 30\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("orders: 4 (2 attack_move, 1 attack, 1 reinforce)\n"), std::string::npos)
      << info.out;
  const RtsResult verify = rts("replay verify " + file.string());
  EXPECT_EQ(verify.status, 0) << verify.out;
}

// An end_battle is recorded, played back (the run stops at its tick) and shown by info; the CLI
// run ends there and its replay verifies.
TEST_F(Replays, AnEndBattleIsRecordedAndPlayedBack) {
  std::ofstream(dir_ / "end.yaml")
      << battleScenario("  - {name: stop, when: {at: 5}, do: [{end_battle: blue}]}\n");
  const fs::path file = dir_ / "end.rpl";
  RtsResult r = rts("run " + (dir_ / "end.yaml").string() + " --replay " + file.string());
  EXPECT_EQ(r.status, 1) << r.out;  // winner == red fails: the trigger gave it to blue
  EXPECT_NE(r.out.find("winner: blue (end_battle by trigger stop) at tick 150"), std::string::npos)
      << r.out;
  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok()) << replay.error().describe();
  ASSERT_FALSE(replay.value().orders.empty());
  EXPECT_EQ(describe({replay.value().orders.back()}),
            describe({IssuedOrder{150, IssuedKind::EndBattle, {}, 0}}));
  EXPECT_EQ(replay.value().lastTick(), 150);
  Result<ReplayPlayback> playback = ReplayPlayback::open(replay.value(), file.string());
  ASSERT_TRUE(playback.ok()) << playback.error().describe();
  EXPECT_FALSE(verifyReplay(playback.value()).mismatch);
  EXPECT_TRUE(playback.value().run().ended());
  EXPECT_EQ(playback.value().run().report().winner, "blue");
  r = rts("replay info " + file.string());
  EXPECT_NE(r.out.find("battle ended at tick 150 by the script, winner: blue"), std::string::npos)
      << r.out;
  r = rts("replay verify " + file.string());
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("verified 150 ticks"), std::string::npos) << r.out;
}

// Command streams that do not fit the scenario are refused before any re-simulation; a battle
// that ends in playback short of the replay's last tick is a mismatch, never a hang.
TEST_F(Replays, BattleCommandStreamsAreChecked) {
  std::ofstream(dir_ / "battle.yaml") << battleScenario();
  const fs::path file = recordFile(dir_ / "battle.yaml", 1);
  Result<Replay> read = readReplay(file);
  ASSERT_TRUE(read.ok()) << read.error().describe();
  const Replay good = read.value();
  ASSERT_EQ(good.orders.size(), 4u);
  const std::int64_t t = good.orders[2].tick;
  const auto openError = [&](const Replay& bad) {
    Result<ReplayPlayback> p = ReplayPlayback::open(bad, file.string());
    EXPECT_FALSE(p.ok());
    return p.ok() ? std::string() : p.error().describe();
  };
  const std::string at = file.string() + ": the order at tick " + std::to_string(t);

  Replay bad = good;  // the reinforcements ordered before they came
  std::swap(bad.orders[2], bad.orders[3]);
  EXPECT_EQ(openError(bad), at + " names a unit the scenario never spawns");
  bad = good;  // blue's units attacking a unit that never comes
  bad.orders[0].command.kind = OrderKind::Attack;
  bad.orders[0].command.targets = {{99, 0}};
  EXPECT_EQ(openError(bad), file.string() +
                                ": the order at tick 0 targets a unit the scenario "
                                "never spawns");
  bad = good;  // a move needs an area on the map; a stop does not
  bad.orders[0].command.kind = OrderKind::Stop;
  bad.orders[0].command.area = {};
  EXPECT_TRUE(ReplayPlayback::open(bad, file.string()).ok());
  bad.orders[0].command.kind = OrderKind::Move;
  EXPECT_EQ(openError(bad),
            file.string() + ": the order at tick 0 moves to an area outside the map");
  bad = good;
  bad.orders[2].group = 0;
  EXPECT_EQ(openError(bad), at + " brings in group 'b' a second time");
  bad.orders[2].group = 7;
  EXPECT_EQ(openError(bad), at + " reinforces group 7, which the scenario does not have");
  bad = good;
  bad.orders.push_back({good.orders.back().tick, IssuedKind::EndBattle, {}, 2});
  EXPECT_EQ(openError(bad), file.string() + ": the order at tick " +
                                std::to_string(good.orders.back().tick) +
                                " ends the battle with team 2, which the scenario does not have");

  // An end at tick 100 that the recording run never had: the run state (ended, one more entry
  // issued) differs from the recording's at the first hash after it, and playback stops.
  bad = good;
  bad.orders.insert(bad.orders.begin() + 2, IssuedOrder{100, IssuedKind::EndBattle, {}, -1});
  Result<ReplayPlayback> playback = ReplayPlayback::open(bad, file.string());
  ASSERT_TRUE(playback.ok()) << playback.error().describe();
  const VerifyOutcome outcome = verifyReplay(playback.value());
  ASSERT_TRUE(outcome.mismatch);
  EXPECT_EQ(outcome.mismatch->tick, 100);
  EXPECT_TRUE(playback.value().done());

  // Damaged kinds in the file are refused when read.
  std::string bytes = slurp(file);
  const std::vector<std::size_t> records = recordOffsets(bytes);
  const std::size_t o = records[1];  // the first order
  ASSERT_EQ(bytes[o], 'O');
  bytes[o + 9 + 8] = 9;  // the entry's kind, after its tick
  const std::uint32_t length = static_cast<std::uint32_t>(records[2] - o - 13);
  const std::uint32_t c = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + o + 9), length));
  for (int b = 0; b < 4; ++b)
    bytes[o + 9 + length + static_cast<std::size_t>(b)] = static_cast<char>(c >> (8 * b));
  spit(file, bytes);
  EXPECT_EQ(readError(file), file.string() + ": record at byte " + std::to_string(o) +
                                 " is malformed: unknown order kind 9");
}

// A replay whose records claim ticks the scenario never reaches passes its checksums, but is
// refused on reading, naming the record: before, `replay verify` simulated "forever".
TEST_F(Replays, TicksPastTheScenarioEndAreRefused) {
  const fs::path file = record(1);  // 12 s at 30 Hz: ticks 0..360
  const std::string good = slurp(file);
  const std::vector<std::size_t> records = recordOffsets(good);
  const std::size_t end = records.back();
  ASSERT_EQ(good[end], 'E');
  const std::string number = std::to_string(records.size());

  std::string bad = good;
  rewritePayload(bad, end, 1, 5'000'000'000);  // the end record's tick, after its reason
  spit(file, bad);
  const std::string expected = file.string() + ": record " + number +
                               ": the end record at tick 5000000000, after the scenario's last "
                               "tick 360";
  EXPECT_EQ(readError(file), expected);
  for (const char* command : {"info", "verify"}) {
    const RtsResult r = rts(std::string("replay ") + command + " " + file.string());
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find(expected), std::string::npos) << r.out;
  }
  const RtsResult render =
      rts("replay render " + file.string() + " --frames " + (dir_ / "frames").string());
  EXPECT_EQ(render.status, 2) << render.out;
  EXPECT_FALSE(fs::exists(dir_ / "frames" / "frame_000000.png"));

  // The last state hash (the record before the end) claims a tick past the end.
  bad = good;
  const std::size_t hash = records[records.size() - 2];
  ASSERT_EQ(bad[hash], 'H');
  rewritePayload(bad, hash, 0, 361);
  spit(file, bad);
  EXPECT_EQ(readError(file), file.string() + ": record " + std::to_string(records.size() - 1) +
                                 ": a state hash at tick 361, after the scenario's last tick 360");

  // Ticks going backwards.
  bad = good;
  rewritePayload(bad, hash, 0, 3);
  spit(file, bad);
  EXPECT_EQ(readError(file), file.string() + ": record at byte " + std::to_string(hash) +
                                 " is malformed: hash ticks out of sequence");

  // An end before the ticks it follows.
  bad = good;
  const std::size_t order = records[1];
  ASSERT_EQ(bad[order], 'O');
  rewritePayload(bad, order, 0, 0);
  rewritePayload(bad, end, 1, 0);
  spit(file, bad);
  EXPECT_NE(readError(file).find(": the end record's tick precedes a recorded hash"),
            std::string::npos);
}

TEST_F(Replays, PlaybackStopsAtTheScenarioEnd) {
  const fs::path file = record(1);
  Result<Replay> replay = readReplay(file);
  ASSERT_TRUE(replay.ok()) << replay.error().describe();
  Replay changed = replay.value();
  changed.end->last.tick = 1'000'000'000;  // made in memory, never checked by readReplay
  const Result<ReplayPlayback> playback = ReplayPlayback::open(changed, file.string());
  ASSERT_FALSE(playback.ok());
  EXPECT_EQ(playback.error().describe(),
            file.string() + ": the replay goes on past the scenario's last tick 360");
}

// Files that are not replays are refused before they are read: quickly and in little memory.
TEST_F(Replays, NonReplayFilesAreRefusedAtOnce) {
  const fs::path sparse = dir_ / "sparse.rpl";
  { std::ofstream create(sparse); }
  fs::resize_file(sparse, 300 * warpath::kMiB);  // no disk blocks: a sparse file of zeros
  EXPECT_EQ(readError(sparse), sparse.string() + ": larger than the 256 MiB limit for replays");
  fs::resize_file(sparse, 200 * warpath::kMiB);  // within the cap: the header says no
  EXPECT_EQ(readError(sparse), sparse.string() + ": not a warpath replay (no WPREPLAY header)");
  EXPECT_EQ(readError("/dev/zero"), "/dev/zero: not a regular file");
  EXPECT_EQ(readError(dir_), dir_.string() + ": is a directory");
  EXPECT_EQ(readError(dir_ / "none.rpl"), (dir_ / "none.rpl").string() + ": no such file");
  for (const fs::path& f : {sparse, fs::path("/dev/zero"), dir_}) {
    for (const char* command : {"info", "verify"}) {
      const RtsResult r = rts(std::string("replay ") + command + " " + f.string());
      EXPECT_EQ(r.status, 2) << r.out;  // was 134: an uncaught std::ios_failure for a folder
      EXPECT_NE(r.out.find("rts: error: " + f.string() + ": "), std::string::npos) << r.out;
    }
  }
}

}  // namespace
