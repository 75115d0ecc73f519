#include "engine/replay.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <map>
#include <string_view>

namespace warpath::engine {

namespace fs = std::filesystem;

namespace {

constexpr std::array<char, 8> kMagic = {'W', 'P', 'R', 'E', 'P', 'L', 'A', 'Y'};
constexpr std::size_t kFileHeader = kMagic.size() + 4;  // magic, version
// A record: kind (1), payload length (4), CRC-32 of those five bytes (4), payload, CRC-32 of
// the payload (4). The header's own CRC tells a corrupted length from a truncated file.
constexpr std::size_t kRecordHead = 9;
constexpr std::size_t kRecordTail = 4;

std::uint32_t crc(const void* data, std::size_t size) {
  return static_cast<std::uint32_t>(
      crc32(0L, static_cast<const Bytef*>(data), static_cast<uInt>(size)));
}

// Little-endian encoding, independent of the host.
class Encoder {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
      u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i)
      u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void i32(int v) { u32(static_cast<std::uint32_t>(v)); }
  void i64(std::int64_t v) { u64(static_cast<std::uint64_t>(v)); }
  void str(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes_.append(s);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// Thrown inside the reader only; readReplay turns it into an Error.
struct Malformed {
  std::string problem;
};
// A well-formed record that cannot be true of the embedded scenario (a tick past its end, an
// end before an order): "FILE: record N: problem".
struct Impossible {
  std::string problem;
};

class Decoder {
 public:
  explicit Decoder(std::string_view bytes) : bytes_(bytes) {}
  std::uint8_t u8() {
    need(1);
    return static_cast<std::uint8_t>(bytes_[at_++]);
  }
  std::uint32_t u32() {
    need(4);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
      v |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes_[at_++])) << (8 * i);
    return v;
  }
  std::uint64_t u64() {
    need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
      v |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(bytes_[at_++])) << (8 * i);
    return v;
  }
  int i32() { return static_cast<int>(u32()); }
  std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
  std::string str() {
    const std::uint32_t n = u32();
    need(n);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  bool empty() const { return at_ == bytes_.size(); }
  std::size_t left() const { return bytes_.size() - at_; }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) throw Malformed{"a record's contents end early"};
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

std::string sourcePayload(const ReplaySource& s) {
  Encoder e;
  e.str(s.scenarioPath);
  e.str(s.scenarioText);
  e.u64(s.seed);
  e.i64(s.hashEvery);
  e.u32(static_cast<std::uint32_t>(s.files.size()));
  for (const ReplayFile& f : s.files) {
    e.str(f.path);
    e.str(f.contents);
  }
  return e.bytes();
}

ReplaySource decodeSource(Decoder& d) {
  ReplaySource s;
  s.scenarioPath = d.str();
  s.scenarioText = d.str();
  if (s.scenarioText.size() > kYamlFileLimit.maxBytes)
    throw Malformed{"the embedded scenario is " + fileTooLarge("", kYamlFileLimit).message};
  s.seed = d.u64();
  s.hashEvery = d.i64();
  if (s.hashEvery < 1) throw Malformed{"the hash interval must be at least 1"};
  const std::uint32_t n = d.u32();
  if (n > d.left() / 8) throw Malformed{"the scenario record lists more files than it holds"};
  for (std::uint32_t i = 0; i < n; ++i) {
    ReplayFile f;
    f.path = d.str();
    f.contents = d.str();
    s.files.push_back(std::move(f));
  }
  return s;
}

void putUnits(Encoder& e, const std::vector<UnitId>& ids) {
  e.u32(static_cast<std::uint32_t>(ids.size()));
  for (UnitId id : ids) {
    e.u32(id.index);
    e.u32(id.generation);
  }
}

std::vector<UnitId> getUnits(Decoder& d, const char* what) {
  const std::uint32_t n = d.u32();
  if (n > d.left() / 8)
    throw Malformed{std::string("an order lists more ") + what + " than it holds"};
  std::vector<UnitId> ids;
  ids.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t index = d.u32();
    ids.push_back({index, d.u32()});
  }
  return ids;
}

