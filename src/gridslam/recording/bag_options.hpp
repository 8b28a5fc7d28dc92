// Options of the bag reader (ROS 1 .bag, MCAP, rosbag2 sqlite3): which topics and frames carry
// the scans and the odometry. Empty strings mean auto-detection (bag_reader.hpp).
#pragma once

#include <string>

#include "gridslam/common/options.hpp"

namespace gridslam::recording {

struct BagOptions {
  /// sensor_msgs/LaserScan topic; "" = the bag's only LaserScan topic.
  std::string scan_topic;
  /// nav_msgs/Odometry topic; "" = the bag's only Odometry topic, else TF odom_frame->base_frame.
  std::string odom_topic;
  /// Odometry frame of TF odometry; "" = "odom" (REP-105). Setting it (or base_frame) selects
  /// TF odometry even when the bag has an Odometry topic.
  std::string odom_frame;
  /// Robot frame; "" = the Odometry messages' child_frame_id, else "base_link".
  std::string base_frame;

  template <class V>
  void Visit(V& v) {
    v("scan_topic", scan_topic, "sensor_msgs/LaserScan topic; '' = auto-detect");
    v("odom_topic", odom_topic, "nav_msgs/Odometry topic; '' = auto-detect (else TF)");
    v("odom_frame", odom_frame, "TF odometry frame; '' = odom");
    v("base_frame", base_frame, "Robot frame; '' = odometry child frame or base_link");
  }
  [[nodiscard]] Status Validate() const { return Status::Ok(); }
};

}  // namespace gridslam::recording
