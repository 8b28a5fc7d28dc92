// Strong time type (docs/style.md §7, after Cartographer's common/time.h): int64 nanoseconds since
// the Unix epoch (or since a log's own relative time base). CARMEN's decimal seconds are parsed
// exactly, digit by digit, so a printed timestamp survives a read/write round trip unchanged.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace gridslam {

struct TimeClock {
  using rep = std::int64_t;
  using period = std::nano;
  using duration = std::chrono::duration<rep, period>;
  using time_point = std::chrono::time_point<TimeClock>;
  static constexpr bool is_steady = true;
};

using Duration = TimeClock::duration;
using Time = TimeClock::time_point;

/// Time from (possibly fractional) seconds; rounds to the nearest nanosecond.
Time FromSeconds(double seconds);
/// Seconds since the epoch as a double (loses precision below ~0.1 us for Unix times).
double ToSeconds(Time time);
/// Duration in seconds as a double.
double ToSeconds(Duration duration);
Duration SecondsToDuration(double seconds);

/// The largest |seconds| ParseSeconds accepts: 9e9 s (year 2255), inside int64 nanoseconds.
constexpr std::int64_t kMaxParsedSeconds = 9'000'000'000LL;

/// Parses a decimal number of seconds such as "976052864.458620", "-0.958593" or "1e3" exactly
/// to nanoseconds (digits beyond the ninth decimal are rounded). Returns nullopt if malformed,
/// not finite, or beyond +-kMaxParsedSeconds.
std::optional<Time> ParseSeconds(std::string_view text);

/// Formats as decimal seconds with `decimals` digits after the point (6 as CARMEN prints).
std::string FormatSeconds(Time time, int decimals = 6);

}  // namespace gridslam
