// `rts path --png`: the picture of a planned path, end to end through the CLI.

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

// Exit status of `rts args`, stderr into `err`.
int rtsPath(const std::string& args, std::string* err) {
  const fs::path errFile = fs::path(::testing::TempDir()) / "rts_path_png_err";
  const std::string command = std::string("'") + RTS_BINARY + "' path '" + WARPATH_SOURCE_DIR +
                              "/assets/maps/crossing.map' " + args + " >/dev/null 2>'" +
                              errFile.string() + "'";
  const int status = std::system(command.c_str());
  std::ostringstream text;
  text << std::ifstream(errFile).rdbuf();
  *err = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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
  ASSERT_TRUE(image.ok()) << image.status().message();
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

}  // namespace
}  // namespace warpath::render
