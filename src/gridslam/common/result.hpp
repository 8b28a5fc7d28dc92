// Status and Result<T>: expected, data-dependent failures as values (docs/style.md §8, kind 1),
// shaped like std::expected / absl::Status, which C++20 with libstdc++ 12 lacks. An error carries a
// message and, for input errors, the file and line number it refers to.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>

#include "gridslam/common/check.hpp"

namespace gridslam {

/// What went wrong; `kInvalidInput` maps to exit code 2, `kRuntime` to exit code 1.
enum class ErrorCode { kInvalidInput, kNotFound, kRuntime };

struct Error {
  ErrorCode code = ErrorCode::kInvalidInput;
  std::string message;
  std::string file;  ///< File the error refers to; empty if none.
  long line = 0;     ///< 1-based line number in `file`; 0 if none.

  /// "file:line: message", "file: message" or "message".
  [[nodiscard]] std::string ToString() const;
};

inline Error InvalidInput(std::string message, std::string file = {}, long line = 0) {
  return Error{ErrorCode::kInvalidInput, std::move(message), std::move(file), line};
}
inline Error NotFound(std::string message, std::string file = {}) {
  return Error{ErrorCode::kNotFound, std::move(message), std::move(file), 0};
}
inline Error RuntimeError(std::string message) {
  return Error{ErrorCode::kRuntime, std::move(message), {}, 0};
}

/// Success or an Error.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)) {}  // NOLINT(google-explicit-constructor)
  static Status Ok() { return {}; }
  [[nodiscard]] bool ok() const { return !error_.has_value(); }
  [[nodiscard]] const Error& error() const {
    GRIDSLAM_CHECK(error_.has_value()) << "error() on an ok Status";
    return *error_;
  }

 private:
  std::optional<Error> error_;
};

/// A value of type T or an Error.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : data_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : data_(std::move(error)) {}  // NOLINT(google-explicit-constructor)
  Result(Status status) : data_(status.error()) {}  // NOLINT(google-explicit-constructor)
  [[nodiscard]] bool ok() const { return std::holds_alternative<T>(data_); }
  [[nodiscard]] const T& value() const& {
    GRIDSLAM_CHECK(ok()) << "value() on an error Result: " << std::get<Error>(data_).ToString();
    return std::get<T>(data_);
  }
  [[nodiscard]] T& value() & {
    GRIDSLAM_CHECK(ok()) << "value() on an error Result: " << std::get<Error>(data_).ToString();
    return std::get<T>(data_);
  }
  [[nodiscard]] T&& value() && {
    GRIDSLAM_CHECK(ok()) << "value() on an error Result: " << std::get<Error>(data_).ToString();
    return std::get<T>(std::move(data_));
  }
  [[nodiscard]] const Error& error() const {
    GRIDSLAM_CHECK(!ok()) << "error() on an ok Result";
    return std::get<Error>(data_);
  }
  [[nodiscard]] Status status() const { return ok() ? Status() : Status(error()); }

 private:
  std::variant<T, Error> data_;
};

}  // namespace gridslam

/// Returns the error of a Status or Result expression from the enclosing function.
#define GRIDSLAM_RETURN_IF_ERROR(expr) \
  do {                                 \
    auto gridslam_status_ = (expr);    \
    if (!gridslam_status_.ok()) {      \
      return gridslam_status_.error(); \
    }                                  \
  } while (false)
