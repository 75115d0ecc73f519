// The renderer, PNG and GIF writers and the frame sink, end to end through OSMesa.

#include <gif_lib.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/map_io.h"
#include "render/frame_sink.h"
#include "render/gif_writer.h"
#include "render/palette.h"
#include "render/png_io.h"
#include "render/renderer.h"
#include "render/sample_scene.h"

namespace warpath::render {
namespace {

namespace fs = std::filesystem;
using pathing::Cell;
using pathing::GridMap;
using pathing::Terrain;

// 24x16: ground, a swamp, a wood, a river with a ford, a wall.
GridMap tinyMap() {
  std::istringstream text(
      "type octile\nheight 16\nwidth 24\nmap\n"
      "........................\n"
      "..SSSS..........TTTT....\n"
      "..SSSS..........TTTT....\n"
      "..SSSS..........TTTT....\n"
      "........................\n"
      "..........WWW...........\n"
      "..........WWW.....@@@@..\n"
      "..........WWW.....@@@@..\n"
      "..........WWW...........\n"
      "..........SSS...........\n"
      "..........WWW...........\n"
      "..........WWW...TTT.....\n"
      "..........WWW...TTT.....\n"
      "..........WWW...........\n"
      "........................\n"
      "........................\n");
  auto map = pathing::parseMap(text, "tiny");
  EXPECT_TRUE(map.ok()) << map.error().describe();
  return map.value();
}

// Every kind of thing a frame shows, placed by hand.
FrameScene tinyScene() {
  FrameScene scene;
  scene.tick = 123;
  scene.seconds = 4.1;
  scene.teams = {{3, 1, 1}, {1, 0, 0}};
  scene.arrivalZones = {{{20, 12, 4, 4}, 0}};
  UnitView tank{.centre = {4.5f, 11.5f}, .size = 3, .team = 0, .type = 1, .facing = 0.0f};
  tank.path = {{8.5f, 11.5f}, {15.5f, 14.5f}, {21.5f, 14.5f}};
  scene.units.push_back(tank);
  scene.units.push_back(
      {.centre = {7.5f, 2.5f}, .size = 1, .team = 0, .type = 0, .facing = 1.5708f, .hp = 0.4f});
  scene.units.push_back(
      {.centre = {14.0f, 6.0f}, .size = 2, .team = 1, .type = 2, .facing = 3.1416f, .stuck = true});
  scene.units.push_back(
      {.centre = {19.0f, 10.0f}, .size = 2, .team = 1, .type = 3, .state = UnitState::Wreck});
  scene.units.push_back({.centre = {22.5f, 13.5f},
                         .size = 1,
                         .team = 0,
                         .type = 4,
                         .facing = -0.7f,
                         .state = UnitState::Arrived});
  return scene;
}

Renderer makeRenderer(const GridMap& map, RenderDef def) {
  auto renderer = Renderer::create(map, def);
  EXPECT_TRUE(renderer.ok()) << renderer.error().describe();
  return std::move(renderer).value();
}

const Image& renderOnce(Renderer& renderer, const FrameScene& scene) {
  const Status s = renderer.render(scene);
  EXPECT_TRUE(s.ok()) << s.error().describe();
  return renderer.image();
}

fs::path scratchDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("warpath_render_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<char> fileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Pixels whose channels differ from the reference's by more than `tolerance`.
int differingPixels(const Image& a, const Image& b, int tolerance) {
  int count = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const Rgba p = a.at(x, y), q = b.at(x, y);
      if (std::abs(p.r - q.r) > tolerance || std::abs(p.g - q.g) > tolerance ||
          std::abs(p.b - q.b) > tolerance) {
        ++count;
      }
    }
  }
  return count;
}

TEST(Renderer, MatchesTheGoldenImage) {
  const GridMap map = tinyMap();
  Renderer renderer = makeRenderer(map, {.width = 192, .height = 128});
  Overlays overlays;
  overlays.paths = true;
  renderer.setOverlays(overlays);
  const Image& image = renderOnce(renderer, tinyScene());

  const fs::path golden = fs::path(WARPATH_GOLDEN_DIR) / "tiny_scene.png";
  if (std::getenv("WARPATH_UPDATE_GOLDEN") != nullptr) {
    ASSERT_TRUE(writePng(golden, image).ok());
    GTEST_SKIP() << "rewrote " << golden;
  }
  auto reference = readPng(golden);
  ASSERT_TRUE(reference.ok()) << reference.error().describe()
                              << " (WARPATH_UPDATE_GOLDEN=1 rewrites it)";
  ASSERT_EQ(reference.value().width, image.width);
  ASSERT_EQ(reference.value().height, image.height);
  // Rasterisers may differ on edge pixels: allow small colour differences everywhere and a
  // few larger ones (0.5% of the pixels).
  const int budget = image.width * image.height / 200;
  EXPECT_LE(differingPixels(image, reference.value(), 8), budget)
      << "the frame differs from " << golden << "; inspect it, then WARPATH_UPDATE_GOLDEN=1";
}

TEST(Renderer, DrawsTerrainColoursExactly) {
  const GridMap map = tinyMap();
  // 8 pixels a cell; no HUD, no units: each cell's centre pixel is its terrain colour.
  Renderer renderer = makeRenderer(map, {.width = 192, .height = 128});
  renderer.setOverlays(Overlays{.stuck = false, .arrivalZones = false, .hud = false});
  const Image& image = renderOnce(renderer, FrameScene{});
  for (const Cell c : {Cell{0, 0}, Cell{3, 2}, Cell{17, 2}, Cell{11, 6}, Cell{19, 6}}) {
    EXPECT_EQ(image.at(c.x * 8 + 4, c.y * 8 + 4), palette::terrainColour(map.at(c)))
        << "cell " << c.x << "," << c.y;
  }
}

TEST(Renderer, CameraShowsARegion) {
  const GridMap map = tinyMap();
  // Cells 18..21 x 5..8 (ground, the wall's rows 6-7, ground) fill the picture, 16 pixels a cell.
  Renderer renderer = makeRenderer(
      map, {.width = 64,
            .height = 64,
            .camera = pathing::CellRect{18, 5, 4, 4},
            .overlays = Overlays{.stuck = false, .arrivalZones = false, .hud = false}});
  const Image& image = renderOnce(renderer, FrameScene{});
  EXPECT_EQ(image.at(8, 8), palette::kGround);     // cell 18,5
  EXPECT_EQ(image.at(8, 24), palette::kBlocked);   // cell 18,6
  EXPECT_EQ(image.at(56, 40), palette::kBlocked);  // cell 21,7
  EXPECT_EQ(image.at(56, 56), palette::kGround);   // cell 21,8
  EXPECT_FALSE(renderer.setCamera(pathing::CellRect{30, 30, 4, 4}).ok());
  EXPECT_FALSE(renderer.setCamera(pathing::CellRect{0, 0, 0, 4}).ok());
}

TEST(Renderer, EachOverlayChangesTheImage) {
  const GridMap map = tinyMap();
  const pathing::AnnotatedGrid grid(map);
  const pathing::Capability ground = pathing::Capability::of({Terrain::Ground, Terrain::Swamp});
  const auto abstraction = pathing::ClusterAbstraction::build(
      grid, {.clusterSize = 8, .maxAgentSize = 2, .capabilities = {ground}});
  const Overlays none{.stuck = false, .arrivalZones = false, .hud = false};
  Renderer renderer = makeRenderer(map, {.width = 192, .height = 128, .overlays = none});
  ASSERT_TRUE(renderer.setClearance(grid.clearance(ground)).ok());
  ASSERT_TRUE(renderer.setAbstractGraph(abstraction).ok());
  const FrameScene scene = tinyScene();
  const Image base = renderOnce(renderer, scene);

  const auto with = [&](auto set) {
    Overlays o = none;
    set(o);
    renderer.setOverlays(o);
    return renderOnce(renderer, scene);
  };
  const std::vector<std::pair<std::string, Image>> variants{
      {"paths", with([](Overlays& o) { o.paths = true; })},
      {"footprints", with([](Overlays& o) { o.footprints = true; })},
      {"clearance", with([](Overlays& o) { o.clearance = true; })},
      {"graph", with([](Overlays& o) { o.abstractGraph = true; })},
      {"stuck", with([](Overlays& o) { o.stuck = true; })},
      {"zones", with([](Overlays& o) { o.arrivalZones = true; })},
      {"hud", with([](Overlays& o) { o.hud = true; })}};
  for (const auto& [name, image] : variants)
    EXPECT_GT(differingPixels(base, image, 0), 20) << name;
  // Switching back reproduces the first frame exactly.
  renderer.setOverlays(none);
  EXPECT_EQ(renderOnce(renderer, scene), base);
}

// Pixels of exactly `colour` inside the pixel rectangle [x0, x1) x [y0, y1).
int pixelsOf(const Image& image, Rgba colour, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const Rgba p = image.at(x, y);
      n += p.r == colour.r && p.g == colour.g && p.b == colour.b ? 1 : 0;
    }
  }
  return n;
}

