#include "rts/video_pipe.h"

#include <fmt/core.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <vector>

#include "rts/cli_support.h"

extern char** environ;

namespace warpath::tools {

VideoPipe::VideoPipe(const std::string& file, int width, int height, double fps)
    : file_(file), width_(width), height_(height) {
  // A socket rather than a pipe: send() with MSG_NOSIGNAL reports a dead ffmpeg as EPIPE
  // instead of killing the run with SIGPIPE, with no process-wide signal setting.
  int ends[2];
  if (socketpair(AF_UNIX, SOCK_STREAM, 0, ends) != 0)
    throw BadInput{"--video: cannot create a socket: " + std::string(std::strerror(errno))};
  const std::string size = fmt::format("{}x{}", width, height);
  const std::string rate = fmt::format("{:g}", fps);
  // H.264 wants even sides: pad by a pixel when odd. yuv420p plays everywhere.
  std::vector<std::string> args = {"ffmpeg",    "-hide_banner", "-loglevel",
                                   "error",     "-nostdin",     "-y",
                                   "-f",        "rawvideo",     "-pix_fmt",
                                   "rgb24",     "-s",           size,
                                   "-r",        rate,           "-i",
                                   "pipe:0",    "-vf",          "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                   "-c:v",      "libx264",      "-preset",
                                   "veryfast",  "-pix_fmt",     "yuv420p",
                                   "-movflags", "+faststart",   file};
  std::vector<char*> argv;
  for (std::string& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, ends[1], STDIN_FILENO);
  posix_spawn_file_actions_addclose(&actions, ends[0]);
  posix_spawn_file_actions_addclose(&actions, ends[1]);
  // A process group of its own: Ctrl-C stops the run between ticks (the report is written
  // and the video finished), not ffmpeg in the middle of it.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int spawned = posix_spawnp(&pid_, "ffmpeg", &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  close(ends[1]);
  if (spawned != 0) {
    close(ends[0]);
    pid_ = -1;
    throw BadInput{spawned == ENOENT
                       ? "--video: ffmpeg was not found on PATH (Debian package ffmpeg; "
                         "tools/setup.sh installs it)"
                       : "--video: cannot start ffmpeg: " + std::string(std::strerror(spawned))};
  }
  fd_ = ends[0];
}

VideoPipe::~VideoPipe() {
  if (fd_ >= 0) close(fd_);
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
}

void VideoPipe::write(const render::Image& image) {
  if (image.width != width_ || image.height != height_)
    throw BadInput{"--video: a frame of another size"};
  rgb_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3);
  for (std::size_t i = 0, o = 0; o < rgb_.size(); i += 4, o += 3) {
    rgb_[o] = static_cast<char>(image.pixels[i]);
    rgb_[o + 1] = static_cast<char>(image.pixels[i + 1]);
    rgb_[o + 2] = static_cast<char>(image.pixels[i + 2]);
  }
  for (std::size_t sent = 0; sent < rgb_.size();) {
    const ssize_t n = send(fd_, rgb_.data() + sent, rgb_.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      throw BadInput{"--video " + file_ + ": ffmpeg stopped taking frames (" +
                     std::string(std::strerror(errno)) + ")"};
    }
    sent += static_cast<std::size_t>(n);
  }
  ++frames_;
}

int VideoPipe::finish() {
  close(fd_);
  fd_ = -1;
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw BadInput{"--video " + file_ + ": ffmpeg failed (its message is above)"};
  return frames_;
}

}  // namespace warpath::tools
