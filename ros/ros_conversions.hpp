// Between ROS messages and the plain structs of live_types.hpp (C++17 side of gridslam_node: the
// only files that include ROS headers).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "live_types.hpp"
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/time.h>
#include <sensor_msgs/LaserScan.h>

namespace gridslam::live {

std::int64_t ToNanoseconds(const ros::Time& t);
ros::Time ToRosTime(std::int64_t stamp_ns);

/// A frame id without its leading '/' (ROS 1 bags often write "/odom"; tf2 refuses it).
std::string StripSlash(const std::string& frame);

Transform3D ToTransform3D(const geometry_msgs::Transform& t);
Transform3D ToTransform3D(const geometry_msgs::Pose& p);

/// The scan's geometry and ranges (the TF parts are left to the caller).
ScanInput ToScanInput(const sensor_msgs::LaserScan& scan);

geometry_msgs::TransformStamped ToTransformStamped(const PlanarPose& T_parent_child,
                                                   const std::string& parent,
                                                   const std::string& child, const ros::Time& t);
nav_msgs::OccupancyGrid ToOccupancyGrid(const GridOutput& grid, const std::string& frame);
nav_msgs::Path ToPath(const std::vector<StampedPose>& poses, const std::string& frame);

}  // namespace gridslam::live
