#include "rts/render_support.h"

#include <algorithm>
#include <cmath>

#include "render/png_io.h"
#include "render/renderer.h"
#include "render/world_scene.h"
#include "rts/cli_support.h"

namespace warpath::tools {

namespace {
// Pixels a cell: as many as fit in ~1024 pixels, between 1 and 16.
constexpr int kTargetPixels = 1024;
}  // namespace

void writePathPng(const std::string& file, const pathing::GridMap& map, pathing::Agent agent,
                  const std::vector<pathing::Cell>& path,
                  const pathing::ClusterAbstraction* graph) {
  const int scale = std::clamp(kTargetPixels / std::max({map.width(), map.height(), 1}), 1, 16);
  render::RenderDef def{.width = std::max(1, map.width() * scale),
                        .height = std::max(1, map.height() * scale)};
  def.overlays = {.paths = true,
                  .footprints = true,
                  .abstractGraph = graph != nullptr,
                  .stuck = false,
                  .arrivalZones = false,
                  .hud = false};
  auto renderer = render::Renderer::create(map, def);
  if (!renderer) throw BadInput{"--png " + file + ": " + renderer.error().describe()};
  if (graph != nullptr) {
    if (Status s = renderer.value().setAbstractGraph(*graph, agent); !s) {
      throw BadInput{"--png " + file + ": " + s.error().describe()};
    }
  }

  // The agent at the start, facing its first move, with the rest of the path ahead of it.
  const float half = static_cast<float>(agent.size) / 2.0f;
  const auto centreOf = [&](pathing::Cell anchor) {  // anchor + size/2 = centre
    return render::Point{static_cast<float>(anchor.x) + half, static_cast<float>(anchor.y) + half};
  };
  render::UnitView unit{.size = agent.size, .type = 1};
  if (!path.empty()) unit.centre = centreOf(path.front());
  if (path.size() >= 2) {
    unit.facing = static_cast<float>(std::atan2(static_cast<double>(path[1].y - path[0].y),
                                                static_cast<double>(path[1].x - path[0].x)));
  }
  for (std::size_t i = 1; i < path.size(); ++i)
    unit.path.push_back(centreOf(path[i]));
  render::FrameScene scene;
  if (!path.empty()) scene.units.push_back(std::move(unit));
  if (Status s = renderer.value().render(scene); !s) {
    throw BadInput{"--png " + file + ": " + s.error().describe()};
  }
  if (Status s = render::writePng(file, renderer.value().image()); !s) {
    throw BadInput{"--png: " + s.error().describe()};
  }
}

std::string FrameOptions::destinations() const {
  return (framesDir.empty() ? "" : " to " + framesDir) + (gif.empty() ? "" : ", GIF " + gif) +
         (video.empty() ? "" : ", video " + video);
}

void addFrameOptions(CLI::App& cmd, FrameOptions& options, const std::string& everyFlag) {
  cmd.add_option("--frames", options.framesDir,
                 "Write a PNG frame (frame_000123.png, by tick) into this folder");
  cmd.add_option(everyFlag, options.every, "A frame every N ticks (default 1)")
      ->check(wholeNumberIn(1, 1'000'000'000));
  cmd.add_option("--gif", options.gif, "Write the frames as an animated GIF");
  cmd.add_option("--video", options.video,
                 "Write the frames as an MP4 video (H.264, through Debian's ffmpeg program)");
  cmd.add_option("--frame-size", options.size, "Pixels along the frame's longer side (default 512)")
      ->check(CLI::Range(16, 8192));
  cmd.add_option("--overlay", options.overlays,
                 "Overlays to switch on in frames: paths, footprints, reservations, stuck, zones, "
                 "hud, or none");
}

FrameRecorder::FrameRecorder(const FrameOptions& options, const pathing::GridMap& map,
                             double tickRate, int teamCount)
    : teamCount_(teamCount) {
  if (options.every < 1) throw BadInput{"--frame-every must be at least 1"};
  if (options.size < 16 || options.size > 8192) throw BadInput{"--frame-size must be 16..8192"};
  render::RenderDef def = render::fittedDef(map, options.size);
  auto overlays = render::parseOverlays(options.overlays);
  if (!overlays) throw BadInput{"--overlay: " + overlays.error().describe()};
  def.overlays = overlays.value();
  auto renderer = render::Renderer::create(map, def);
  if (!renderer) throw BadInput{"frames: " + renderer.error().describe()};
  renderer_.emplace(std::move(renderer).value());

  const double frameSeconds = options.every / tickRate;
  auto sink = render::FrameSink::open(
      {.framesDir = options.framesDir,
       .gifFile = options.gif,
       .every = options.every,
       .gifDelayCentiseconds = std::max(2, static_cast<int>(std::lround(frameSeconds * 100.0)))},
      def.width, def.height);
  if (!sink) throw BadInput{"frames: " + sink.error().describe()};
  sink_.emplace(std::move(sink).value());
  if (!options.video.empty())
    video_.emplace(options.video, def.width, def.height, 1.0 / frameSeconds);
}

void FrameRecorder::onTick(const engine::World& world) {
  if (!sink_->wants(world.tick())) return;
  if (Status s = renderer_->render(render::sceneOf(world, teamCount_)); !s) {
    throw BadInput{"frames: " + s.error().describe()};
  }
  if (Status s = sink_->submit(world.tick(), renderer_->image()); !s) {
    throw BadInput{"frames: " + s.error().describe()};
  }
  if (video_) video_->write(renderer_->image());
}

int FrameRecorder::finish() {
  if (Status s = sink_->finish(); !s) throw BadInput{"frames: " + s.error().describe()};
  const int videoFrames = video_ ? video_->finish() : 0;
  return std::max(sink_->framesWritten(), videoFrames);
}

}  // namespace warpath::tools
