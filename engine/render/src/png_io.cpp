#include "render/png_io.h"

#include <png.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "pathing/file_read.h"

namespace warpath::render {
namespace {

// libpng reports errors by longjmp; everything live across setjmp below is a trivially
// destructible local or owned by the caller, so the jump skips no destructor.
struct EncodeState {
  std::vector<std::uint8_t>* out;
  char error[200];
};

void appendBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* state = static_cast<EncodeState*>(png_get_io_ptr(png));
  state->out->insert(state->out->end(), data, data + length);
}

void flushNothing(png_structp) {}

void recordError(png_structp png, png_const_charp message) {
  auto* state = static_cast<EncodeState*>(png_get_error_ptr(png));
  std::snprintf(state->error, sizeof state->error, "%s", message);
  png_longjmp(png, 1);
}

void ignoreWarning(png_structp, png_const_charp) {}

bool encodeRows(const Image& image, const PngOptions& options, EncodeState* state) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, state, recordError, ignoreWarning);
  if (png == nullptr) {
    std::snprintf(state->error, sizeof state->error, "libpng could not start");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, state, appendBytes, flushNothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, options.compressionLevel);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, options.filterRows ? PNG_ALL_FILTERS : PNG_FILTER_NONE);
  png_write_info(png, info);
  png_set_filler(png, 0, PNG_FILLER_AFTER);  // rows hold RGBA; the file RGB
  const std::size_t stride = static_cast<std::size_t>(image.width) * 4;
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, image.pixels.data() + stride * static_cast<std::size_t>(y));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

Result<std::vector<std::uint8_t>> encodePng(const Image& image, const PngOptions& options) {
  if (image.width < 1 || image.height < 1 ||
      image.pixels.size() !=
          static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4) {
    return Error{"", 0, 0,
                 "cannot encode an empty or inconsistent " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " image as PNG"};
  }
  if (options.compressionLevel < 0 || options.compressionLevel > 9) {
    return Error{
        "", 0, 0,
        "PNG compression level " + std::to_string(options.compressionLevel) + " is outside 0..9"};
  }
  std::vector<std::uint8_t> bytes;
  bytes.reserve(image.pixels.size() / 8);
  EncodeState state{&bytes, {}};
  if (!encodeRows(image, options, &state)) {
    return Error{"", 0, 0, std::string("PNG encoding failed: ") + state.error};
  }
  return bytes;
}

Status writeFile(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) return Error{file.string(), 0, 0, "cannot open for writing"};
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) return Error{file.string(), 0, 0, "write failed"};
  return Status::success();
}

Status writePng(const std::filesystem::path& file, const Image& image, const PngOptions& options) {
  auto bytes = encodePng(image, options);
  if (!bytes) return Error{file.string(), 0, 0, bytes.error().describe()};
  return writeFile(file, bytes.value());
}

Result<Image> readPng(const std::filesystem::path& file) {
  const Result<std::string> bytes = readFileCapped(file, kPngFileLimit);
  if (!bytes) return bytes.error();
  // The simplified API reports errors in the struct instead of by longjmp.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.value().data(), bytes.value().size())) {
    return Error{file.string(), 0, 0, png.message};
  }
  // The header alone must not make us allocate gigabytes: frames are at most 8192x8192.
  constexpr png_uint_32 kMaxSide = 8192;
  if (png.width > kMaxSide || png.height > kMaxSide) {
    png_image_free(&png);
    return Error{file.string(), 0, 0,
                 "a " + std::to_string(png.width) + "x" + std::to_string(png.height) +
                     " image is larger than the 8192x8192 limit"};
  }
  png.format = PNG_FORMAT_RGBA;
  Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.pixels.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    return Error{file.string(), 0, 0, message};
  }
  return image;
}

std::string frameFileName(std::int64_t tick) {
  char name[48];
  std::snprintf(name, sizeof name, "frame_%06lld.png", static_cast<long long>(tick));
  return name;
}

}  // namespace warpath::render
