#pragma once
// Errors from reading files: where (file, line) and what went wrong, for people to read.

#include <string>
#include <utility>
#include <variant>

namespace warpath::pathing {

struct LoadError {
  std::string file;  // as given by the caller
  int line = 0;      // 1-based; 0 when the problem is not tied to a line (e.g. cannot open)
  std::string message;

  // "file:line: message" (or "file: message" without a line).
  std::string describe() const;
};

// A value or the error that prevented it. Library boundaries return this instead of throwing.
template <class T>
class Loaded {
 public:
  Loaded(T value) : state_(std::move(value)) {}          // NOLINT(google-explicit-constructor)
  Loaded(LoadError error) : state_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }
  const T& value() const& { return std::get<T>(state_); }
  T& value() & { return std::get<T>(state_); }
  T&& value() && { return std::get<T>(std::move(state_)); }
  const LoadError& error() const { return std::get<LoadError>(state_); }

 private:
  std::variant<T, LoadError> state_;
};

}  // namespace warpath::pathing