TEST(Renderer, ShotsAreDrawnAsTracersAndStreaks) {
  const GridMap map = tinyMap();  // 24x16 cells at 10 pixels a cell
  Renderer renderer =
      makeRenderer(map, {.width = 240, .height = 160, .overlays = {.stuck = false, .hud = false}});
  FrameScene scene;
  const Image plain = renderOnce(renderer, scene);
  // An instant shot along row 14 (ground) in red's colour; a shell over row 0 in blue's.
  scene.shots = {{{2.5f, 14.55f}, {9.5f, 14.55f}, 1, false},
                 {{12.5f, 0.55f}, {18.5f, 0.55f}, 0, true}};
  const Image shot = renderOnce(renderer, scene);
  const Rgba red = palette::teamColour(1);
  const Rgba blue = palette::teamColour(0);
  EXPECT_EQ(pixelsOf(plain, red, 0, 130, 240, 160), 0);
  EXPECT_GE(pixelsOf(shot, red, 25, 140, 95, 151), 60);            // a line about 70 pixels long
  EXPECT_GE(pixelsOf(shot, blue, 125, 0, 180, 12), 40);            // the streak ...
  EXPECT_GT(pixelsOf(shot, palette::kWhite, 180, 0, 192, 12), 0);  // ... and its head
  // Nothing changed outside the two shots' bands.
  int outside = 0;
  for (int y = 0; y < 160; ++y) {
    for (int x = 0; x < 240; ++x) {
      const bool band = (y < 15 && x >= 115 && x < 200) || (y >= 135 && x >= 15 && x < 105);
      outside += !band && !(plain.at(x, y) == shot.at(x, y)) ? 1 : 0;
    }
  }
  EXPECT_EQ(outside, 0);
  scene.shots.clear();
  EXPECT_EQ(renderOnce(renderer, scene), plain);
}

