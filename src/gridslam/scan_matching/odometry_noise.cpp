#include "gridslam/scan_matching/odometry_noise.hpp"

#include <algorithm>
#include <cmath>

#include "gridslam/common/check.hpp"

namespace gridslam::scan_matching {
namespace {

/// Median of the chi-square distribution with one degree of freedom.
constexpr double kChi2Median1 = 0.45493642311957283;

double RobustScale(std::vector<double> squares, double min_scale) {
  const auto middle = squares.begin() + static_cast<std::ptrdiff_t>(squares.size() / 2);
  std::nth_element(squares.begin(), middle, squares.end());
  return std::clamp(std::sqrt(*middle / kChi2Median1), min_scale, 1.0);
}

}  // namespace

OdometryNoiseEstimate::OdometryNoiseEstimate(int window, double min_scale)
    : window_(static_cast<std::size_t>(window)), min_scale_(min_scale) {
  GRIDSLAM_CHECK(window > 0 && min_scale > 0.0 && min_scale <= 1.0);
}

void OdometryNoiseEstimate::Add(double theta_correction, double sigma_theta) {
  const double t = theta_correction / sigma_theta;
  if (rotation_.size() < window_) {
    rotation_.push_back(t * t);
  } else {
    rotation_[next_] = t * t;
    next_ = (next_ + 1) % window_;
  }
  if (rotation_.size() == window_) {
    rotation_scale_ = RobustScale(rotation_, min_scale_);
  }
}

}  // namespace gridslam::scan_matching
