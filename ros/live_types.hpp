// The plain structs through which the ROS adapter (C++17, the only code that sees ROS headers)
// and the mapping core (C++20, the only code that sees gridslam) talk. Standard library only:
// this header is compiled in both languages. Stamps are ROS times in int64 nanoseconds; poses
// follow REP-103/105 (metres, radians, quaternions as geometry_msgs/Transform).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace gridslam::live {

/// A geometry_msgs/Transform as numbers: translation [m] and rotation quaternion.
struct Transform3D {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double qx = 0.0;
  double qy = 0.0;
  double qz = 0.0;
  double qw = 1.0;
};

/// A planar pose [m, m, rad].
struct PlanarPose {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

/// One sensor_msgs/LaserScan with its laser mounting.
struct ScanInput {
  std::int64_t stamp_ns = 0;  ///< header.stamp.
  float angle_min = 0.0F;     ///< [rad]
  float angle_increment = 0.0F;
  float range_min = 0.0F;  ///< [m]
  float range_max = 0.0F;
  std::vector<float> ranges;
  Transform3D T_base_laser;  ///< Laser mounting (static TF base -> laser frame).
};

/// One odometry sample: a nav_msgs/Odometry (header.stamp, pose.pose), or a TF odom -> child
/// transform; T_odom_base = T_odom_child * T_child_base, where T_child_base completes a TF
/// odometry that ends in an intermediate frame (odom -> base_footprint, then base_link).
struct OdometryInput {
  std::int64_t stamp_ns = 0;
  Transform3D T_odom_child;
  std::optional<Transform3D> T_child_base;  ///< nullopt: the child is the base frame.
};

/// Where the odometry comes from.
enum class OdometrySource { kTf, kTopic, kNone };

/// An occupancy grid as nav_msgs/OccupancyGrid: row-major, row 0 at the lowest y, -1 unknown,
/// 0 free, 100 occupied; origin = the lower-left corner of cell (0, 0) in the map frame.
struct GridOutput {
  std::int64_t stamp_ns = 0;
  int width = 0;
  int height = 0;
  double resolution = 0.0;  ///< [m / cell]
  double origin_x = 0.0;    ///< [m]
  double origin_y = 0.0;
  std::vector<std::int8_t> cells;
};

/// A corrected pose T_map_base at a scan's stamp.
struct StampedPose {
  std::int64_t stamp_ns = 0;
  PlanarPose pose;
};

/// Counters for status messages.
struct CoreProgress {
  long scans_received = 0;
  long scans_mapped = 0;
  long scans_dropped = 0;  ///< Unusable scans (no beams, non-finite geometry, no odometry yet)
                           ///< or after Finish.
  long scans_without_odometry = 0;  ///< Odometry clamped to the nearest sample (none after).
  long scans_queued = 0;
  long key_maps = 0;
  long loop_closures = 0;
  long maps_published = 0;
  bool finished = false;
};

}  // namespace gridslam::live
