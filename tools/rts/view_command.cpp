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
  std::string window;  // "WxH"
  view::ViewerDef def;
};

int runView(const ViewOptions& options) {
  view::ViewerDef def = options.def;
  if (!options.window.empty()) {
    const auto size = view::parseWindowSize(options.window);
    if (!size)
      throw BadInput{"--window: must be WIDTHxHEIGHT, each 16..8192, got '" + options.window + "'"};
    def.windowWidth = size->first;
    def.windowHeight = size->second;
  }
  if (!def.screenshot.empty() && def.framesThenExit <= 0)
    throw BadInput{"--screenshot needs --frames-then-exit (the frame it shows)"};
  const engine::Replay replay = readReplayOrThrow(options.file);
  engine::ReplayPlayback playback = openPlaybackOrThrow(replay, options.file);
  if (Status s = view::runViewer(playback, def); !s)
    throw BadInput{options.file + ": " + s.error().describe()};
  if (def.framesThenExit > 0) {
    fmt::print("{}: {} frames drawn, tick {}\n", options.file, def.framesThenExit,
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
  cmd->add_option("--window", options->window,
                  "The window's size at the start, WIDTHxHEIGHT (default: the map's shape at "
                  "--size); the map is scaled to the window, keeping its shape");
  cmd->add_option("--screenshot", options->def.screenshot,
                  "Write the window's last frame as a PNG (with --frames-then-exit)");
  cmd->add_option("--speed", options->def.speed, "Simulated seconds per second at the start (1)")
      ->check(positiveNumberUpTo(1e6));
  cmd->add_flag("--paused", options->def.paused, "Start paused");
  cmd->add_option("--keys", options->def.keys,
                  "Keys to press one a frame from the start (SDL names, Shift+ to hold shift; "
                  "Window=WxH resizes the window)")
      ->delimiter(',');
  cmd->add_option("--frames-then-exit", options->def.framesThenExit,
                  "Draw N frames, then quit (for tests under SDL_VIDEODRIVER=offscreen)")
      ->check(wholeNumberIn(1, 1'000'000'000));
}

}  // namespace warpath::tools
