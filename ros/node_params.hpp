// gridslam_node's ROS parameters (docs/ros.md "Node parameters"), read from the node's private
// namespace (~name). The SLAM options themselves come from the gridslam YAML file named by
// ~config, as for `gridslam map --config`.
#pragma once

#include <string>
#include <vector>

#include "mapping_core.hpp"
#include <ros/node_handle.h>

namespace gridslam::live {

struct NodeParams {
  CoreSettings core;  ///< ~config, ~set, odometry source, ~odom_timeout, ~map_publish_period.
  std::string scan_topic = "scan";
  std::string odom_topic;  ///< Topic odometry (nav_msgs/Odometry) when set.
  std::string map_frame = "map";
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  double tf_timeout = 0.2;           ///< TF odometry: wait for a sample after a scan [s, wall].
  double mounting_timeout = 1.0;     ///< Wait for base -> laser at the first scan [s, wall].
  double tf_publish_period = 0.05;   ///< Re-publication of map -> odom [s, wall]; 0 = off.
  double transform_tolerance = 0.1;  ///< Future-dating of the re-published map -> odom [s].
  int scan_queue_size = 2000;        ///< Subscriber queue of ~scan_topic [messages].
  std::string output_dir = "gridslam_map";  ///< Default folder of the services.
};

/// Reads the parameters; false with `error` set when a value is unusable.
bool ReadNodeParams(const ros::NodeHandle& private_nh, NodeParams* params, std::string* error);

/// The folder the services write into: ~output_dir as it is now (re-read at every call).
std::string OutputDir(const ros::NodeHandle& private_nh, const NodeParams& params);

}  // namespace gridslam::live
