#pragma once
// The one error type of every module (pathing, units, engine, render, tools): where a problem
// is (file, line, column) and what it is, for people to read. Library boundaries return a
// Result<T> (a value or the Error that prevented it) or a Status (success, or the Error), never
// throw. In namespace warpath so that every module names it unqualified.

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace warpath {

struct Error {
  std::string file;  // as given by the caller; empty when the problem is not about a file
  int line = 0;      // 1-based; 0 when the problem is not tied to a line (e.g. cannot open)
  int column = 0;    // 1-based; 0 when not tied to a column
  std::string message;

  // Compiler style, so editors and terminals can jump to the spot: "file:line:column: message",
  // "file:line: message" when column is 0, "file: message" when line is 0, just the message when
  // there is no file ("line N: message" when there is a line but no file).
  std::string describe() const;
};

// Success, or the Error that prevented it: for operations that give no value.
class [[nodiscard]] Status {
 public:
  Status(Error error) : error_(std::move(error)) {}  // NOLINT(google-explicit-constructor)
  static Status success() { return Status(); }
  static Status failure(Error error) { return Status(std::move(error)); }

  bool ok() const { return !error_.has_value(); }
  explicit operator bool() const { return ok(); }
  // [Limit: !ok()]
  const Error& error() const { return *error_; }

 private:
  Status() = default;
  std::optional<Error> error_;
};

// A value or the Error that prevented it.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : state_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }
  // [Limit: ok()]
  const T& value() const& { return std::get<T>(state_); }
  T& value() & { return std::get<T>(state_); }
  T&& value() && { return std::get<T>(std::move(state_)); }
  // [Limit: !ok()]
  const Error& error() const { return std::get<Error>(state_); }
  // Success, or the error: for callers that pass a failure on from an operation without value.
  Status status() const { return ok() ? Status::success() : Status(error()); }

 private:
  std::variant<T, Error> state_;
};

}  // namespace warpath