TEST(Renderer, RejectsBadDefinitionsWithAMessage) {
  const GridMap map = tinyMap();
  auto tooSmall = Renderer::create(map, {.width = 0, .height = 10});
  ASSERT_FALSE(tooSmall.ok());
  EXPECT_NE(tooSmall.error().describe().find("resolution"), std::string::npos);
  auto offMap = Renderer::create(map, {.camera = pathing::CellRect{100, 0, 4, 4}});
  ASSERT_FALSE(offMap.ok());
  EXPECT_NE(offMap.error().describe().find("camera"), std::string::npos);
  EXPECT_FALSE(Renderer::create(GridMap(), {}).ok());
  Renderer renderer = makeRenderer(map, {.width = 32, .height = 32});
  const GridMap other(5, 5);
  EXPECT_FALSE(renderer
                   .setClearance(pathing::ClearanceField::compute(
                       other, pathing::Capability::of({Terrain::Ground})))
                   .ok());
}

TEST(Overlays, ParseNames) {
  auto o = parseOverlays("paths,graph");
  ASSERT_TRUE(o.ok());
  EXPECT_TRUE(o.value().paths);
  EXPECT_TRUE(o.value().abstractGraph);
  EXPECT_FALSE(o.value().clearance);
  auto none = parseOverlays("none", Overlays{.paths = true});
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none.value(), (Overlays{.stuck = false, .arrivalZones = false, .hud = false}));
  auto bad = parseOverlays("paths,heat");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().describe().find("'heat'"), std::string::npos);
}

