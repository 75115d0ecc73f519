// `rts replay verify|render|info`: re-simulate a replay from what it embeds, never the disk.

#include <fmt/core.h>

#include <map>
#include <string>

#include "engine/replay.h"
#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/render_support.h"
#include "rts/replay_support.h"

namespace warpath::tools {
namespace {

struct VerifyOptions {
  std::string file;
};

struct RenderOptions {
  std::string file;
  FrameOptions frames;
};

struct InfoOptions {
  std::string file;
};

void printMismatch(const std::string& file, const engine::HashMismatch& m) {
  if (m.battleEnded) {
    fmt::print(stderr,
               "{}: the battle ended in playback before tick {}, which the replay records "
               "(expected {:016x}, state hash where it ended {:016x})\n",
               file, m.tick, m.expected, m.actual);
    return;
  }
  fmt::print(stderr, "{}: tick {}: state hash differs: expected {:016x}, actual {:016x}\n", file,
             m.tick, m.expected, m.actual);
}

int runVerify(const VerifyOptions& options) {
  const engine::Replay replay = readReplayOrThrow(options.file);
  engine::ReplayPlayback playback = openPlaybackOrThrow(replay, options.file);
  const engine::VerifyOutcome outcome = engine::verifyReplay(playback);
  if (outcome.mismatch) {
    printMismatch(options.file, *outcome.mismatch);
    return kExitFailed;
  }
  fmt::print("{}: verified {} ticks, {} state hashes match{}\n", options.file, outcome.ticks,
             outcome.hashes,
             replay.end ? "" : " (the run was interrupted: verified up to its last recorded tick)");
  return kExitOk;
}

int runRender(const RenderOptions& options) {
  if (!options.frames.wanted())
    throw BadInput{"replay render: give --frames DIR, --gif FILE or --video FILE"};
  const engine::Replay replay = readReplayOrThrow(options.file);
  engine::ReplayPlayback playback = openPlaybackOrThrow(replay, options.file);
  const engine::Scenario& scenario = playback.scenario();
  FrameRecorder frames(options.frames, scenario.grid->map(), scenario.settings.tickRate,
                       static_cast<int>(scenario.teams.size()));
  frames.onTick(playback.run().world());
  while (!playback.done()) {
    if (const auto mismatch = playback.step()) {
      frames.finish();
      printMismatch(options.file, *mismatch);
      return kExitFailed;
    }
    frames.onTick(playback.run().world());
  }
  const int written = frames.finish();
  fmt::print("{}: {} ticks, {} frames written{}\n", options.file, playback.run().world().tick(),
             written, options.frames.destinations());
  return kExitOk;
}

int runInfo(const InfoOptions& options) {
  const engine::Replay replay = readReplayOrThrow(options.file);
  const engine::ReplaySource& s = replay.source;
  const Result<engine::Scenario> scenario = engine::replayScenario(replay);
  fmt::print("replay: {}\n", options.file);
  fmt::print("format version: {}\n", replay.version);
  fmt::print(
      "scenario: {} ({})\n",
      scenario.ok() ? scenario.value().name : "does not load: " + scenario.error().describe(),
      s.scenarioPath);
  fmt::print("seed: {}\n", s.seed);
  fmt::print("ticks recorded: {}\n", replay.lastTick());
  fmt::print("hash every: {} ticks ({} hashes)\n", s.hashEvery, replay.hashes.size());
  // The command stream by kind: orders by what they tell, then reinforcements and the end.
  std::map<std::string_view, int> kinds;
  for (const engine::IssuedOrder& o : replay.orders) {
    ++kinds[o.kind == engine::IssuedKind::Order ? engine::toString(o.command.kind)
                                                : engine::kIssuedKindNames.name(o.kind)];
  }
  std::vector<std::string_view> names;  // table order: the orders, then the other entries
  for (const auto& row : engine::kOrderKindNames.rows())
    names.push_back(row.name);
  for (const auto& row : engine::kIssuedKindNames.rows())
    if (row.value != engine::IssuedKind::Order) names.push_back(row.name);
  std::string byKind;
  for (std::string_view k : names) {
    if (const auto it = kinds.find(k); it != kinds.end())
      byKind += fmt::format("{}{} {}", byKind.empty() ? "" : ", ", it->second, k);
  }
  fmt::print("orders: {}{}\n", replay.orders.size(), byKind.empty() ? "" : " (" + byKind + ")");
  for (const engine::IssuedOrder& o : replay.orders) {
    if (o.kind == engine::IssuedKind::EndBattle) {
      fmt::print("battle ended at tick {} by the script, winner: {}\n", o.tick,
                 o.group < 0 || !scenario.ok() ||
                         static_cast<std::size_t>(o.group) >= scenario.value().teams.size()
                     ? std::string("none")
                     : scenario.value().teams[static_cast<std::size_t>(o.group)]);
    }
  }
  fmt::print("embedded files:\n  {} ({} bytes, the scenario)\n", s.scenarioPath,
             s.scenarioText.size());
  for (const engine::ReplayFile& f : s.files)
    fmt::print("  {} ({} bytes)\n", f.path, f.contents.size());
  if (replay.end) {
    fmt::print("status: {} at tick {}\n", engine::toString(replay.end->reason),
               replay.end->last.tick);
  } else {
    fmt::print("status: interrupted (no end record: the recording run did not finish)\n");
  }
  return kExitOk;
}

}  // namespace

void registerReplayCommand(CLI::App& app, CommandRunner& run) {
  CLI::App* replay =
      app.add_subcommand("replay", "Check, draw or describe a replay written by rts run --replay");
  replay->require_subcommand(1);

  auto [verify, verifyOptions] = addSubcommand<VerifyOptions>(
      *replay, run, "verify",
      "Re-simulate; exit 0 when every recorded state hash matches, 1 naming the first that "
      "differs",
      runVerify);
  verify->add_option("file", verifyOptions->file, "Replay file")->required();

  auto [render, renderOptions] = addSubcommand<RenderOptions>(
      *replay, run, "render", "Re-simulate and write frames (PNG) and/or an animated GIF",
      runRender);
  render->add_option("file", renderOptions->file, "Replay file")->required();
  addFrameOptions(*render, renderOptions->frames, "--every");

  auto [info, infoOptions] =
      addSubcommand<InfoOptions>(*replay, run, "info", "Summarise a replay", runInfo);
  info->add_option("file", infoOptions->file, "Replay file")->required();
}

}  // namespace warpath::tools
