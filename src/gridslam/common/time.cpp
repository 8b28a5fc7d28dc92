#include "gridslam/common/time.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace gridslam {

Time FromSeconds(double seconds) { return Time(SecondsToDuration(seconds)); }

double ToSeconds(Time time) { return ToSeconds(time.time_since_epoch()); }

double ToSeconds(Duration duration) { return static_cast<double>(duration.count()) * 1e-9; }

Duration SecondsToDuration(double seconds) {
  return Duration(static_cast<std::int64_t>(std::llround(seconds * 1e9)));
}

std::optional<Time> ParseSeconds(std::string_view text) {
  if (text.empty()) {
    return std::nullopt;
  }
  // Exponent notation is rare in logs; fall back to double parsing for it.
  if (text.find_first_of("eE") != std::string_view::npos) {
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value) ||
        std::abs(value) > static_cast<double>(kMaxParsedSeconds)) {
      return std::nullopt;
    }
    return FromSeconds(value);
  }
  bool negative = false;
  std::size_t pos = 0;
  if (text[0] == '-' || text[0] == '+') {
    negative = text[0] == '-';
    pos = 1;
  }
  std::int64_t whole = 0;
  std::int64_t frac = 0;
  int frac_digits = 0;
  bool any_digit = false;
  bool round_up = false;
  bool seen_point = false;
  for (; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (c == '.') {
      if (seen_point) {
        return std::nullopt;
      }
      seen_point = true;
      continue;
    }
    if (c < '0' || c > '9') {
      return std::nullopt;
    }
    any_digit = true;
    const int digit = c - '0';
    if (!seen_point) {
      whole = whole * 10 + digit;
      if (whole > kMaxParsedSeconds) {
        return std::nullopt;  // Would overflow int64 nanoseconds.
      }
    } else if (frac_digits < 9) {
      frac = frac * 10 + digit;
      ++frac_digits;
    } else if (frac_digits == 9) {
      round_up = digit >= 5;
      ++frac_digits;
    }
  }
  if (!any_digit) {
    return std::nullopt;
  }
  for (int i = frac_digits; i < 9; ++i) {
    frac *= 10;
  }
  std::int64_t ns = whole * 1'000'000'000LL + frac + (round_up ? 1 : 0);
  return Time(Duration(negative ? -ns : ns));
}

std::string FormatSeconds(Time time, int decimals) {
  const std::int64_t count = time.time_since_epoch().count();
  const bool negative = count < 0;
  // The magnitude as unsigned: -INT64_MIN does not fit an int64.
  const std::uint64_t ns = negative ? std::uint64_t{0} - static_cast<std::uint64_t>(count)
                                    : static_cast<std::uint64_t>(count);
  if (decimals < 0) {
    decimals = 0;
  }
  if (decimals > 9) {
    decimals = 9;
  }
  std::uint64_t scale = 1;
  for (int i = decimals; i < 9; ++i) {
    scale *= 10;
  }
  const std::uint64_t units = (ns + scale / 2) / scale;  // rounded to `decimals` digits
  std::uint64_t denom = 1;
  for (int i = 0; i < decimals; ++i) {
    denom *= 10;
  }
  char buffer[64];
  if (decimals == 0) {
    std::snprintf(buffer, sizeof(buffer), "%s%llu", negative ? "-" : "",
                  static_cast<unsigned long long>(units));
  } else {
    std::snprintf(buffer, sizeof(buffer), "%s%llu.%0*llu", negative ? "-" : "",
                  static_cast<unsigned long long>(units / denom), decimals,
                  static_cast<unsigned long long>(units % denom));
  }
  return buffer;
}

}  // namespace gridslam