TEST(Png, RoundTripsAFrame) {
  const GridMap map = tinyMap();
  Renderer renderer = makeRenderer(map, {.width = 96, .height = 64});
  const Image& image = renderOnce(renderer, tinyScene());
  const fs::path dir = scratchDir("png");
  for (const bool filter : {false, true}) {
    const fs::path file = dir / frameFileName(filter ? 7 : 123456);
    ASSERT_TRUE(
        writePng(file, image, {.compressionLevel = filter ? 6 : 1, .filterRows = filter}).ok());
    auto back = readPng(file);
    ASSERT_TRUE(back.ok()) << back.error().describe();
    EXPECT_EQ(back.value(), image);
  }
  EXPECT_TRUE(fs::exists(dir / "frame_123456.png"));
  EXPECT_TRUE(fs::exists(dir / "frame_000007.png"));
}

TEST(Png, ReportsUnwritableAndUnreadableFiles) {
  const Image image(4, 4, palette::kWater);
  const Status s = writePng("/nonexistent-dir/frame.png", image);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().describe().find("/nonexistent-dir/frame.png"), std::string::npos);
  EXPECT_FALSE(writePng(scratchDir("png_empty") / "e.png", Image()).ok());

  const fs::path notPng = scratchDir("png_bad") / "not.png";
  std::ofstream(notPng) << "this is not a PNG";
  auto read = readPng(notPng);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.error().describe().find("not.png"), std::string::npos);
}

TEST(Gif, WritesAnAnimationThatGiflibReadsBack) {
  const GridMap map = tinyMap();
  Renderer renderer = makeRenderer(map, {.width = 96, .height = 64});
  const fs::path file = scratchDir("gif") / "run.gif";
  auto gif = GifWriter::open(file, 96, 64, 5);
  ASSERT_TRUE(gif.ok()) << gif.error().describe();
  FrameScene scene = tinyScene();
  for (int i = 0; i < 3; ++i) {
    scene.tick = i;
    scene.units[0].centre.x += 2.0f;
    ASSERT_TRUE(gif.value().addFrame(renderOnce(renderer, scene)).ok());
  }
  EXPECT_FALSE(gif.value().addFrame(Image(8, 8)).ok());
  ASSERT_TRUE(gif.value().close().ok());
  EXPECT_FALSE(gif.value().addFrame(renderer.image()).ok());

  int error = 0;
  GifFileType* read = DGifOpenFileName(file.string().c_str(), &error);
  ASSERT_NE(read, nullptr) << GifErrorString(error);
  ASSERT_EQ(DGifSlurp(read), GIF_OK) << GifErrorString(read->Error);
  EXPECT_EQ(read->SWidth, 96);
  EXPECT_EQ(read->SHeight, 64);
  EXPECT_EQ(read->ImageCount, 3);
  // The last frame's pixels are the palette's nearest colours; terrain comes out exact.
  const PaletteQuantizer quantizer(palette::gifPalette());
  const Image& last = renderer.image();
  int mismatches = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 96; ++x) {
      const GifByteType index = read->SavedImages[2].RasterBits[y * 96 + x];
      if (index != quantizer.indexOf(last.at(x, y))) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0);
  const GifColorType water = read->SColorMap->Colors[quantizer.indexOf(palette::kWater)];
  EXPECT_EQ(water.Red, palette::kWater.r);
  EXPECT_EQ(water.Green, palette::kWater.g);
  EXPECT_EQ(water.Blue, palette::kWater.b);
  DGifCloseFile(read, &error);

  EXPECT_FALSE(GifWriter::open("/nonexistent-dir/run.gif", 8, 8, 5).ok());
}

