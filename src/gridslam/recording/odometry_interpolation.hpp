// Odometry at a scan's stamp (docs/ros.md): linear in x, y and along the shortest arc in the
// heading between the samples before and after it, clamped to the first / last sample outside
// their span. Shared by the bag reader and the ROS node (ros/), which interpolate nav_msgs/Odometry
// samples the same way.
#pragma once

#include <cstdint>
#include <span>

#include "gridslam/geometry/pose2.hpp"

namespace gridslam::recording {

/// One odometry pose T_odom_base at a stamp.
struct OdometrySample {
  std::int64_t stamp_ns = 0;
  Pose2 pose;
  std::uint64_t sequence = 0;  ///< Position in the recording's storage order (bags).
};

/// The pose at `stamp_ns` from `samples` sorted by stamp (at least one). `clamped` (optional) is
/// set when the stamp lies outside the samples' span and the nearest end sample was returned.
Pose2 InterpolateOdometry(std::span<const OdometrySample> samples, std::int64_t stamp_ns,
                          bool* clamped = nullptr);

}  // namespace gridslam::recording
