// The error channel of the libraries' readers and parsers: a value, or the reason there is none
// (in the spirit of C++23's std::expected, with a message for a person as the error). The core's
// computations answer with a Status (status.h); the CLI alone turns errors into exit codes.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace oblique {

/// The value of an Expected for an operation that has nothing to return (starting a process).
struct Done {};

template <class T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : value_(std::move(value)) {}  // NOLINT: implicit, as std::expected's

  /// No value, because of `error` (a sentence naming what was wrong and where).
  static Expected failure(std::string error) {
    Expected e;
    e.error_ = std::move(error);
    return e;
  }

  bool has_value() const noexcept { return value_.has_value(); }
  explicit operator bool() const noexcept { return has_value(); }

  /// The value; precondition: has_value().
  const T& operator*() const& { return *value_; }
  T& operator*() & { return *value_; }
  T&& operator*() && { return *std::move(value_); }
  const T* operator->() const { return &*value_; }
  T* operator->() { return &*value_; }

  /// The value, or std::invalid_argument carrying error() (for static data a test reads once).
  const T& value() const& {
    if (!value_) throw std::invalid_argument(error_);
    return *value_;
  }
  T value() && {
    if (!value_) throw std::invalid_argument(error_);
    return *std::move(value_);
  }

  /// Why there is no value ("" when there is one).
  const std::string& error() const noexcept { return error_; }

 private:
  Expected() = default;
  std::optional<T> value_;
  std::string error_;
};

}  // namespace oblique
