// A planar laser scan and the frame (one timestamped scan with its odometry) that flows through
// the pipeline (docs/design.md §1.1). Beam k has angle angle_min + k * angle_increment in the laser
// frame (0 along the laser's +x, counter-clockwise), as sensor_msgs/LaserScan.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"

namespace gridslam {

struct LaserScan {
  std::vector<float> ranges;     ///< [m], one per beam.
  double angle_min = 0.0;        ///< Angle of the first beam [rad].
  double angle_increment = 0.0;  ///< Angle between beams [rad].
  double range_min = 0.0;        ///< Readings at or below this are no-returns [m].
  double range_max = 0.0;        ///< Readings at or above this are no-returns [m].

  [[nodiscard]] std::size_t size() const { return ranges.size(); }
  [[nodiscard]] double Angle(std::size_t k) const {
    return angle_min + static_cast<double>(k) * angle_increment;
  }
  /// True when beam k returned from an obstacle (finite, in (range_min, range_max)). The limits
  /// are compared in the readings' (float) precision, so a reading equal to range_max is not a hit.
  [[nodiscard]] bool IsHit(std::size_t k) const;
  /// True when beam k saw nothing within range (finite, at or above range_max, above range_min).
  [[nodiscard]] bool IsNoReturn(std::size_t k) const;
  /// Endpoints of the hits in the laser frame [m].
  [[nodiscard]] std::vector<Eigen::Vector2d> HitPoints() const;
  /// Number of hits.
  [[nodiscard]] std::size_t CountHits() const;
};

/// One laser scan with its odometry, as delivered by a log reader or a robot.
struct Frame {
  Time time;            ///< The scan's printed timestamp: its identity in outputs and relations.
  Time corrected_time;  ///< Timestamp repaired for ordering/interpolation (== time if not needed).
  Pose2 T_odom_base;    ///< Odometry pose of the robot centre at the scan.
  /// False when the recording has no odometry: T_odom_base is then a placeholder (identity) and
  /// the front end predicts the motion from the scans alone.
  bool has_odometry = true;
  Pose2 T_base_laser;  ///< Laser mounting on the robot.
  LaserScan scan;
  std::optional<Pose2> T_world_base_true;  ///< Ground truth, when the log has it (TRUEPOS).
  long source_line = 0;                    ///< Line of the log it came from (for messages).

  [[nodiscard]] Pose2 T_odom_laser() const { return T_odom_base * T_base_laser; }
};

}  // namespace gridslam