std::string orderPayload(const IssuedOrder& o) {
  Encoder e;
  e.i64(o.tick);
  e.u8(static_cast<std::uint8_t>(o.kind));
  e.i32(o.group);
  e.u8(static_cast<std::uint8_t>(o.command.kind));
  e.i32(o.command.area.x);
  e.i32(o.command.area.y);
  e.i32(o.command.area.width);
  e.i32(o.command.area.height);
  putUnits(e, o.command.units);
  putUnits(e, o.command.targets);
  return e.bytes();
}

IssuedOrder decodeOrder(Decoder& d) {
  IssuedOrder o;
  o.tick = d.i64();
  const std::uint8_t kind = d.u8();
  if (kind > static_cast<std::uint8_t>(IssuedKind::SetTerrain))
    throw Malformed{"unknown order kind " + std::to_string(kind)};
  o.kind = static_cast<IssuedKind>(kind);
  o.group = d.i32();
  const std::uint8_t command = d.u8();
  if (command > static_cast<std::uint8_t>(OrderKind::Hold))
    throw Malformed{"unknown command kind " + std::to_string(command)};
  o.command.kind = static_cast<OrderKind>(command);
  o.command.area = {d.i32(), d.i32(), d.i32(), d.i32()};
  o.command.units = getUnits(d, "units");
  o.command.targets = getUnits(d, "targets");
  return o;
}

std::string hashPayload(TickHash h) {
  Encoder e;
  e.i64(h.tick);
  e.u64(h.hash);
  return e.bytes();
}

std::string endPayload(const ReplayEndRecord& end) {
  Encoder e;
  e.u8(static_cast<std::uint8_t>(end.reason));
  e.i64(end.last.tick);
  e.u64(end.last.hash);
  return e.bytes();
}

// "an order at tick 5000000000, after the scenario's last tick 1800".
std::string pastTheEnd(const char* what, std::int64_t tick, std::int64_t lastTick) {
  return std::string(what) + " at tick " + std::to_string(tick) +
         ", after the scenario's last tick " + std::to_string(lastTick);
}

// Adds one record's contents to `replay`, checking the order records must come in and that no
// tick lies past `lastTick` (the embedded scenario's duration, once the scenario record is in).
void addRecord(Replay& replay, bool& haveSource, char kind, Decoder& d, std::int64_t lastTick) {
  if (replay.end) throw Malformed{"a record follows the end record"};
  if (!haveSource && kind != 'S') throw Malformed{"the first record is not the scenario"};
  switch (kind) {
    case 'S':
      if (haveSource) throw Malformed{"a second scenario record"};
      replay.source = decodeSource(d);
      haveSource = true;
      break;
    case 'O': {
      IssuedOrder o = decodeOrder(d);
      if (o.tick < 0 || (!replay.orders.empty() && o.tick < replay.orders.back().tick))
        throw Malformed{"order ticks out of sequence"};
      if (o.tick > lastTick) throw Impossible{pastTheEnd("an order", o.tick, lastTick)};
      replay.orders.push_back(std::move(o));
      break;
    }
    case 'H': {
      const TickHash h{d.i64(), d.u64()};
      if (h.tick <= (replay.hashes.empty() ? 0 : replay.hashes.back().tick))
        throw Malformed{"hash ticks out of sequence"};
      if (h.tick > lastTick) throw Impossible{pastTheEnd("a state hash", h.tick, lastTick)};
      replay.hashes.push_back(h);
      break;
    }
    case 'E': {
      const std::uint8_t reason = d.u8();
      if (reason > static_cast<std::uint8_t>(ReplayEnd::Interrupted))
        throw Malformed{"unknown end reason " + std::to_string(reason)};
      ReplayEndRecord end{static_cast<ReplayEnd>(reason), {d.i64(), d.u64()}};
      if (end.last.tick < (replay.hashes.empty() ? 0 : replay.hashes.back().tick))
        throw Malformed{"the end record's tick precedes a recorded hash"};
      if (end.last.tick > lastTick)
        throw Impossible{pastTheEnd("the end record", end.last.tick, lastTick)};
      if (!replay.orders.empty() && end.last.tick < replay.orders.back().tick)
        throw Impossible{"the end record's tick " + std::to_string(end.last.tick) +
                         " precedes an order at tick " + std::to_string(replay.orders.back().tick)};
      replay.end = end;
      break;
    }
    default:
      throw Malformed{"unknown record kind " + std::to_string(static_cast<unsigned char>(kind))};
  }
  if (!d.empty()) throw Malformed{"a record holds more than its contents"};
}

}  // namespace

