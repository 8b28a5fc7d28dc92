#include "node_params.hpp"

#include <algorithm>

namespace gridslam::live {

bool ReadNodeParams(const ros::NodeHandle& private_nh, NodeParams* params, std::string* error) {
  NodeParams& p = *params;
  private_nh.param("config", p.core.config_path, p.core.config_path);
  // ~set: a list of "section.key=value" (rosparam, launch files) or, as `_set:=...` on the command
  // line can only give a string, one string of assignments separated by ';'.
  if (!private_nh.getParam("set", p.core.overrides)) {
    std::string assignments;
    private_nh.getParam("set", assignments);
    std::size_t start = 0;
    while (start < assignments.size()) {
      const std::size_t end = std::min(assignments.find(';', start), assignments.size());
      if (end > start) {
        p.core.overrides.push_back(assignments.substr(start, end - start));
      }
      start = end + 1;
    }
  }
  private_nh.param("scan_topic", p.scan_topic, p.scan_topic);
  bool use_odom_topic = false;
  private_nh.param("use_odom_topic", use_odom_topic, use_odom_topic);
  private_nh.param("odom_topic", p.odom_topic, p.odom_topic);
  bool use_odometry = true;
  private_nh.param("use_odometry", use_odometry, use_odometry);
  if (use_odom_topic && p.odom_topic.empty()) {
    p.odom_topic = "odom";
  }
  p.core.odometry = !use_odometry           ? OdometrySource::kNone
                    : !p.odom_topic.empty() ? OdometrySource::kTopic
                                            : OdometrySource::kTf;
  private_nh.param("map_frame", p.map_frame, p.map_frame);
  private_nh.param("odom_frame", p.odom_frame, p.odom_frame);
  private_nh.param("base_frame", p.base_frame, p.base_frame);
  private_nh.param("map_publish_period", p.core.map_publish_period, p.core.map_publish_period);
  private_nh.param("odom_timeout", p.core.odom_wait, p.core.odom_wait);
  private_nh.param("tf_timeout", p.tf_timeout, p.tf_timeout);
  private_nh.param("mounting_timeout", p.mounting_timeout, p.mounting_timeout);
  private_nh.param("tf_publish_period", p.tf_publish_period, p.tf_publish_period);
  private_nh.param("transform_tolerance", p.transform_tolerance, p.transform_tolerance);
  private_nh.param("scan_queue_size", p.scan_queue_size, p.scan_queue_size);
  private_nh.param("output_dir", p.output_dir, p.output_dir);
  if (p.core.odometry == OdometrySource::kTf) {
    p.core.odom_wait = p.tf_timeout;  // the core waits for TF samples as for topic ones
  }
  if (p.map_frame.empty() || p.odom_frame.empty() || p.base_frame.empty()) {
    *error = "~map_frame, ~odom_frame and ~base_frame must not be empty";
    return false;
  }
  if (p.tf_timeout < 0.0 || p.mounting_timeout < 0.0 || p.core.odom_wait < 0.0 ||
      p.tf_publish_period < 0.0 || p.scan_queue_size < 1) {
    *error =
        "~tf_timeout, ~mounting_timeout, ~odom_timeout and ~tf_publish_period must be >= 0, "
        "~scan_queue_size >= 1";
    return false;
  }
  return true;
}

std::string OutputDir(const ros::NodeHandle& private_nh, const NodeParams& params) {
  std::string dir = params.output_dir;
  private_nh.getParam("output_dir", dir);
  return dir;
}

}  // namespace gridslam::live
