#include "ros_conversions.hpp"

#include <cmath>

namespace gridslam::live {
namespace {

geometry_msgs::Quaternion YawQuaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.x = 0.0;
  q.y = 0.0;
  q.z = std::sin(0.5 * yaw);
  q.w = std::cos(0.5 * yaw);
  return q;
}

}  // namespace

std::int64_t ToNanoseconds(const ros::Time& t) {
  return static_cast<std::int64_t>(t.sec) * 1'000'000'000 + static_cast<std::int64_t>(t.nsec);
}

ros::Time ToRosTime(std::int64_t stamp_ns) {
  ros::Time t;
  t.sec = static_cast<std::uint32_t>(stamp_ns / 1'000'000'000);
  t.nsec = static_cast<std::uint32_t>(stamp_ns % 1'000'000'000);
  return t;
}

std::string StripSlash(const std::string& frame) {
  return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame;
}

Transform3D ToTransform3D(const geometry_msgs::Transform& t) {
  return {t.translation.x, t.translation.y, t.translation.z, t.rotation.x,
          t.rotation.y,    t.rotation.z,    t.rotation.w};
}

Transform3D ToTransform3D(const geometry_msgs::Pose& p) {
  return {p.position.x,    p.position.y,    p.position.z,   p.orientation.x,
          p.orientation.y, p.orientation.z, p.orientation.w};
}

ScanInput ToScanInput(const sensor_msgs::LaserScan& scan) {
  ScanInput in;
  in.stamp_ns = ToNanoseconds(scan.header.stamp);
  in.angle_min = scan.angle_min;
  in.angle_increment = scan.angle_increment;
  in.range_min = scan.range_min;
  in.range_max = scan.range_max;
  in.ranges = scan.ranges;
  return in;
}

geometry_msgs::TransformStamped ToTransformStamped(const PlanarPose& T_parent_child,
                                                   const std::string& parent,
                                                   const std::string& child, const ros::Time& t) {
  geometry_msgs::TransformStamped msg;
  msg.header.stamp = t;
  msg.header.frame_id = parent;
  msg.child_frame_id = child;
  msg.transform.translation.x = T_parent_child.x;
  msg.transform.translation.y = T_parent_child.y;
  msg.transform.translation.z = 0.0;
  msg.transform.rotation = YawQuaternion(T_parent_child.yaw);
  return msg;
}

nav_msgs::OccupancyGrid ToOccupancyGrid(const GridOutput& grid, const std::string& frame) {
  nav_msgs::OccupancyGrid msg;
  msg.header.stamp = ToRosTime(grid.stamp_ns);
  msg.header.frame_id = frame;
  msg.info.map_load_time = msg.header.stamp;
  msg.info.resolution = static_cast<float>(grid.resolution);
  msg.info.width = static_cast<std::uint32_t>(grid.width);
  msg.info.height = static_cast<std::uint32_t>(grid.height);
  msg.info.origin.position.x = grid.origin_x;
  msg.info.origin.position.y = grid.origin_y;
  msg.info.origin.orientation.w = 1.0;
  msg.data = grid.cells;
  return msg;
}

nav_msgs::Path ToPath(const std::vector<StampedPose>& poses, const std::string& frame) {
  nav_msgs::Path msg;
  msg.header.frame_id = frame;
  msg.header.stamp = poses.empty() ? ros::Time() : ToRosTime(poses.back().stamp_ns);
  msg.poses.resize(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    geometry_msgs::PoseStamped& p = msg.poses[k];
    p.header.frame_id = frame;
    p.header.stamp = ToRosTime(poses[k].stamp_ns);
    p.pose.position.x = poses[k].pose.x;
    p.pose.position.y = poses[k].pose.y;
    p.pose.orientation = YawQuaternion(poses[k].pose.yaw);
  }
  return msg;
}

}  // namespace gridslam::live