std::string_view toString(ReplayEnd end) {
  return kReplayEndNames.name(end);
}

std::int64_t Replay::lastTick() const {
  if (end) return end->last.tick;
  return hashes.empty() ? 0 : hashes.back().tick;
}

Result<Scenario> loadRecordedScenario(const fs::path& file, ReplaySource& source) {
  const Result<std::string> text = readDiskFile(file, kYamlFileLimit);
  if (!text) return text.error();
  source.scenarioPath = file.generic_string();
  source.scenarioText = text.value();
  source.files.clear();
  const FileReader recording = [&source](const fs::path& f, FileLimit limit) {
    Result<std::string> contents = readDiskFile(f, limit);
    if (contents) source.files.push_back({f.generic_string(), contents.value()});
    return contents;
  };
  return parseScenario(text.value(), source.scenarioPath, recording);
}

Result<Replay> readReplay(const fs::path& file) {
  const auto fail = [&](const std::string& problem) -> Result<Replay> {
    return Error{file.string(), 0, 0, problem};
  };
  Result<CappedFile> opened = CappedFile::open(file, kReplayFileLimit);
  if (!opened) return opened.error();
  CappedFile& in = opened.value();
  // The header first: a file that is not a replay is refused before anything else is read.
  std::string header;
  if (Result<std::size_t> got = in.read(header, kFileHeader); !got) return got.error();
  if (header.size() < kFileHeader || !std::equal(kMagic.begin(), kMagic.end(), header.begin()))
    return fail("not a warpath replay (no WPREPLAY header)");

  Replay replay;
  replay.version = Decoder(std::string_view(header).substr(kMagic.size(), 4)).u32();
  if (replay.version < kOldestReplayVersion || replay.version > kReplayVersion) {
    std::string problem = "replay format version " + std::to_string(replay.version) +
                          " is not supported (this build reads versions " +
                          std::to_string(kOldestReplayVersion) + " to " +
                          std::to_string(kReplayVersion) + ")";
    if (replay.version < kOldestReplayVersion)
      problem +=
          "; it was written before battles were recorded: record it again with rts run "
          "--replay";
    return fail(problem);
  }
  // Then record by record: only one record's bytes are held at a time.
  bool haveSource = false;
  std::string record;
  std::int64_t lastTick = kMaxScenarioTicks;  // until the scenario record says otherwise
  for (std::int64_t number = 1;; ++number) {
    const std::uint64_t at = in.offset();
    record.clear();
    Result<std::size_t> got = in.read(record, kRecordHead);
    if (!got) return got.error();
    if (got.value() == 0) break;
    const std::string where = "record at byte " + std::to_string(at);
    if (got.value() < kRecordHead) {
      return fail("truncated in the middle of a record at byte " + std::to_string(at) +
                  " (the file ends " + std::to_string(got.value()) + " bytes into it)");
    }
    Decoder head(record);
    const char kind = static_cast<char>(head.u8());
    const std::uint32_t length = head.u32();
    if (head.u32() != crc(record.data(), 5))
      return fail(where + " is corrupted (header checksum mismatch)");
    const std::size_t total = kRecordHead + std::size_t{length} + kRecordTail;
    // The size stat gave bounds what a record may claim before anything is allocated.
    const std::uint64_t left = in.size() > at ? in.size() - at : 0;
    if (left < total) {
      return fail("truncated in the middle of a record at byte " + std::to_string(at) +
                  " (the file ends " + std::to_string(left) + " bytes into its " +
                  std::to_string(total) + ")");
    }
    got = in.read(record, length + kRecordTail);
    if (!got) return got.error();
    if (got.value() < length + kRecordTail) {
      return fail("truncated in the middle of a record at byte " + std::to_string(at) +
                  " (the file ends " + std::to_string(kRecordHead + got.value()) +
                  " bytes into its " + std::to_string(total) + ")");
    }
    const std::string_view payload = std::string_view(record).substr(kRecordHead, length);
    const std::uint32_t stored =
        Decoder(std::string_view(record).substr(kRecordHead + length, kRecordTail)).u32();
    if (stored != crc(payload.data(), payload.size()))
      return fail(where + " is corrupted (checksum mismatch)");
    try {
      Decoder d(payload);
      addRecord(replay, haveSource, kind, d, lastTick);
    } catch (const Malformed& m) {
      return fail(where + " is malformed: " + m.problem);
    } catch (const Impossible& m) {
      return fail("record " + std::to_string(number) + ": " + m.problem);
    }
    if (kind == 'S') {
      // Every later tick must lie within the embedded scenario's duration. A scenario whose
      // duration cannot be read is refused at playback; until then the schema's maximum holds.
      const Result<std::int64_t> ticks =
          scenarioDurationTicks(replay.source.scenarioText, replay.source.scenarioPath);
      if (ticks) lastTick = ticks.value();
    }
  }
  if (!haveSource) return fail("truncated: no scenario record");
  return replay;
}

