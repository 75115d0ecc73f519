// `rts view FILE`: a window on a replay (engine/view), re-simulated from what the replay embeds.

#include <fmt/core.h>

#include <string>

#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/replay_support.h"
#include "view/viewer.h"

namespace warpath::tools {
namespace {

struct ViewOptions {
  std::string file;
  view::ViewerDef def;
};

int runView(const ViewOptions& options) {
  const engine::Replay replay = readReplayOrThrow(options.file);
  engine::ReplayPlayback playback = openPlaybackOrThrow(replay, options.file);
  if (Status s = view::runViewer(playback, options.def); !s)
    throw BadInput{options.file + ": " + s.error().describe()};
  if (options.def.framesThenExit > 0) {
    fmt::print("{}: {} frames drawn, tick {}\n", options.file, options.def.framesThenExit,
               playback.run().world().tick());
  }
  return kExitOk;
}

}  // namespace

void registerViewCommand(CLI::App& app, CommandRunner& run) {
  auto [cmd, options] = addSubcommand<ViewOptions>(
      app, run, "view",
      "Watch a replay in a window: space play/pause, right/. step, left back, shift+arrows 10 s, "
      "Home/End, +/- speed, 1-7 overlays, c unit type, h help, q quit",
      runView);
  cmd->add_option("file", options->file, "Replay file (rts run --replay)")->required();
  cmd->add_option("--size", options->def.size, "Pixels along the window's longer side (768)")
      ->check(CLI::Range(16, 8192));
  cmd->add_option("--speed", options->def.speed, "Simulated seconds per second at the start (1)")
      ->check(positiveNumberUpTo(1e6));
  cmd->add_flag("--paused", options->def.paused, "Start paused");
  cmd->add_option("--keys", options->def.keys,
                  "Keys to press one a frame from the start (SDL names, Shift+ to hold shift)")
      ->delimiter(',');
  cmd->add_option("--frames-then-exit", options->def.framesThenExit,
                  "Draw N frames, then quit (for tests under SDL_VIDEODRIVER=offscreen)")
      ->check(wholeNumberIn(1, 1'000'000'000));
}

}  // namespace warpath::tools
