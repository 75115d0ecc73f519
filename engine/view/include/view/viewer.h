#pragma once
// `rts view`: a window on a replay. Frames are drawn by the same renderer as `rts run --frames`
// (OSMesa, offscreen) and shown in an SDL2 window; the replay is re-simulated as it plays.
//
// Keys: space play/pause; right or '.' one tick on; left one tick back; shift+right / shift+left
// ten seconds on / back; Home / End the first / last tick; '+' / '-' speed x2 / x0.5; 1-7
// overlays (paths, footprints, stuck, zones, HUD, clearance, reserved windows); c the unit type
// clearance and graph are shown for;
// h the help line; q or Escape quit. Going back re-simulates from tick 0: worlds hold Box2D
// state and cannot be copied, and re-simulating the bundled scenarios takes well under a second.

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/replay.h"
#include "pathing/error.h"

namespace warpath::view {

struct ViewerDef {
  int size = 768;  // [Unit: pixels] [Limit: 16..8192] the window's longer side
  // [Unit: pixels] [Limit: 0, or 16..8192] the window's size at the start; 0: the map's shape
  // at `size`. The map is drawn as large as the window allows, keeping its shape, centred,
  // and again at the new size when the window is resized.
  int windowWidth = 0;
  int windowHeight = 0;
  // A PNG of the whole window as the last of framesThenExit frames leaves it; empty: none.
  std::string screenshot;
  int framesThenExit = 0;  // > 0: draw this many frames, then quit (tests under SDL's
                           // offscreen or dummy video driver)
  double speed = 1.0;      // [Limit: > 0] simulated seconds per wall second at the start
  bool paused = false;
  // Keys pressed one a frame from the first frame, as if typed (scripted runs, tests): SDL key
  // names ("Space", "Right", "End", "+", "1"), "Shift+" before one to hold shift;
  // "Window=WxH" resizes the window instead, as if its edge were dragged.
  std::vector<std::string> keys;
};

// "WIDTHxHEIGHT", each 16..8192 pixels, else nullopt.
std::optional<std::pair<int, int>> parseWindowSize(std::string_view text);

// Runs until the window is closed (or framesThenExit frames are drawn). Fails, naming the
// problem, when SDL, the window or the renderer cannot be set up, or the replay's hashes stop
// matching (the status names the tick).
Status runViewer(engine::ReplayPlayback& playback, const ViewerDef& def);

}  // namespace warpath::view
