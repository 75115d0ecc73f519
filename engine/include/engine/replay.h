#pragma once
// Self-contained replays (format in docs/replays.md): the scenario text and every file it
// read, the seed, the command stream (orders the world received, reinforcements, the end of
// the battle) and the state hash every N ticks. Written
// record by record and flushed after every tick, so a run that stops early still leaves a
// replay that verifies up to its last recorded tick. Every record carries CRC-32s; reading a
// truncated, corrupted or foreign file gives an error naming the file and the problem.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "pathing/enum_names.h"

namespace warpath::engine {

// 2: orders of every kind (move, attack-move, attack, hold, stop), reinforcements and the end of
// the battle. 3: the same records; the hashes are ScenarioRun::stateHash (the whole world and
// run state) instead of format 2's hand-picked field list, which is still computed
// (World::legacyStateHash) so that format-2 files verify. 4: the same records, recorded with
// cooperative movement (docs/cooperative.md); the hashes cover its state too (a format-3 file's
// hashes are computed without it: engine/state_description.h's Since). 5: the same, the hashes
// also covering each queued path request's cost profile (terrain costs, docs/terrain_costs.md).
// 6: terrain that changes (docs/terrain_changes.md): set_terrain entries in the command stream
// (an order record of kind set_terrain: the area, the terrain in the group field), wrecks of
// large units blocking planning, and the hashes covering the terrain changes and wreck
// obstacles. 7: the same records; a scenario that leaves `pathing: cooperative` out runs with
// cooperative movement on (the default since this format; older files play back with it off
// unless their scenario switched it on). 8: the same records; with cooperation, routes avoid
// queues at narrow places (congestion-aware routes, engine/congestion.h; older files play back
// without them), and the hashes cover each queued request's speed. 9: the same records and
// hashes; with `pathing: sliced` the cooperative window searches are sliced too (older files
// play back with only the spatial searches sliced). 10: the same records and hashes; `jps` and
// `jps+` expand only the forced turns of a straight jump point, and JPS+ pushes the goal alone
// from a jump point that has it in sight (older files play back with every side turn taken:
// pathing::JumpSuccessors::EverySide). 11: the same records and hashes; a unit kept out of a
// passage steps out of the stream and mouth a row at a time and does not wait there, and those
// kept out nearest to the passage are let through first (older files play back with
// pathing::KeepOutExit::HighestLevel, in the priority order of all). 12: the same records and
// hashes; vehicles' lanes go on through junctions too wide for lanes, and a walker stepping off
// a vehicle's course steps to the side with room (older files play back with lanes that end there,
// stepping aside on the side the walker is on). 13: the same records and hashes; a cooperating
// unit without a timed window that jams asks for a detour around the units standing in its way
// (older files play back asking for its path again). 14: the same records and hashes; a vehicle
// stopped in the traffic, but not by its own window or a passage's gate, claims its lane ahead,
// which another team's walkers step out of (older files play back with stopped vehicles
// claiming none). 15: the same records and hashes; a cooperating unit inside its goal area
// whose goal cell another parked on, and whose area has no other free cell for it, parks where
// it stands (older files play back with it pushing on). 16: the same records and hashes; the
// gate of a passage used one way only lets any number through, and walkers cross it without
// timed windows (older files play back with at most 8 through at a time, in windows). 17: the
// same records and hashes; a notch in a ragged edge (a dent) has passing room (older files play
// back with it a chokepoint). 18: the same records and hashes; a vehicle's lane holds its full
// shift for two footprints beyond its passage (older files play back with lanes ending at the
// mouth). 19: a cooperating unit's window without progress spent queued behind a unit going its
// way that made progress in its own last window does not count toward the stuck flag (the
// state hash covers the count; older files play back counting it). 20: the same records and
// hashes; a vehicle's lane holds for five footprints beyond a passage at least five footprints
// across (older files play back with two). 21: the same records and hashes; two vehicles meeting
// head on outside timed windows each veer to their right (older files play back pushing nose to
// nose). 22: the same records and hashes; a vehicle's lane may detour twice its largest shift,
// a unit's planned time (in the hash) is taken along its lane, and a vehicle veers right from a
// lighter one steering its way however that one moves (older files play back dropping lanes
// that cost more than the fixed allowance, with planned times taken before the lane, veering
// only from vehicles moving at them). 23: the same records and hashes; a unit kept out of a
// passage but standing inside it takes the turn from a holder going the other way that has not
// entered yet (older files play back with it waiting there, pushed back by the holder). 24: the
// same records and hashes; a unit waiting in its window on a teammate parked on the way into
// their goal area takes that one's goal cell and sends it on to its own (older files play back
// with it waiting on). 25: the same records and hashes; the turning-circle cap lets a unit pass
// within its waypoint's radius (older files play back slowing until it could pass through the
// waypoint's centre). 26: the same records and hashes; a vehicle a heavier one drives into steps
// off its course, and a unit turning about turns away from a wall when the shorter way is into
// it (older files play back with only the lightest kind stepping aside, turning the shorter
// way). 27: the same records and hashes; a unit kept out of a passage but standing inside it with
// the holder of its turn, who comes the other way, plans windows that back it out ahead of the
// holder (older files play back with it keeping its window and waiting to be pushed). 28: the
// same records and hashes; a unit pushed back along its path reads what lies ahead from where it
// stands and, pushed back farther than its length, heads for the path from there (older files
// play back with it going on from the waypoint it had reached). 29: the same records and hashes;
// a terrain change is checked against a unit's path from its place on it, so a unit pushed back
// along its path repaths for a change on the cells it must walk again (older files play back
// checking from the waypoint before the one it steers to). 30: the same records and hashes; a
// jammed unit asks for a way round the units standing in its way (unless all are teammates of
// its kind sent to its area) before a new goal cell, a way that may end at its goal when they
// stand just before it and that keeps clear of every unit standing in its region (older files play
// back asking for a new goal cell first, with no detour when they stand near the path's end and one
// kept clear only of those on the path). Version-1 files (move orders only) are refused with a
// message saying so.
inline constexpr std::uint32_t kReplayVersion = 30;
// Formats before this one were recorded before cooperative movement and play back without it.
inline constexpr std::uint32_t kFirstCooperativeReplayVersion = 4;
// Formats before this one were recorded before terrain changes: they play back with wrecks that
// block bodies but not plans (CombatSettings::wrecksBlock off).
inline constexpr std::uint32_t kFirstTerrainReplayVersion = 6;
// Formats before this one were recorded when cooperative movement was off by default.
inline constexpr std::uint32_t kCooperativeByDefaultReplayVersion = 7;
// Formats before this one were recorded before congestion-aware routes: they play back without.
inline constexpr std::uint32_t kFirstCongestionReplayVersion = 8;
// Formats before this one were recorded when `sliced` sliced the spatial searches only: they play
// back with window searches run to their end (PathServiceSettings::slicedWindows off).
inline constexpr std::uint32_t kFirstSlicedWindowsReplayVersion = 9;
// Formats before this one were recorded when jump point searches took every side turn of a
// straight jump point: they play back so (PathServiceSettings::jumpSuccessors EverySide).
inline constexpr std::uint32_t kFirstForcedJumpsReplayVersion = 10;
// Formats before this one were recorded when a unit kept out of a passage left its stream and
// mouth only by moves that lowered its footprint's highest level, and could wait where it
// started, and units kept out of a passage were let through in the priority order of all: they
// play back so (PathServiceSettings::keepOutExit HighestLevel, nearestKeptOutFirst false).
inline constexpr std::uint32_t kFirstKeptOutRulesReplayVersion = 11;
// Formats before this one were recorded when a vehicle's lane ended where the passage grew too
// wide for lanes, a junction included, and a walker stepping off a vehicle's course stepped to
// the side it was on even without room there: they play back so
// (PathServiceSettings::lanesThroughJunctions and stepAsideToRoom off).
inline constexpr std::uint32_t kFirstJunctionRulesReplayVersion = 12;
// Formats before this one were recorded when a cooperating unit without a timed window that
// jammed asked for the same path again: they play back so (PathServiceSettings::jamDetours off).
inline constexpr std::uint32_t kFirstJamDetoursReplayVersion = 13;
// Formats before this one were recorded when a vehicle stopped in the traffic claimed no lane:
// they play back so (PathServiceSettings::standingVehicleLanes off).
inline constexpr std::uint32_t kFirstStandingLanesReplayVersion = 14;
// Formats before this one were recorded when a cooperating unit whose goal area had no free cell
// left for it pushed on into the parked crowd: they play back so
// (PathServiceSettings::parkWhenAreaFull off).
inline constexpr std::uint32_t kFirstParkWhenFullReplayVersion = 15;
// Formats before this one were recorded when a passage's gate let at most 8 through at a time
// and walkers crossed it in timed windows even while nobody came the other way: they play back
// so (PathServiceSettings::oneWayPassages off).
inline constexpr std::uint32_t kFirstOneWayPassagesReplayVersion = 16;
// Formats before this one were recorded when a notch in a ragged edge was a chokepoint like a
// door: they play back so (PathServiceSettings::openDents off).
inline constexpr std::uint32_t kFirstOpenDentsReplayVersion = 17;
// Formats before this one were recorded when a vehicle's lane ended at its passage's mouth: they
// play back so (PathServiceSettings::laneApproaches off).
inline constexpr std::uint32_t kFirstLaneApproachesReplayVersion = 18;
// Formats before this one were recorded when a cooperating unit queued behind another counted
// its windows without progress toward the stuck flag: they play back so
// (PathServiceSettings::queuesExcused off).
inline constexpr std::uint32_t kFirstQueuesExcusedReplayVersion = 19;
// Formats before this one were recorded when a vehicle's lane held two footprints beyond its
// passage however wide: they play back so (PathServiceSettings::widerLaneApproaches off).
inline constexpr std::uint32_t kFirstWiderLaneApproachesReplayVersion = 20;
// Formats before this one were recorded when two vehicles meeting head on outside timed windows
// pushed nose to nose: they play back so (PathServiceSettings::headOnKeepRight off).
inline constexpr std::uint32_t kFirstHeadOnKeepRightReplayVersion = 21;
// Formats before this one were recorded when a vehicle's lane that cost more than two cells per
// cell of footprint side plus one was dropped however far it shifted, and a unit's planned time
// was taken before its lane, and a vehicle veered only from vehicles moving at it: they play
// back so (PathServiceSettings::wideLaneDetours, plannedTimeWithLanes and headOnByIntent off).
inline constexpr std::uint32_t kFirstWideLaneDetoursReplayVersion = 22;
// Formats before this one were recorded when a unit kept out of a passage waited where it
// stood even inside it: they play back so (PathServiceSettings::insideGoesFirst off).
inline constexpr std::uint32_t kFirstInsideGoesFirstReplayVersion = 23;
// Formats before this one were recorded when a unit waiting on a teammate parked in its way
// went on waiting: they play back so (PathServiceSettings::parkedMoveOn off).
inline constexpr std::uint32_t kFirstParkedMoveOnReplayVersion = 24;
// Formats before this one were recorded when the turning-circle cap made a unit pass through the
// centre of its waypoint: they play back so (PathServiceSettings::turnsWithinWaypoints off).
inline constexpr std::uint32_t kFirstTurnsWithinWaypointsReplayVersion = 25;
// Formats before this one were recorded when only the lightest kind stepped off a vehicle's
// course and units always turned the shorter way: they play back so
// (PathServiceSettings::lighterVehiclesStepAside and turnAwayFromWalls off).
inline constexpr std::uint32_t kFirstLighterVehiclesStepAsideReplayVersion = 26;
// Formats before this one were recorded when a unit kept out of a passage but caught inside it
// with the holder kept its window and waited to be pushed: they play back so
// (PathServiceSettings::keptOutBacksOut off).
inline constexpr std::uint32_t kFirstKeptOutBacksOutReplayVersion = 27;
// Formats before this one were recorded when a unit pushed back along its path went on from the
// waypoint it had reached, however far it was pushed: they play back so
// (PathServiceSettings::rewindPushedBack off).
inline constexpr std::uint32_t kFirstRewindPushedBackReplayVersion = 28;
// Formats before this one were recorded when a terrain change was checked against a unit's path
// from the waypoint before the one it steered to: they play back so
// (PathServiceSettings::routeFromPlaceOnPath off).
inline constexpr std::uint32_t kFirstRouteFromPlaceOnPathReplayVersion = 29;
// Formats before this one were recorded when a jammed unit asked for a new goal cell before a
// detour, and detours neither ended at the goal nor kept clear of units standing off the path:
// they play back so (PathServiceSettings::detoursToGoal off).
inline constexpr std::uint32_t kFirstDetoursToGoalReplayVersion = 30;
inline constexpr std::uint32_t kOldestReplayVersion = 2;

// A file the scenario read, under the path the scenario resolved for it.
struct ReplayFile {
  std::string path;
  std::string contents;
};

// Everything needed to rebuild the run's scenario and world.
struct ReplaySource {
  std::string scenarioPath;  // as given to `rts run`; relative files resolve against it
  std::string scenarioText;
  std::vector<ReplayFile> files;  // in the order the scenario read them
  std::uint64_t seed = 0;         // after any --seed override
  std::int64_t hashEvery = 1;     // [Unit: ticks] [Limit: >= 1]
};

struct TickHash {
  std::int64_t tick = 0;
  std::uint64_t hash = 0;
};

enum class ReplayEnd : std::uint8_t {
  Complete,     // ran to its end: the scenario's whole duration, or until the battle ended
  Stopped,      // stopped at a tick limit (--until)
  Interrupted,  // stopped by SIGINT/SIGTERM between ticks
};
// Why a run ended, as `rts replay info` says it.
inline constexpr EnumNames<ReplayEnd, 3> kReplayEndNames{{{
    {ReplayEnd::Complete, "complete"},
    {ReplayEnd::Stopped, "stopped at a tick limit"},
    {ReplayEnd::Interrupted, "interrupted"},
}}};
std::string_view toString(ReplayEnd end);

struct ReplayEndRecord {
  ReplayEnd reason = ReplayEnd::Complete;
  TickHash last;  // the final tick and its hash
};

struct Replay {
  std::uint32_t version = kReplayVersion;
  ReplaySource source;
  std::vector<IssuedOrder> orders;  // ascending tick
  std::vector<TickHash> hashes;     // ascending tick, every source.hashEvery ticks
  // Absent when the writer never finished (killed, or the file was cut at a record boundary).
  std::optional<ReplayEndRecord> end;

