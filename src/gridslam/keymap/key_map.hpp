// Key maps (docs/design.md §1.3; docs/method.md §1.4): snapshots of the front end's rolling
// local map that become the vertices of the pose graph. A key map's frame is the window centre
// with yaw 0 in the odometry frame (`T_odom_key`); it holds the log-odds grid with MapLimits in
// that frame, and the scans it added to the map with their robot poses in that frame, so that a
// corrected pose of every scan follows from the optimized graph as T_map_key * T_key_scan.
#pragma once

#include <cstdint>
#include <vector>

#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::keymap {

/// A scan held by a key map. "scan" is the robot base frame at the scan's time (what trajectory
/// files report); the laser is at T_key_scan * T_base_laser.
struct KeyMapScan {
  Time time;           ///< Printed timestamp (the scan's identity).
  Pose2 T_key_scan;    ///< Robot pose in the key-map frame.
  Pose2 T_base_laser;  ///< Laser mounting.
  LaserScan scan;      ///< The ranges, if the front end keeps them (else empty).
};

struct KeyMap {
  int id = 0;                     ///< 0, 1, 2, ... in creation order.
  Time time;                      ///< Time of the last scan inserted before the snapshot.
  Pose2 T_odom_key;               ///< Key-map frame in the front end's odometry frame (yaw 0).
  Grid2D<float> log_odds;         ///< The window's log-odds; MapLimits in the key-map frame.
  std::vector<KeyMapScan> scans;  ///< Scans added since the previous key map, in order.
};

/// nav_msgs/OccupancyGrid-style image of a log-odds grid: kOccupiedCell above
/// `occupied_probability`, kFreeCell below `free_probability`, kUnknownCell otherwise.
OccupancyImage ToOccupancyImage(const Grid2D<float>& log_odds, double occupied_probability,
                                double free_probability);

/// 1 where the probability exceeds `occupied_probability` (the sources of the distance
/// transform, docs/design.md §1.4), else 0.
Grid2D<std::uint8_t> ObstacleMask(const Grid2D<float>& log_odds, double occupied_probability);

}  // namespace gridslam::keymap
