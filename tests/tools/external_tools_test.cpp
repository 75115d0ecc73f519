// What needs programs from outside the build: the HTML report in headless Chromium, the viewer
// in an X server (Xvfb), `rts run --video` through ffmpeg. Each test skips when its program is
// missing, and a run whose every test skipped exits 77, which CTest shows as skipped
// (SKIP_RETURN_CODE): tools/setup.sh installs chromium, xvfb and ffmpeg.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "render/palette.h"
#include "render/png_io.h"
#include "rts/chart.h"
#include "support/rts_process.h"
#include "support/scratch_dir.h"
#include "support/walk_scenario.h"

namespace warpath {
namespace {

namespace fs = std::filesystem;
using testing::rts;
using testing::RtsResult;
using testing::shell;

bool installed(const std::string& program) {
  return shell("command -v " + program + " >/dev/null").status == 0;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

class ExternalTools : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::freshTestDir("warpath_external_");
    scenario_ = testing::writeWalkScenario(dir_ / "s.yaml").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string scenario_;
};

TEST_F(ExternalTools, HtmlReportRendersItsChartsInHeadlessChromium) {
  if (!installed("chromium")) GTEST_SKIP() << "chromium is not installed (tools/setup.sh)";
  const fs::path html = dir_ / "page.html";
  RtsResult r = rts("run " + scenario_ + " --quiet --html " + html.string() + " --gif " +
                    (dir_ / "run.gif").string() + " --frame-every 30 --frame-size 64");
  ASSERT_EQ(r.status, 0) << r.out;
  // No network: the page must render from the file alone.
  const std::string chromium =
      "timeout 120 chromium --headless --no-sandbox --disable-gpu "
      "--user-data-dir=" +
      (dir_ / "profile").string() + " ";
  r = shell(chromium + "--dump-dom file://" + html.string() + " 2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_GE(count(r.out, "<svg class=\"chart\""), 3) << r.out;  // arrivals, a delay, timing
  EXPECT_GE(count(r.out, "<polyline class=\"series\""), 1);
  EXPECT_GE(count(r.out, "<rect class=\"bar\""), 5);
  EXPECT_NE(r.out.find("data:image/gif;base64,"), std::string::npos);

  const fs::path shot = dir_ / "shot.png";
  r = shell(chromium + "--window-size=1000,1600 --screenshot=" + shot.string() + " file://" +
            html.string());
  ASSERT_EQ(r.status, 0) << r.out;
  auto image = render::readPng(shot);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  // The charts' first colour fills the legend swatches and the timing bars: drawn, not blank.
  const render::Rgba colour = tools::seriesColour(0);
  int painted = 0;
  for (int y = 0; y < image.value().height; ++y) {
    for (int x = 0; x < image.value().width; ++x)
      painted += image.value().at(x, y) == colour ? 1 : 0;
  }
  EXPECT_GT(painted, 500);
}

// An X server of its own for the test, on a display it picks (-displayfd); stopped at the end.
class Xvfb {
 public:
  Xvfb() {
    int fds[2];
    if (pipe(fds) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      close(fds[0]);
      const std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1024x768x24", "-nolisten",
             "tcp", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    std::string number;
    char ch = 0;
    while (read(fds[0], &ch, 1) == 1 && ch != '\n')
      number += ch;
    close(fds[0]);
    if (!number.empty()) display_ = ":" + number;
  }
  ~Xvfb() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
  }
  Xvfb(const Xvfb&) = delete;
  Xvfb& operator=(const Xvfb&) = delete;
  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

TEST_F(ExternalTools, ViewerScalesTheMapToItsWindowUnderXvfb) {
  if (!installed("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (tools/setup.sh)";
  const std::string replay = (dir_ / "r.rpl").string();
  RtsResult r = rts("run " + scenario_ + " --quiet --replay " + replay);
  ASSERT_EQ(r.status, 0) << r.out;
  const Xvfb server;
  ASSERT_FALSE(server.display().empty()) << "Xvfb did not start";
  const fs::path shot = dir_ / "window.png";
  // A 640x480 window: the 8:5 map is drawn 640x400, centred, with 40 rows above and below.
  r = shell("SDL_VIDEODRIVER=x11 DISPLAY=" + server.display() + " " RTS_BINARY " view " + replay +
            " --window 640x480 --frames-then-exit 5 --screenshot " + shot.string());
  ASSERT_EQ(r.status, 0) << r.out;
  auto image = render::readPng(shot);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  const render::Image& im = image.value();
  ASSERT_EQ(im.width, 640);
  ASSERT_EQ(im.height, 480);
  const render::Rgba edge = render::palette::kBackground;
  EXPECT_EQ(im.at(320, 20), edge);
  EXPECT_EQ(im.at(320, 460), edge);
  // The map reaches both sides, and from row 40 to row 439.
  for (const int y : {60, 240, 420}) {
    EXPECT_NE(im.at(1, y), edge) << "row " << y;
    EXPECT_NE(im.at(638, y), edge) << "row " << y;
  }
  EXPECT_NE(im.at(320, 42), edge);
  EXPECT_NE(im.at(320, 437), edge);
}

TEST_F(ExternalTools, RunWritesAnMp4ThroughFfmpeg) {
  if (!installed("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed (tools/setup.sh)";
  const fs::path video = dir_ / "out" / "run.mp4";
  RtsResult r = rts("run " + scenario_ + " --video " + video.string() +
                    " --frame-every 10 --frame-size 65");  // odd sides: padded for H.264
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("frames: 16 written, video " + video.string()), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(video));
  EXPECT_GT(fs::file_size(video), 0u);
  if (installed("ffprobe")) {  // 150 ticks, a frame every 10 from tick 0: 16 frames
    r = shell(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames -of csv=p=0 " +
        video.string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(std::atoi(r.out.c_str()), 16) << r.out;
  }
}

}  // namespace
}  // namespace warpath

// CTest's SKIP_RETURN_CODE: 77 when every test that ran was skipped.
int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
  const ::testing::UnitTest* unit = ::testing::UnitTest::GetInstance();
  if (status == 0 && unit->test_to_run_count() > 0 &&
      unit->skipped_test_count() == unit->test_to_run_count())
    return 77;
  return status;
}
