// Exact, locale-independent number parsing for the text readers (std::from_chars). Internal.
#pragma once

#include <charconv>
#include <string_view>

namespace gridslam::io::internal {

/// Parses the whole of `text` as a double; false if it is not exactly one number.
inline bool ParseDouble(std::string_view text, double& value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

}  // namespace gridslam::io::internal
