#pragma once
// `--video FILE.mp4`: frames piped as raw RGB to Debian's ffmpeg program (H.264 in MP4), which
// encodes in a process of its own while the run goes on. No codec library is linked: ffmpeg is
// needed only when a video is asked for.

#include <sys/types.h>

#include <string>

#include "render/image.h"

namespace warpath::tools {

class VideoPipe {
 public:
  // Starts `ffmpeg` (looked up on PATH) writing `file` from `width` x `height` frames shown at
  // `fps` a second. Throws BadInput when ffmpeg is missing or cannot be started.
  VideoPipe(const std::string& file, int width, int height, double fps);
  VideoPipe(const VideoPipe&) = delete;
  VideoPipe& operator=(const VideoPipe&) = delete;
  ~VideoPipe();  // stops ffmpeg if finish() was not called (an error unwinding the run)

  // Throws BadInput when ffmpeg has stopped taking frames (it printed why on stderr).
  void write(const render::Image& image);
  // Closes the stream and waits for ffmpeg; throws BadInput when it failed. Returns the frames.
  int finish();

 private:
  std::string file_;
  int width_ = 0;
  int height_ = 0;
  int fd_ = -1;  // our end of the socket ffmpeg reads its frames from
  pid_t pid_ = -1;
  int frames_ = 0;
  std::string rgb_;  // scratch: one frame without alpha
};

}  // namespace warpath::tools
