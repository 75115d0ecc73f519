#include "render/frame_sink.h"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>
#include <utility>

#include "render/gif_writer.h"

namespace warpath::render {

struct FrameSink::Impl {
  FrameSinkDef def;
  int width = 0;
  int height = 0;
  std::optional<GifWriter> gif;

  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::pair<std::int64_t, Image>> queue;  // guarded by mutex
  Status failure = Status::success();                // guarded by mutex; the first one
  int written = 0;                                   // guarded by mutex
  bool stopping = false;                             // guarded by mutex
  bool finished = false;
  std::thread worker;

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() { static_cast<void>(finish()); }

  // Encodes and writes one frame; the same code serially and on the worker.
  Status write(std::int64_t tick, const Image& image) {
    if (!def.framesDir.empty()) {
      if (Status s = writePng(def.framesDir / frameFileName(tick), image, def.png); !s) return s;
    }
    if (gif) return gif->addFrame(image);
    return Status::success();
  }

  void record(Status status) {
    std::lock_guard lock(mutex);
    if (status.ok()) {
      ++written;
    } else if (failure.ok()) {
      failure = std::move(status);
    }
  }

  void work() {
    for (;;) {
      std::pair<std::int64_t, Image> frame;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return stopping || !queue.empty(); });
        if (queue.empty()) return;  // stopping with nothing left
        frame = std::move(queue.front());
        queue.pop_front();
      }
      changed.notify_all();  // room in the queue
      bool failed = false;
      {
        std::lock_guard lock(mutex);
        failed = !failure.ok();
      }
      if (!failed) record(write(frame.first, frame.second));
    }
  }

  Status submit(std::int64_t tick, const Image& image) {
    if (finished) return Error{"", 0, 0, "frames submitted after the frame sink finished"};
    if (image.width != width || image.height != height) {
      return Error{"", 0, 0,
                   "a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                       " frame for a " + std::to_string(width) + "x" + std::to_string(height) +
                       " frame sink"};
    }
    if (!worker.joinable()) {
      {
        std::lock_guard lock(mutex);
        if (!failure.ok()) return failure;
      }
      record(write(tick, image));
      std::lock_guard lock(mutex);
      return failure;
    }
    std::unique_lock lock(mutex);
    changed.wait(lock, [&] { return queue.size() < static_cast<std::size_t>(def.queueLimit); });
    if (!failure.ok()) return failure;
    queue.emplace_back(tick, image);
    lock.unlock();
    changed.notify_all();
    return Status::success();
  }

  Status finish() {
    if (finished) {
      std::lock_guard lock(mutex);
      return failure;
    }
    finished = true;
    if (worker.joinable()) {
      {
        std::lock_guard lock(mutex);
        stopping = true;
      }
      changed.notify_all();
      worker.join();
    }
    if (gif) {
      Status closed = gif->close();
      if (!closed) record(std::move(closed));
    }
    std::lock_guard lock(mutex);
    return failure;
  }
};

FrameSink::FrameSink(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FrameSink::FrameSink(FrameSink&&) noexcept = default;
FrameSink& FrameSink::operator=(FrameSink&&) noexcept = default;
FrameSink::~FrameSink() = default;

Result<FrameSink> FrameSink::open(const FrameSinkDef& def, int width, int height) {
  if (def.every < 1)
    return Error{"", 0, 0,
                 "frames every " + std::to_string(def.every) + " ticks: expected at least 1"};
  if (def.queueLimit < 1) return Error{"", 0, 0, "a frame queue limit below 1"};
  auto impl = std::make_unique<Impl>();
  impl->def = def;
  impl->width = width;
  impl->height = height;
  if (!def.framesDir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(def.framesDir, error);
    if (error || !std::filesystem::is_directory(def.framesDir)) {
      return Error{def.framesDir.string(), 0, 0,
                   "cannot create the frames folder" +
                       (error ? " (" + error.message() + ")" : std::string())};
    }
  }
  if (!def.gifFile.empty()) {
    auto gif = GifWriter::open(def.gifFile, width, height, def.gifDelayCentiseconds);
    if (!gif) return gif.error();
    impl->gif.emplace(std::move(gif).value());
  }
  if (def.background) impl->worker = std::thread([p = impl.get()] { p->work(); });
  return FrameSink(std::move(impl));
}

bool FrameSink::wants(std::int64_t tick) const {
  return tick % impl_->def.every == 0;
}
Status FrameSink::submit(std::int64_t tick, const Image& image) {
  return impl_->submit(tick, image);
}
Status FrameSink::finish() {
  return impl_->finish();
}
int FrameSink::framesWritten() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->written;
}

}  // namespace warpath::render
