// Pictures through the CLI, end to end: `rts path --png` and `rts run --frames/--gif`.

#include <gif_lib.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "render/palette.h"
#include "render/png_io.h"

namespace warpath::render {
namespace {

namespace fs = std::filesystem;

// Exit status of `rts args`, stderr into `err`. The file is per test: CTest runs the tests of
// this binary as parallel processes, and a shared file let one test read another's stderr.
int rts(const std::string& args, std::string* err) {
  const fs::path errFile = fs::path(::testing::TempDir()) /
                           (std::string("rts_render_cli_err_") +
                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
  const std::string command =
      std::string("'") + RTS_BINARY + "' " + args + " >/dev/null 2>'" + errFile.string() + "'";
  const int status = std::system(command.c_str());
  std::ostringstream text;
  text << std::ifstream(errFile).rdbuf();
  *err = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int rtsPath(const std::string& args, std::string* err) {
  return rts(std::string("path '") + WARPATH_SOURCE_DIR + "/assets/maps/crossing.map' " + args,
             err);
}

TEST(PathPng, DrawsTheMapTheAgentAndItsFootprints) {
  const fs::path file = fs::path(::testing::TempDir()) / "rts_path.png";
  fs::remove(file);
  std::string err;
  ASSERT_EQ(rtsPath("--size 3 --capability ground --from 3,20 --to 56,22 --algo haa-hq "
                    "--png '" +
                        file.string() + "' --png-graph",
                    &err),
            0)
      << err;
  auto image = readPng(file);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  // crossing.map is 64x40: 16 pixels a cell.
  EXPECT_EQ(image.value().width, 64 * 16);
  EXPECT_EQ(image.value().height, 40 * 16);
  // The tank (team 0) stands at 3,20 (centre 4.5,21.5); the river at 32,3 is untouched water.
  const Rgba tank = image.value().at(static_cast<int>(4.0 * 16), static_cast<int>(22.2 * 16));
  EXPECT_EQ(tank, palette::teamColour(0));
  EXPECT_EQ(image.value().at(32 * 16 + 8, 3 * 16 + 8), palette::kWater);
}

TEST(PathPng, ReportsAnUnwritableFile) {
  std::string err;
  EXPECT_EQ(rtsPath("--size 1 --capability ground --from 3,20 --to 56,22 "
                    "--png /nonexistent-dir/path.png",
                    &err),
            2);
  EXPECT_NE(err.find("/nonexistent-dir/path.png"), std::string::npos) << err;
}

TEST(RunFrames, WritesPngFramesEveryNTicksAndAGif) {
  const fs::path dir = fs::path(::testing::TempDir()) / "rts_run_frames";
  fs::remove_all(dir);
  std::string err;
  ASSERT_EQ(rts(std::string("run '") + WARPATH_SOURCE_DIR +
                    "/scenarios/demo.yaml' --until 60 --quiet --frames '" +
                    (dir / "frames").string() + "' --frame-every 30 --frame-size 192 --gif '" +
                    (dir / "run.gif").string() + "' --overlay paths",
                &err),
            1)  // stopped before the expectations' deadlines: they fail
      << err;
  for (const char* name : {"frame_000000.png", "frame_000030.png", "frame_000060.png"}) {
    auto frame = readPng(dir / "frames" / name);
    ASSERT_TRUE(frame.ok()) << frame.error().describe();
    EXPECT_EQ(frame.value().width, 192);  // the 96x64 demo map
    EXPECT_EQ(frame.value().height, 128);
  }
  EXPECT_FALSE(fs::exists(dir / "frames" / "frame_000001.png"));
  int error = 0;
  GifFileType* gif = DGifOpenFileName((dir / "run.gif").string().c_str(), &error);
  ASSERT_NE(gif, nullptr) << GifErrorString(error);
  ASSERT_EQ(DGifSlurp(gif), GIF_OK);
  EXPECT_EQ(gif->ImageCount, 3);
  DGifCloseFile(gif, &error);
}

TEST(RunFrames, RejectsAnUnknownOverlay) {
  std::string err;
  EXPECT_EQ(
      rts(std::string("run '") + WARPATH_SOURCE_DIR +
              "/scenarios/demo.yaml' --until 1 --quiet --gif /nonexistent-dir/x.gif --overlay heat",
          &err),
      2);
  EXPECT_NE(err.find("'heat'"), std::string::npos) << err;
}

}  // namespace
}  // namespace warpath::render
