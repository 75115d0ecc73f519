#pragma once
// Status results for the render library's boundaries: a failed context, an unreadable or
// unwritable file, a malformed image are reported as a message naming the problem, never
// thrown and never a crash.

#include <string>
#include <utility>
#include <variant>

namespace warpath::render {

class Status {
 public:
  static Status success() { return Status(); }
  static Status failure(std::string message) { return Status(std::move(message)); }

  bool ok() const { return message_.empty(); }
  explicit operator bool() const { return ok(); }
  // Empty when ok().
  const std::string& message() const { return message_; }

 private:
  Status() = default;
  explicit Status(std::string message) : message_(std::move(message)) {
    if (message_.empty()) message_ = "unknown error";
  }
  std::string message_;
};

// A value or the failure that prevented it.
template <class T>
class Result {
 public:
  Result(T value) : state_(std::move(value)) {}          // NOLINT(google-explicit-constructor)
  Result(Status failure) : state_(std::move(failure)) {  // NOLINT(google-explicit-constructor)
    if (std::get<Status>(state_).ok()) state_ = Status::failure("no value");
  }

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }
  const T& value() const& { return std::get<T>(state_); }
  T& value() & { return std::get<T>(state_); }
  T&& value() && { return std::get<T>(std::move(state_)); }
  // The failure; success() when ok().
  Status status() const { return ok() ? Status::success() : std::get<Status>(state_); }

 private:
  std::variant<T, Status> state_;
};

}  // namespace warpath::render
