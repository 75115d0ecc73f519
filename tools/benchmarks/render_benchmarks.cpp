// Google Benchmark targets for rts_render: frames per second (items_per_second) for a
// 200-unit scene on the demo map, rendering alone and rendering plus PNG encoding, at 512^2
// and 1024^2. For one core: LP_NUM_THREADS=0 taskset -c 0 build/tools/render_benchmarks
// (llvmpipe otherwise rasterises on a thread per core).

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

#include "pathing/map_io.h"
#include "render/png_io.h"
#include "render/renderer.h"
#include "render/sample_scene.h"

namespace {

using namespace warpath;

pathing::GridMap demoMap() {
  auto map = pathing::loadMap(WARPATH_SOURCE_DIR "/assets/maps/demo.map");
  if (!map) {
    std::fprintf(stderr, "%s\n", map.error().describe().c_str());
    std::exit(2);
  }
  return std::move(map).value();
}

render::Renderer makeRenderer(const pathing::GridMap& map, int side) {
  render::RenderDef def{.width = side, .height = side};
  def.overlays.paths = true;
  auto renderer = render::Renderer::create(map, def);
  if (!renderer) {
    std::fprintf(stderr, "%s\n", renderer.error().describe().c_str());
    std::exit(2);
  }
  return std::move(renderer).value();
}

// Moves every unit a little each frame, as a running simulation would.
void advance(render::FrameScene& scene) {
  ++scene.tick;
  for (render::UnitView& u : scene.units)
    u.facing += 0.05f;
}

void BM_Render(benchmark::State& state) {
  const pathing::GridMap map = demoMap();
  render::Renderer renderer = makeRenderer(map, static_cast<int>(state.range(0)));
  render::FrameScene scene = render::sampleScene(map, {.units = 200});
  for (auto _ : state) {
    advance(scene);
    if (!renderer.render(scene)) state.SkipWithError("render failed");
    benchmark::DoNotOptimize(renderer.image().pixels.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Render)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond);

void BM_RenderAndPng(benchmark::State& state) {
  const pathing::GridMap map = demoMap();
  render::Renderer renderer = makeRenderer(map, static_cast<int>(state.range(0)));
  render::FrameScene scene = render::sampleScene(map, {.units = 200});
  std::size_t bytes = 0;
  for (auto _ : state) {
    advance(scene);
    if (!renderer.render(scene)) state.SkipWithError("render failed");
    auto png = render::encodePng(renderer.image());
    if (!png) state.SkipWithError("PNG encoding failed");
    bytes = png.value().size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["png_bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_RenderAndPng)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