void rulesOfReplayFormat(PathServiceSettings& rules, std::uint32_t version) {
  // A scenario that does not name these settings plays back as it was recorded: with
  // cooperation off before it became the default, without congestion-aware routes before they
  // came (no older scenario can name them), with window searches unsliced before they were,
  // with jump point searches taking every side turn before they took only forced ones, and
  // with units kept out of a passage leaving it by its highest level, and let through by the
  // priority order of all, before they stepped out and were let through nearest first, and
  // with vehicles' lanes ending at junctions, and walkers stepping aside on their side of a
  // vehicle, before lanes went on through junctions and walkers stepped to the side with room,
  // and with jammed units asking for their path again before detours, and stopped vehicles
  // claiming no lane before they claimed theirs, and units pushing on in a full goal area
  // before they parked where they stood there, and passages used one way letting 8 through at
  // a time, walkers in windows, before any number went through, walkers without windows, and
  // with every window without progress counted toward the stuck flag before queued units'
  // were not, and vehicles meeting head on pushing nose to nose before they veered right, and
  // vehicles dropping lanes that cost more than a fixed allowance before it grew with the shift,
  // and planned times taken before the lane, and vehicles veering only from vehicles moving at
  // them before they veered from lighter ones steering their way too, and units kept out of a
  // passage waiting inside it before they took the turn from a holder not yet in, and units
  // waiting on a parked teammate before it moved on, and units slowing to pass through their
  // waypoint's centre before they passed within its radius, and only the lightest kind
  // stepping off a vehicle's course, turning the shorter way, before lighter vehicles stepped
  // aside too and units turned away from walls, and units kept out of a passage but caught
  // inside it with the holder waiting to be pushed before they backed out ahead of it, and
  // units pushed back along their paths going on from the waypoint they had reached before they
  // went on from where they stood, and terrain changes checked against such a unit's path from
  // that waypoint before they were checked from where it stood.
  if (version < kCooperativeByDefaultReplayVersion) rules.cooperative = false;
  if (version < kFirstCongestionReplayVersion) rules.congestion = false;
  if (version < kFirstSlicedWindowsReplayVersion) rules.slicedWindows = false;
  if (version < kFirstForcedJumpsReplayVersion)
    rules.jumpSuccessors = pathing::JumpSuccessors::EverySide;
  if (version < kFirstKeptOutRulesReplayVersion) {
    rules.keepOutExit = pathing::KeepOutExit::HighestLevel;
    rules.nearestKeptOutFirst = false;
  }
  if (version < kFirstJunctionRulesReplayVersion) {
    rules.lanesThroughJunctions = false;
    rules.stepAsideToRoom = false;
  }
  if (version < kFirstJamDetoursReplayVersion) rules.jamDetours = false;
  if (version < kFirstStandingLanesReplayVersion) rules.standingVehicleLanes = false;
  if (version < kFirstParkWhenFullReplayVersion) rules.parkWhenAreaFull = false;
  if (version < kFirstOneWayPassagesReplayVersion) rules.oneWayPassages = false;
  if (version < kFirstOpenDentsReplayVersion) rules.openDents = false;
  if (version < kFirstLaneApproachesReplayVersion) rules.laneApproaches = false;
  if (version < kFirstQueuesExcusedReplayVersion) rules.queuesExcused = false;
  if (version < kFirstWiderLaneApproachesReplayVersion) rules.widerLaneApproaches = false;
  if (version < kFirstHeadOnKeepRightReplayVersion) rules.headOnKeepRight = false;
  if (version < kFirstWideLaneDetoursReplayVersion) {
    rules.wideLaneDetours = false;
    rules.plannedTimeWithLanes = false;
    rules.headOnByIntent = false;
  }
  if (version < kFirstInsideGoesFirstReplayVersion) rules.insideGoesFirst = false;
  if (version < kFirstParkedMoveOnReplayVersion) rules.parkedMoveOn = false;
  if (version < kFirstTurnsWithinWaypointsReplayVersion) rules.turnsWithinWaypoints = false;
  if (version < kFirstLighterVehiclesStepAsideReplayVersion) {
    rules.lighterVehiclesStepAside = false;
    rules.turnAwayFromWalls = false;
  }
  if (version < kFirstKeptOutBacksOutReplayVersion) rules.keptOutBacksOut = false;
  if (version < kFirstRewindPushedBackReplayVersion) rules.rewindPushedBack = false;
  if (version < kFirstRouteFromPlaceOnPathReplayVersion) rules.routeFromPlaceOnPath = false;
  if (version < kFirstDetoursToGoalReplayVersion) rules.detoursToGoal = false;
}

