#include "render/gif_writer.h"

#include <fcntl.h>
#include <gif_lib.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "render/palette.h"

namespace warpath::render {

PaletteQuantizer::PaletteQuantizer(std::span<const Rgba> palette) : lut_(1u << 15, 0) {
  for (std::size_t key = 0; key < lut_.size(); ++key) {
    // The centre of the 8x8x8 block of colours sharing this key.
    const int r = static_cast<int>((key >> 10) & 31) * 8 + 4;
    const int g = static_cast<int>((key >> 5) & 31) * 8 + 4;
    const int b = static_cast<int>(key & 31) * 8 + 4;
    int best = 0;
    int bestDistance = INT32_MAX;
    for (std::size_t i = 0; i < palette.size(); ++i) {
      const int dr = r - palette[i].r, dg = g - palette[i].g, db = b - palette[i].b;
      const int d = dr * dr + dg * dg + db * db;
      if (d < bestDistance) {
        bestDistance = d;
        best = static_cast<int>(i);
      }
    }
    lut_[key] = static_cast<std::uint8_t>(best);
  }
  // Exact colours win their block; the earliest entry wins a shared one.
  for (std::size_t i = palette.size(); i-- > 0;) {
    const Rgba c = palette[i];
    lut_[static_cast<std::size_t>((c.r >> 3) << 10 | (c.g >> 3) << 5 | (c.b >> 3))] =
        static_cast<std::uint8_t>(i);
  }
}

struct GifWriter::Impl {
  GifFileType* gif = nullptr;
  std::string name;
  int width = 0;
  int height = 0;
  int delay = 0;
  int frames = 0;
  PaletteQuantizer quantizer{palette::gifPalette()};
  std::vector<GifPixelType> row;

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (gif != nullptr) EGifCloseFile(gif, nullptr);
  }

  Error failure(const std::string& what) const {
    return Error{name, 0, 0,
                 what + " (" + (gif != nullptr ? GifErrorString(gif->Error) : "giflib") + ")"};
  }
};

GifWriter::GifWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GifWriter::GifWriter(GifWriter&&) noexcept = default;
GifWriter& GifWriter::operator=(GifWriter&&) noexcept = default;
GifWriter::~GifWriter() = default;

Result<GifWriter> GifWriter::open(const std::filesystem::path& file, int width, int height,
                                  int delayCentiseconds) {
  if (width < 1 || height < 1 || width > 65535 || height > 65535) {
    return Error{file.string(), 0, 0,
                 "GIF frames of " + std::to_string(width) + "x" + std::to_string(height) +
                     " are outside 1x1..65535x65535"};
  }
  auto impl = std::make_unique<Impl>();
  impl->name = file.string();
  impl->width = width;
  impl->height = height;
  impl->delay = std::clamp(delayCentiseconds, 0, 65535);
  impl->row.resize(static_cast<std::size_t>(width));
  // Opened here rather than by EGifOpenFileName, which creates files readable by the owner
  // only; giflib owns (and closes) the descriptor from then on.
  const int fd = ::open(impl->name.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
  if (fd < 0) {
    return Error{impl->name, 0, 0, std::string("cannot create (") + std::strerror(errno) + ")"};
  }
  int error = 0;
  impl->gif = EGifOpenFileHandle(fd, &error);
  if (impl->gif == nullptr) {
    ::close(fd);
    return Error{impl->name, 0, 0, std::string("cannot create (") + GifErrorString(error) + ")"};
  }
  EGifSetGifVersion(impl->gif, true);  // GIF89a: delays and looping

  const std::span<const Rgba> colours = palette::gifPalette();
  ColorMapObject* map = GifMakeMapObject(256, nullptr);
  if (map == nullptr) return Error{impl->name, 0, 0, "out of memory for the palette"};
  for (int i = 0; i < 256; ++i) {
    const Rgba c = static_cast<std::size_t>(i) < colours.size()
                       ? colours[static_cast<std::size_t>(i)]
                       : palette::kBlack;
    map->Colors[i] = {c.r, c.g, c.b};
  }
  const int screen = EGifPutScreenDesc(impl->gif, width, height, 8, 0, map);  // copies the map
  GifFreeMapObject(map);
  if (screen != GIF_OK) return impl->failure("cannot write the screen descriptor");

  // NETSCAPE2.0 application extension: loop forever.
  static constexpr std::array<GifByteType, 11> kNetscape{'N', 'E', 'T', 'S', 'C', 'A',
                                                         'P', 'E', '2', '.', '0'};
  static constexpr std::array<GifByteType, 3> kLoopForever{1, 0, 0};
  if (EGifPutExtensionLeader(impl->gif, APPLICATION_EXT_FUNC_CODE) != GIF_OK ||
      EGifPutExtensionBlock(impl->gif, kNetscape.size(), kNetscape.data()) != GIF_OK ||
      EGifPutExtensionBlock(impl->gif, kLoopForever.size(), kLoopForever.data()) != GIF_OK ||
      EGifPutExtensionTrailer(impl->gif) != GIF_OK) {
    return impl->failure("cannot write the loop extension");
  }
  return GifWriter(std::move(impl));
}

Status GifWriter::addFrame(const Image& image) {
  Impl& s = *impl_;
  if (s.gif == nullptr) return Error{s.name, 0, 0, "the GIF is already closed"};
  if (image.width != s.width || image.height != s.height ||
      image.pixels.size() !=
          static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4) {
    return Error{s.name, 0, 0,
                 "a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " frame in a " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     " GIF"};
  }
  GraphicsControlBlock gcb{};
  gcb.DisposalMode = DISPOSAL_UNSPECIFIED;
  gcb.DelayTime = s.delay;
  gcb.TransparentColor = NO_TRANSPARENT_COLOR;
  std::array<GifByteType, 4> extension{};
  EGifGCBToExtension(&gcb, extension.data());
  if (EGifPutExtension(s.gif, GRAPHICS_EXT_FUNC_CODE, extension.size(), extension.data()) !=
          GIF_OK ||
      EGifPutImageDesc(s.gif, 0, 0, s.width, s.height, false, nullptr) != GIF_OK) {
    return s.failure("cannot start frame " + std::to_string(s.frames));
  }
  const std::uint8_t* p = image.pixels.data();
  for (int y = 0; y < s.height; ++y) {
    for (GifPixelType& index : s.row) {
      index = s.quantizer.indexOf({p[0], p[1], p[2], p[3]});
      p += 4;
    }
    if (EGifPutLine(s.gif, s.row.data(), s.width) != GIF_OK) {
      return s.failure("cannot write frame " + std::to_string(s.frames));
    }
  }
  ++s.frames;
  return Status::success();
}

Status GifWriter::close() {
  Impl& s = *impl_;
  if (s.gif == nullptr) return Error{s.name, 0, 0, "the GIF is already closed"};
  int error = 0;
  const int result = EGifCloseFile(s.gif, &error);  // frees the handle either way
  s.gif = nullptr;
  if (result != GIF_OK) {
    return Error{s.name, 0, 0, std::string("cannot finish (") + GifErrorString(error) + ")"};
  }
  return Status::success();
}

int GifWriter::frameCount() const {
  return impl_->frames;
}

}  // namespace warpath::render