  // The last tick the replay vouches for: the end record's, else the last hash's.
  std::int64_t lastTick() const;
};

// Loads a scenario from disk as loadScenario does and keeps in `source` the scenario's text and
// every file it read (seed and hash interval are left to the caller).
Result<Scenario> loadRecordedScenario(const std::filesystem::path& file, ReplaySource& source);

// Reads and checks a whole replay, the header first, then record by record (through
// CappedFile, at most kReplayFileLimit bytes). Errors: "FILE: problem" (an Error with line 0);
// a tick past the embedded scenario's duration: "FILE: record N: problem".
Result<Replay> readReplay(const std::filesystem::path& file);

// The embedded scenario, its map and catalogue read from the replay, never from disk. It is
// parsed with the path service's defaults of the replay's format (rulesOfReplayFormat): keys
// the scenario sets keep their values.
Result<Scenario> replayScenario(const Replay& replay);

// `rules` with every rule that came after replay format `version` set back as files of that
// format play back (the kFirst...ReplayVersion constants above say which rule came when).
// replayScenario applies it to the defaults; the replay tests record files of older formats with
// it.
void rulesOfReplayFormat(PathServiceSettings& rules, std::uint32_t version);

// Appends a replay while a ScenarioRun runs: record() after construction and after every step,
// finish() at the end. Each call flushes. Errors name the file.
class ReplayWriter {
 public:
  // `format`: the version written and the state layout hashed, for files an older build could
  // have written (tests of compatibility); the run must be set up as that format plays back
  // (ReplayPlayback::open). [Limit: 3..kReplayVersion, else an error]
  static Result<ReplayWriter> open(const std::filesystem::path& file, const ReplaySource& source,
                                   std::uint32_t format = kReplayVersion);
  // The orders given since the last call and, when the tick is a multiple of hashEvery, the
  // world's hash.
  Status record(const ScenarioRun& run);
  Status finish(const ScenarioRun& run, ReplayEnd reason);

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  ReplayWriter(std::string file, std::unique_ptr<std::FILE, Closer> out, std::int64_t every,
               std::uint32_t format)
      : file_(std::move(file)), out_(std::move(out)), every_(every), format_(format) {}
  Status append(char kind, const std::string& payload);