Result<Scenario> replayScenario(const Replay& replay) {
  std::map<std::string, const std::string*> embedded;
  for (const ReplayFile& f : replay.source.files)
    embedded[f.path] = &f.contents;
  const FileReader fromReplay = [&embedded](const fs::path& f,
                                            FileLimit limit) -> Result<std::string> {
    const auto it = embedded.find(f.generic_string());
    if (it == embedded.end()) return Error{f.string(), 0, 0, std::string(kNoSuchFile)};
    if (it->second->size() > limit.maxBytes) return fileTooLarge(f.string(), limit);
    return *it->second;
  };
  WorldSettings defaults;
  rulesOfReplayFormat(defaults.pathing, replay.version);
  return parseScenario(replay.source.scenarioText, replay.source.scenarioPath, fromReplay,
                       defaults);
}

Result<ReplayWriter> ReplayWriter::open(const fs::path& file, const ReplaySource& source,
                                        std::uint32_t format) {
  if (format < 3 || format > kReplayVersion)
    return Error{file.string(), 0, 0,
                 "cannot write replay format " + std::to_string(format) + " (3 to " +
                     std::to_string(kReplayVersion) + ")"};
  std::unique_ptr<std::FILE, Closer> out(std::fopen(file.c_str(), "wb"));
  if (!out) return Error{file.string(), 0, 0, "cannot create the replay"};
  ReplayWriter writer(file.string(), std::move(out), std::max<std::int64_t>(source.hashEvery, 1),
                      format);
  Encoder head;
  head.u32(format);
  if (std::fwrite(kMagic.data(), 1, kMagic.size(), writer.out_.get()) != kMagic.size() ||
      std::fwrite(head.bytes().data(), 1, 4, writer.out_.get()) != 4) {
    return Error{file.string(), 0, 0, "cannot write the replay"};
  }
  if (Status s = writer.append('S', sourcePayload(source)); !s) return s.error();
  return writer;
}

Status ReplayWriter::append(char kind, const std::string& payload) {
  Encoder head;
  head.u8(static_cast<std::uint8_t>(kind));
  head.u32(static_cast<std::uint32_t>(payload.size()));
  head.u32(crc(head.bytes().data(), head.bytes().size()));
  Encoder tail;
  tail.u32(crc(payload.data(), payload.size()));
  std::FILE* f = out_.get();
  if (std::fwrite(head.bytes().data(), 1, kRecordHead, f) != kRecordHead ||
      std::fwrite(payload.data(), 1, payload.size(), f) != payload.size() ||
      std::fwrite(tail.bytes().data(), 1, kRecordTail, f) != kRecordTail) {
    return Error{file_, 0, 0, "cannot write the replay"};
  }
  return Status::success();
}

