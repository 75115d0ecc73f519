#pragma once
// Pictures for the CLI's subcommands, drawn by rts_render.

#include <CLI/App.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/world.h"
#include "pathing/annotated_grid.h"
#include "pathing/cluster_abstraction.h"
#include "render/frame_sink.h"
#include "render/renderer.h"
#include "rts/video_pipe.h"

namespace warpath::tools {

// Writes `file` (PNG): the map, the agent's footprint along `path` with the path's line, the
// agent at the goal facing its last move, and the abstraction's graph (edges usable by the
// agent) when `graph` is non-null. Throws BadInput naming the problem when it cannot.
void writePathPng(const std::string& file, const pathing::GridMap& map, pathing::Agent agent,
                  const std::vector<pathing::Cell>& path, const pathing::ClusterAbstraction* graph);

struct FrameOptions {
  std::string framesDir;  // PNG frames (frame_000123.png); empty: none
  std::string gif;        // animated GIF; empty: none
  std::string video;      // MP4 through ffmpeg (video_pipe.h); empty: none
  int every = 1;          // [Unit: ticks] [Limit: >= 1]
  int size = 512;         // [Unit: pixels] [Limit: 16..8192] the frame's longer side
  std::string overlays;   // overlay names to switch on (render::parseOverlays)
  bool wanted() const { return !framesDir.empty() || !gif.empty() || !video.empty(); }
  // Where they went: " to DIR, GIF FILE, video FILE" (the parts asked for).
  std::string destinations() const;
};

// --frames, `everyFlag` (a frame every N ticks), --gif, --video, --frame-size and --overlay on
// `cmd`.
void addFrameOptions(CLI::App& cmd, FrameOptions& options, const std::string& everyFlag);

// Frames of a running world: renders the world every `every` ticks and hands the frame to a
// FrameSink that encodes on a second thread. Throws BadInput naming what cannot be created or
// written.
class FrameRecorder {
 public:
  FrameRecorder(const FrameOptions& options, const pathing::GridMap& map, double tickRate,
                int teamCount);
  void onTick(const engine::World& world);
  // Waits for the encoder; returns the frames written.
  int finish();

 private:
  std::optional<render::Renderer> renderer_;
  std::optional<render::FrameSink> sink_;
  std::optional<VideoPipe> video_;
  int teamCount_ = 0;
};

}  // namespace warpath::tools
