// libFuzzer harness: one CARMEN line through the tokenizer and the message parser, with the
// default options and with FLASER geometry configured. Invariant: a parsed laser line has a
// finite geometry and bounded poses; nothing crashes or reads out of bounds.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "gridslam/io/internal/carmen_line.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace gridslam::io;
  const std::string line = gridslam::fuzz::AsString(data, size);
  std::vector<std::string_view> tokens;
  internal::SplitFields(line, tokens);
  internal::CarmenMessage message;
  CarmenOptions options;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      options.flaser_angle_increment = 0.01;
      options.lenient = true;
    }
    const gridslam::Status status =
        internal::ParseCarmenMessage(tokens, options, "fuzz.clf", 1, message);
    if (status.ok() && message.kind == internal::CarmenKind::kLaser) {
      if (!std::isfinite(message.scan.angle_min) || !std::isfinite(message.scan.angle_increment)) {
        __builtin_trap();
      }
      if (message.robot_pose &&
          std::abs(message.robot_pose->x()) > internal::kMaxCarmenCoordinate) {
        __builtin_trap();
      }
    }
  }
  return 0;
}
