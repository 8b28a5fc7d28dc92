// A timestamped pose: one entry of a trajectory (what `gridslam map`/`odometry` write and `eval`
// reads; io/trajectory_io.hpp reads and writes them as text).
#pragma once

#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"

namespace gridslam::eval {

struct StampedPose {
  Time time;   ///< The scan's printed timestamp (its identity in the relations).
  Pose2 pose;  ///< Pose in the trajectory's frame (docs/frames.md).
};

}  // namespace gridslam::eval