TEST(FrameSink, BackgroundEncodingWritesTheSameBytesAsSerial) {
  const GridMap map = tinyMap();
  Renderer renderer = makeRenderer(map, {.width = 96, .height = 64});
  const auto run = [&](bool background) {
    const fs::path dir = scratchDir(background ? "sink_bg" : "sink_serial");
    auto sink = FrameSink::open({.framesDir = dir / "frames",
                                 .gifFile = dir / "run.gif",
                                 .every = 3,
                                 .background = background,
                                 .queueLimit = 2},
                                96, 64);
    EXPECT_TRUE(sink.ok()) << sink.error().describe();
    FrameScene scene = sampleScene(map, {.units = 12, .seed = 5});
    for (std::int64_t tick = 0; tick < 20; ++tick) {
      scene.tick = tick;
      for (UnitView& u : scene.units)
        u.centre.x = std::fmod(u.centre.x + 0.5f, 24.0f);
      if (!sink.value().wants(tick)) continue;
      EXPECT_TRUE(sink.value().submit(tick, renderOnce(renderer, scene)).ok());
    }
    EXPECT_TRUE(sink.value().finish().ok());
    EXPECT_EQ(sink.value().framesWritten(), 7);
    return dir;
  };
  const fs::path serial = run(false);
  const fs::path background = run(true);
  for (const std::int64_t tick : {0, 3, 9, 18}) {
    const std::string name = "frames/" + frameFileName(tick);
    ASSERT_TRUE(fs::exists(serial / name)) << name;
    EXPECT_EQ(fileBytes(serial / name), fileBytes(background / name)) << name;
  }
  EXPECT_FALSE(fs::exists(serial / "frames" / frameFileName(1)));
  EXPECT_EQ(fileBytes(serial / "run.gif"), fileBytes(background / "run.gif"));
}

TEST(FrameSink, ReportsAFrameItCannotWrite) {
  for (const bool background : {false, true}) {
    const fs::path dir = scratchDir(background ? "sink_gone_bg" : "sink_gone") / "frames";
    auto sink = FrameSink::open({.framesDir = dir, .background = background}, 8, 8);
    ASSERT_TRUE(sink.ok()) << sink.error().describe();
    fs::remove_all(dir);  // the folder vanishes under the running sink
    static_cast<void>(sink.value().submit(0, Image(8, 8)));
    const Status finished = sink.value().finish();
    ASSERT_FALSE(finished.ok()) << (background ? "background" : "serial");
    EXPECT_NE(finished.error().describe().find("frame_000000.png"), std::string::npos)
        << finished.error().describe();
    EXPECT_EQ(sink.value().framesWritten(), 0);
    EXPECT_FALSE(sink.value().submit(1, Image(8, 8)).ok());
  }
}

TEST(FrameSink, ReportsAFolderItCannotCreate) {
  const fs::path file = scratchDir("sink_blocked") / "file";
  std::ofstream(file) << "a file where the folder should go";
  auto sink = FrameSink::open({.framesDir = file / "frames"}, 8, 8);
  ASSERT_FALSE(sink.ok());
  EXPECT_NE(sink.error().describe().find("frames"), std::string::npos);
}

}  // namespace
}  // namespace warpath::render
