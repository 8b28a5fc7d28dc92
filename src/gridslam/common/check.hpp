// Fatal invariant checks for programming errors (docs/style.md §8, kind 2): a broken invariant
// aborts with file, line and message in every build type, like Cartographer's CHECK.
//
//   GRIDSLAM_CHECK(resolution > 0.0) << "resolution was " << resolution;
#pragma once

#include <sstream>

namespace gridslam::internal {

/// Collects the message of a failed check and aborts when destroyed.
class CheckFailure {
 public:
  CheckFailure(const char* file, int line, const char* condition);
  [[noreturn]] ~CheckFailure();
  CheckFailure(const CheckFailure&) = delete;
  CheckFailure& operator=(const CheckFailure&) = delete;
  std::ostream& stream() { return stream_; }

 private:
  std::ostringstream stream_;
};

/// Turns the stream expression into void so that it fits the ternary in GRIDSLAM_CHECK.
struct Voidify {
  void operator&(std::ostream&) {}
};

}  // namespace gridslam::internal

#define GRIDSLAM_CHECK(condition)                 \
  (condition) ? (void)0                           \
              : ::gridslam::internal::Voidify() & \
                    ::gridslam::internal::CheckFailure(__FILE__, __LINE__, #condition).stream()
