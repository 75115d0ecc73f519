#pragma once
// Writes rendered frames: a PNG per frame into a folder (frame_000123.png, named by tick)
// and/or one animated GIF, every `every` ticks. With `background`, encoding and writing run on
// a second thread, in submission order, so the files are byte for byte those of serial
// encoding; submit() then only copies the image (and waits when `queueLimit` frames are
// already waiting).

#include <cstdint>
#include <filesystem>
#include <memory>

#include "pathing/error.h"
#include "render/image.h"
#include "render/png_io.h"

namespace warpath::render {

struct FrameSinkDef {
  std::filesystem::path framesDir{};  // PNG frames go here (created if missing); empty: none
  std::filesystem::path gifFile{};    // empty: no GIF
  int every = 1;                      // [Unit: ticks] [Limit: >= 1] frames on ticks divisible by it
  int gifDelayCentiseconds = 10;      // [Unit: 1/100 s] how long each GIF frame shows
  PngOptions png{};
  bool background = true;
  int queueLimit = 4;  // [Limit: >= 1] frames waiting for the encoder at most
};

class FrameSink {
 public:
  // Creates the folder and the GIF; fails naming what cannot be created.
  static Result<FrameSink> open(const FrameSinkDef& def, int width, int height);

  FrameSink(FrameSink&&) noexcept;
  FrameSink& operator=(FrameSink&&) noexcept;
  ~FrameSink();  // finishes (waits for the encoder), ignoring errors

  bool wants(std::int64_t tick) const;
  // Queues (or, without `background`, writes) the frame of `tick`. Returns the first failure
  // so far: once a write fails, later frames are dropped.
  Status submit(std::int64_t tick, const Image& image);
  // Waits for every queued frame, closes the GIF and returns the first failure, if any.
  Status finish();
  int framesWritten() const;  // finished frames so far

 private:
  struct Impl;
  explicit FrameSink(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace warpath::render