Status ReplayWriter::record(const ScenarioRun& run) {
  const std::vector<IssuedOrder>& orders = run.issued();
  for (; ordersWritten_ < orders.size(); ++ordersWritten_) {
    if (Status s = append('O', orderPayload(orders[ordersWritten_])); !s) return s;
  }
  const std::int64_t tick = run.world().tick();
  if (tick > lastHashed_ && tick % every_ == 0) {
    if (Status s = append('H', hashPayload({tick, run.stateHash(format_)})); !s) return s;
    lastHashed_ = tick;
  }
  // Flushed every tick: a run killed between ticks leaves whole records behind.
  if (std::fflush(out_.get()) != 0) return Error{file_, 0, 0, "cannot write the replay"};
  return Status::success();
}

Status ReplayWriter::finish(const ScenarioRun& run, ReplayEnd reason) {
  if (Status s = record(run); !s) return s;
  if (Status s = append('E', endPayload({reason, {run.world().tick(), run.stateHash(format_)}}));
      !s)
    return s;
  if (std::fflush(out_.get()) != 0) return Error{file_, 0, 0, "cannot write the replay"};
  return Status::success();
}

ReplayPlayback::ReplayPlayback(const Replay& replay, std::unique_ptr<Scenario> scenario)
    : replay_(&replay), scenario_(std::move(scenario)) {
  restart();
}

namespace {

// Empty when `replay`'s command stream fits `scenario`, else the first entry that does not:
// units and targets the scenario has spawned by then (its groups in order, then each
// reinforcement as it comes), areas inside the map, reinforcement groups that exist and come
// in once, winners that are teams.
std::string scriptProblem(const Replay& replay, const Scenario& scenario) {
  // readReplay has checked this against the scenario's duration already; a Replay built or
  // changed in memory has not.
  if (replay.lastTick() > scenario.durationTicks() ||
      (!replay.orders.empty() && replay.orders.back().tick > scenario.durationTicks()))
    return "the replay goes on past the scenario's last tick " +
           std::to_string(scenario.durationTicks());
  std::uint32_t spawned = 0;
  std::vector<bool> in(scenario.groups.size(), false);
  for (std::size_t g = 0; g < scenario.groups.size(); ++g) {
    if (scenario.groups[g].reinforcement) continue;
    spawned += static_cast<std::uint32_t>(scenario.groups[g].anchors.size());
    in[g] = true;
  }
  const pathing::GridMap& map = scenario.grid->map();
  const auto known = [&](const std::vector<UnitId>& ids) {
    return std::all_of(ids.begin(), ids.end(),
                       [&](UnitId id) { return id.index < spawned && id.generation == 0; });
  };
  for (const IssuedOrder& o : replay.orders) {
    const std::string at = "the order at tick " + std::to_string(o.tick);
    switch (o.kind) {
      case IssuedKind::Order: {
        const pathing::CellRect& a = o.command.area;
        const bool inside = a.width >= 1 && a.height >= 1 && a.x >= 0 && a.y >= 0 &&
                            a.x <= map.width() - a.width && a.y <= map.height() - a.height;
        const bool needsArea =
            o.command.kind == OrderKind::Move || o.command.kind == OrderKind::AttackMove;
        if (needsArea && !inside) return at + " moves to an area outside the map";
        if (!known(o.command.units)) return at + " names a unit the scenario never spawns";
        if (!known(o.command.targets)) return at + " targets a unit the scenario never spawns";
        break;
      }
      case IssuedKind::Reinforce: {
        if (o.group < 0 || static_cast<std::size_t>(o.group) >= scenario.groups.size())
          return at + " reinforces group " + std::to_string(o.group) +
                 ", which the scenario does not have";
        const GroupSpec& g = scenario.groups[static_cast<std::size_t>(o.group)];
        if (!g.reinforcement || in[static_cast<std::size_t>(o.group)])
          return at + " brings in group '" + g.name + "' a second time";
        in[static_cast<std::size_t>(o.group)] = true;
        spawned += static_cast<std::uint32_t>(g.anchors.size());
        break;
      }
      case IssuedKind::EndBattle:
        if (o.group < -1 || o.group >= static_cast<int>(scenario.teams.size()))
          return at + " ends the battle with team " + std::to_string(o.group) +
                 ", which the scenario does not have";
        break;
      case IssuedKind::SetTerrain: {
        const pathing::CellRect& a = o.command.area;
        if (replay.version < kFirstTerrainReplayVersion)
          return at + " sets terrain, which format " + std::to_string(replay.version) +
                 " cannot record";
        if (!scenario.settings.terrainChanges)
          return at + " sets terrain, and the scenario has no set_terrain action";
        if (a.width < 1 || a.height < 1 || a.x < 0 || a.y < 0 || a.x > map.width() - a.width ||
            a.y > map.height() - a.height)
          return at + " sets the terrain of an area outside the map";
        if (o.group < 0 || o.group >= static_cast<int>(pathing::kTerrainNames.rows().size()))
          return at + " sets an unknown terrain " + std::to_string(o.group);
        break;
      }
    }
  }
  return {};
}

}  // namespace

