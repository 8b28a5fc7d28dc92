// A ground-truth relation of the SLAM benchmark (Kümmerle et al. 2009; docs/formats.md §4): the
// motion of the robot from its pose at t1 to its pose at t2, expressed in the frame at t1.
#pragma once

#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"

namespace gridslam::eval {

struct Relation {
  Time t1;
  Time t2;
  Pose2 T_1_2;  ///< Pose at t2 in the frame of the pose at t1.
};

}  // namespace gridslam::eval
