#include "pathing/file_read.h"

#include <algorithm>
#include <cerrno>
#include <system_error>

namespace warpath {
namespace {

Error problem(const std::filesystem::path& file, std::string message) {
  return Error{file.string(), 0, 0, std::move(message)};
}

Error cannotRead(const std::filesystem::path& file, int error) {
  std::string message = "cannot read";
  if (error != 0) {
    message.append(": ");
    message.append(std::generic_category().message(error));
  }
  return problem(file, std::move(message));
}

}  // namespace

Result<CappedFile> CappedFile::open(const std::filesystem::path& file, FileLimit limit) {
  // stat before opening: a FIFO would block in open, and /dev/zero never ends. The
  // error_code overloads do not throw.
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (status.type() == fs::file_type::not_found) return problem(file, std::string(kNoSuchFile));
  if (error) return cannotRead(file, error.value());
  if (status.type() == fs::file_type::directory) return problem(file, "is a directory");
  if (status.type() != fs::file_type::regular) return problem(file, "not a regular file");
  const std::uint64_t size = fs::file_size(file, error);
  if (error) return cannotRead(file, error.value());
  CappedFile capped(file.string(), nullptr, size, limit);
  if (size > limit.maxBytes) return capped.tooLarge();
  errno = 0;
  capped.in_.reset(std::fopen(file.c_str(), "rb"));
  if (!capped.in_) return cannotRead(file, errno);
  return capped;
}

Error CappedFile::tooLarge() const {
  return fileTooLarge(name_, limit_);
}

std::string describeSize(std::uint64_t bytes) {
  constexpr std::uint64_t kKiB = 1024;
  if (bytes % kMiB == 0 && bytes != 0) return std::to_string(bytes / kMiB) + " MiB";
  if (bytes % kKiB == 0 && bytes != 0) return std::to_string(bytes / kKiB) + " KiB";
  return std::to_string(bytes) + " bytes";
}

Error fileTooLarge(const std::string& file, FileLimit limit) {
  std::string message = "larger than the ";
  message.append(describeSize(limit.maxBytes));
  message.append(" limit for ");
  message.append(limit.kind);
  return Error{file, 0, 0, std::move(message)};
}

Result<std::size_t> CappedFile::read(std::string& out, std::size_t count) {
  // The file may have grown since stat, or lie about its size: the cap holds while reading.
  const std::uint64_t allowed = limit_.maxBytes - std::min(offset_, limit_.maxBytes);
  const std::size_t wanted = static_cast<std::size_t>(std::min<std::uint64_t>(count, allowed + 1));
  const std::size_t before = out.size();
  out.resize(before + wanted);
  errno = 0;
  const std::size_t got = std::fread(out.data() + before, 1, wanted, in_.get());
  const int error = errno;
  out.resize(before + got);
  if (got < wanted && std::ferror(in_.get()) != 0) return cannotRead(name_, error);
  offset_ += got;
  if (offset_ > limit_.maxBytes) return tooLarge();
  return std::min(got, count);
}

Status CappedFile::readRest(std::string& out) {
  constexpr std::size_t kChunk = 1 << 16;
  // Sized from stat up front; the loop still stops at the cap if the file keeps going.
  out.reserve(out.size() + static_cast<std::size_t>(std::min(size_, limit_.maxBytes)) + 1);
  while (true) {
    Result<std::size_t> got = read(out, kChunk);
    if (!got) return got.error();
    if (got.value() < kChunk) return Status::success();
  }
}

Result<std::string> readFileCapped(const std::filesystem::path& file, FileLimit limit) {
  Result<CappedFile> opened = CappedFile::open(file, limit);
  if (!opened) return opened.error();
  std::string text;
  if (Status read = opened.value().readRest(text); !read) return read.error();
  return text;
}

}  // namespace warpath