Result<ReplayPlayback> ReplayPlayback::open(const Replay& replay, const std::string& file) {
  Result<Scenario> loaded = replayScenario(replay);
  if (!loaded.ok())
    return Error{file, 0, 0, "the embedded scenario does not load: " + loaded.error().describe()};
  if (const std::string problem = scriptProblem(replay, loaded.value()); !problem.empty())
    return Error{file, 0, 0, problem};
  auto scenario = std::make_unique<Scenario>(std::move(loaded).value());
  if (replay.version < kFirstCooperativeReplayVersion) {
    // Recorded before cooperative movement: replayed under the movement of its time.
    scenario->settings.pathing.cooperative = false;
  }
  if (replay.version < kFirstTerrainReplayVersion) {
    // Recorded before wrecks blocked planning: replayed with wrecks that block bodies only.
    scenario->settings.combat.wrecksBlock = false;
  }
  return ReplayPlayback(replay, std::move(scenario));
}

void ReplayPlayback::restart() {
  run_ = std::make_unique<ScenarioRun>(*scenario_, replay_->source.seed, replay_->orders);
  nextHash_ = 0;
}

std::int64_t ReplayPlayback::lastTick() const {
  return std::min(replay_->lastTick(), scenario_->durationTicks());
}

bool ReplayPlayback::done() const {
  return run_->world().tick() >= lastTick() || run_->ended();
}

std::uint64_t ReplayPlayback::recordedHash() const {
  return replay_->version >= 3 ? run_->stateHash(replay_->version)
                               : run_->world().legacyStateHash();
}

std::optional<HashMismatch> ReplayPlayback::step() {
  const std::vector<TickHash>& hashes = replay_->hashes;
  if (run_->ended()) {
    // The battle ended before the replay's last tick: the recording run went on, so playback
    // has departed from it. Named at the next tick the replay vouches for.
    const std::int64_t tick = run_->world().tick();
    while (nextHash_ < hashes.size() && hashes[nextHash_].tick <= tick)
      ++nextHash_;
    HashMismatch m{tick, 0, recordedHash(), true};
    if (nextHash_ < hashes.size()) {
      m.tick = hashes[nextHash_].tick;
      m.expected = hashes[nextHash_].hash;
    } else if (replay_->end) {
      m.tick = replay_->end->last.tick;
      m.expected = replay_->end->last.hash;
    }
    return m;
  }
  run_->step();
  const std::int64_t tick = run_->world().tick();
  const std::uint64_t actual = recordedHash();
  while (nextHash_ < hashes.size() && hashes[nextHash_].tick < tick)
    ++nextHash_;
  if (nextHash_ < hashes.size() && hashes[nextHash_].tick == tick &&
      hashes[nextHash_].hash != actual) {
    return HashMismatch{tick, hashes[nextHash_].hash, actual};
  }
  if (replay_->end && replay_->end->last.tick == tick && replay_->end->last.hash != actual)
    return HashMismatch{tick, replay_->end->last.hash, actual};
  return std::nullopt;
}

VerifyOutcome verifyReplay(ReplayPlayback& playback) {
  playback.restart();
  VerifyOutcome outcome;
  const Replay& replay = playback.replay();
  while (playback.run().world().tick() < playback.lastTick()) {
    outcome.mismatch = playback.step();
    outcome.ticks = playback.run().world().tick();
    if (outcome.mismatch) return outcome;
  }
  outcome.hashes = static_cast<std::int64_t>(
      std::count_if(replay.hashes.begin(), replay.hashes.end(),
                    [&](const TickHash& h) { return h.tick <= outcome.ticks; }));
  if (replay.end) ++outcome.hashes;
  return outcome;
}

}  // namespace warpath::engine
