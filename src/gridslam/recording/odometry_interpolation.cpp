#include "gridslam/recording/odometry_interpolation.hpp"

#include <algorithm>

#include "gridslam/common/check.hpp"

namespace gridslam::recording {

Pose2 InterpolateOdometry(std::span<const OdometrySample> samples, std::int64_t stamp_ns,
                          bool* clamped) {
  GRIDSLAM_CHECK(!samples.empty()) << "no odometry samples to interpolate";
  bool outside = false;
  Pose2 pose;
  const auto it =
      std::lower_bound(samples.begin(), samples.end(), stamp_ns,
                       [](const OdometrySample& s, std::int64_t t) { return s.stamp_ns < t; });
  if (it == samples.begin()) {
    outside = it->stamp_ns != stamp_ns;
    pose = it->pose;
  } else if (it == samples.end()) {
    outside = true;
    pose = samples.back().pose;
  } else {
    const OdometrySample& b = *it;
    const OdometrySample& a = *(it - 1);
    const auto span = static_cast<double>(b.stamp_ns - a.stamp_ns);
    const double u = span > 0.0 ? static_cast<double>(stamp_ns - a.stamp_ns) / span : 0.0;
    const Eigen::Vector2d p = (1.0 - u) * a.pose.translation() + u * b.pose.translation();
    const double dtheta = NormalizeAngle(b.pose.theta() - a.pose.theta());
    pose = Pose2(p, a.pose.theta() + u * dtheta);
  }
  if (clamped != nullptr) {
    *clamped = outside;
  }
  return pose;
}

}  // namespace gridslam::recording