  std::string file_;
  std::unique_ptr<std::FILE, Closer> out_;
  std::int64_t every_ = 1;
  std::uint32_t format_ = kReplayVersion;
  std::size_t ordersWritten_ = 0;
  std::int64_t lastHashed_ = 0;
};

struct HashMismatch {
  std::int64_t tick = 0;
  std::uint64_t expected = 0;
  std::uint64_t actual = 0;
  // The battle ended in playback before the replay's last tick (so it never reached `tick`,
  // the next tick the replay vouches for); `actual` is the hash where it stopped.
  bool battleEnded = false;
};

// Re-simulates a replay: its embedded scenario, recorded seed and recorded orders. Movable.
class ReplayPlayback {
 public:
  // `replay` must outlive the playback. Errors name `file` and the problem (an embedded scenario
  // that no longer loads, an order naming a unit the scenario never spawns).
  static Result<ReplayPlayback> open(const Replay& replay, const std::string& file);

  // Steps once; a mismatch when the new tick has a recorded hash that differs, or when the
  // battle has already ended short of the replay's last tick (the world cannot step on).
  std::optional<HashMismatch> step();
  // Starts again from tick 0 (scrubbing back: worlds cannot be copied, so re-simulate).
  void restart();
  // The last tick playback goes to: the replay's, never past the scenario's duration.
  std::int64_t lastTick() const;
  // At lastTick(), or the battle ended.
  bool done() const;
  const ScenarioRun& run() const { return *run_; }
  const Scenario& scenario() const { return *scenario_; }
  const Replay& replay() const { return *replay_; }

 private:
  // The hash the replay's format recorded, for the state after the last step.
  std::uint64_t recordedHash() const;
  ReplayPlayback(const Replay& replay, std::unique_ptr<Scenario> scenario);

  const Replay* replay_;
  std::unique_ptr<Scenario> scenario_;  // stable address: the run refers to it
  std::unique_ptr<ScenarioRun> run_;
  std::size_t nextHash_ = 0;
};

struct VerifyOutcome {
  std::int64_t ticks = 0;   // ticks re-simulated
  std::int64_t hashes = 0;  // hashes compared (the end record's included)
  std::optional<HashMismatch> mismatch;
};

// Re-simulates to the replay's last tick, stopping at the first hash that differs.
VerifyOutcome verifyReplay(ReplayPlayback& playback);

}  // namespace warpath::engine
