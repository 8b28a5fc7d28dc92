// Angle helpers: normalization to [-pi, pi) and degree conversion (REP-103: radians everywhere).
#pragma once

#include <cmath>
#include <numbers>

namespace gridslam {

/// Wraps `theta` [rad] into [-pi, pi).
inline double NormalizeAngle(double theta) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  if (theta >= -std::numbers::pi && theta < std::numbers::pi) {
    return theta;
  }
  double wrapped = std::fmod(theta + std::numbers::pi, kTwoPi);
  if (wrapped < 0.0) {
    wrapped += kTwoPi;
  }
  wrapped -= std::numbers::pi;
  // fmod can round to exactly +pi for values just below a multiple of 2 pi.
  return wrapped >= std::numbers::pi ? -std::numbers::pi : wrapped;
}

constexpr double DegToRad(double deg) { return deg * std::numbers::pi / 180.0; }
constexpr double RadToDeg(double rad) { return rad * 180.0 / std::numbers::pi; }

}  // namespace gridslam
