// Replays drawn: `rts replay render` frames and GIF, `rts view` under SDL's offscreen and dummy
// video drivers with scripted keys, and the caption line the viewer draws its help with.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "pathing/map_io.h"
#include "render/palette.h"
#include "render/png_io.h"
#include "render/renderer.h"
#include "support/rts_process.h"
#include "support/scratch_dir.h"
#include "support/walk_scenario.h"

namespace warpath::render {
namespace {

namespace fs = std::filesystem;
using warpath::testing::rts;
using warpath::testing::RtsResult;

class ReplayPictures : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = warpath::testing::freshTestDir("warpath_replay_view_");
    const std::string scenario = warpath::testing::writeWalkScenario(dir_ / "s.yaml").string();
    replay_ = (dir_ / "r.rpl").string();
    const RtsResult r = rts("run " + scenario + " --quiet --replay " + replay_);
    ASSERT_EQ(r.status, 0) << r.out;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `rts view` with `driver` as SDL's video driver (inherited by the child).
  RtsResult view(const std::string& driver, const std::string& args) {
    setenv("SDL_VIDEODRIVER", driver.c_str(), 1);
    return rts("view " + replay_ + " " + args);
  }

  fs::path dir_;
  std::string replay_;
};

TEST_F(ReplayPictures, RenderWritesFramesAndAGif) {
  const fs::path frames = dir_ / "frames";
  const fs::path gif = dir_ / "r.gif";
  const RtsResult r = rts("replay render " + replay_ + " --frames " + frames.string() +
                          " --every 30 --frame-size 64 --overlay paths --gif " + gif.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("150 ticks, 6 frames written"), std::string::npos) << r.out;
  for (int tick : {0, 30, 150}) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", tick);
    auto image = readPng(frames / name);
    ASSERT_TRUE(image.ok()) << image.error().describe();
    EXPECT_EQ(image.value().width, 64);
    EXPECT_EQ(image.value().height, 40);
  }
  EXPECT_GT(fs::file_size(gif), 0u);
  // Without --frames or --gif there is nothing to do: bad input.
  EXPECT_EQ(rts("replay render " + replay_).status, 2);
}

TEST_F(ReplayPictures, ViewerDrawsFramesAndQuitsUnderTheOffscreenDriver) {
  // Paused, then End, Home, two steps, ten seconds on and one back: tick 0+1+1+300-1.
  const RtsResult r =
      view("offscreen", "--paused --keys End,Home,Right,.,Shift+Right,Left --frames-then-exit 8");
  ASSERT_EQ(r.status, 0) << r.out;
  // The replay ends at tick 150: ten seconds on from tick 2 stops there.
  EXPECT_NE(r.out.find("8 frames drawn, tick 149"), std::string::npos) << r.out;
}

TEST_F(ReplayPictures, ViewerPlaysAndTogglesUnderTheDummyDriver) {
  // Playing at x2, one tick a frame of 1/60 s, but two in frame 10 ('+' makes it x4 until the
  // '-' of frame 11): 61 ticks.
  RtsResult r = view("dummy", "--speed 2 --keys 1,2,3,4,5,6,7,c,h,h,+,- --frames-then-exit 60");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("60 frames drawn, tick 61"), std::string::npos) << r.out;
  r = view("dummy", "--keys Nonesuch --frames-then-exit 2");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("unknown key 'Nonesuch'"), std::string::npos) << r.out;
  std::ofstream(replay_, std::ios::binary | std::ios::app) << "x";  // half a record
  r = view("dummy", "--frames-then-exit 2");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(replay_ + ": truncated in the middle of a record"), std::string::npos)
      << r.out;
}

TEST_F(ReplayPictures, ViewerScalesTheMapToItsWindowKeepingItsShape) {
  // A tall window: the 8:5 map is drawn 300 wide and 188 high, centred (rows 206-393).
  const fs::path shot = dir_ / "window.png";
  RtsResult r =
      view("offscreen", "--window 300x600 --frames-then-exit 3 --screenshot " + shot.string());
  ASSERT_EQ(r.status, 0) << r.out;
  auto image = readPng(shot);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  const Image& im = image.value();
  ASSERT_EQ(im.width, 300);
  ASSERT_EQ(im.height, 600);
  const Rgba edge = palette::kBackground;
  EXPECT_EQ(im.at(150, 100), edge);
  EXPECT_EQ(im.at(150, 500), edge);
  for (const int y : {210, 300, 390}) {
    EXPECT_NE(im.at(0, y), edge) << "row " << y;
    EXPECT_NE(im.at(299, y), edge) << "row " << y;
  }
  // Resized while it runs (as if its edge were dragged): drawn again at the new size.
  r = view(
      "offscreen",
      "--window 400x250 --keys Window=250x400 --frames-then-exit 3 --screenshot " + shot.string());
  ASSERT_EQ(r.status, 0) << r.out;
  image = readPng(shot);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  ASSERT_EQ(image.value().width, 250);
  ASSERT_EQ(image.value().height, 400);
  EXPECT_EQ(image.value().at(125, 60), edge);  // the map: 250x156, rows 122-277
  EXPECT_NE(image.value().at(0, 200), edge);
  EXPECT_NE(image.value().at(249, 200), edge);
  r = view("offscreen", "--keys Window=2x2 --frames-then-exit 1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("'Window=2x2': the size must be WxH"), std::string::npos) << r.out;
  r = view("offscreen", "--window 300 --frames-then-exit 1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--window: must be WIDTHxHEIGHT"), std::string::npos) << r.out;
  r = view("offscreen", "--screenshot " + shot.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--screenshot needs --frames-then-exit"), std::string::npos) << r.out;
}

TEST(Caption, DrawsAStripAlongTheBottomOnly) {
  std::string rows;
  for (int y = 0; y < 8; ++y)
    rows += std::string(16, '.') + "\n";
  std::istringstream in("type octile\nheight 8\nwidth 16\nmap\n" + rows);
  auto map = pathing::parseMap(in, "caption");
  ASSERT_TRUE(map) << map.error().describe();
  RenderDef def = fittedDef(map.value(), 256);
  EXPECT_EQ(def.width, 256);
  EXPECT_EQ(def.height, 128);
  def.overlays.hud = false;
  auto renderer = Renderer::create(map.value(), def);
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  FrameScene scene;
  ASSERT_TRUE(renderer.value().render(scene));
  const Image plain = renderer.value().image();
  scene.caption = "SPACE PLAY";
  ASSERT_TRUE(renderer.value().render(scene));
  const Image captioned = renderer.value().image();
  EXPECT_EQ(plain.at(128, 10), captioned.at(128, 10));    // the top is untouched
  EXPECT_NE(plain.at(250, 125), captioned.at(250, 125));  // the strip covers the bottom
  int white = 0;
  for (int y = 110; y < 128; ++y) {
    for (int x = 0; x < 80; ++x)
      white += captioned.at(x, y) == palette::kWhite ? 1 : 0;
  }
  EXPECT_GT(white, 20);  // the letters
}

}  // namespace
}  // namespace warpath::render
