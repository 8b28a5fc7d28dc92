// Where the laser sits on the robot, measured from the data (docs/frames.md, "Laser mounting").
// Many logs carry no mounting (CARMEN RAWLASER lines, logs converted from bags without their
// /tf_static); the reader then assumes the laser at the robot's centre, and every pose the mapper
// writes is the laser's, not the robot's. The scans tell where the laser really is: if it sits
// `d` (in the robot frame) beyond the mounting the front end used, the matched motion is the
// odometry's motion seen from a point `d` off the centre of rotation. For an increment with
// rotation R and translation t, the matched one is D^-1 (t, R) D with D = (d, 0), whose translation
// is t + (R - I) d: the difference between the matched and the odometry's translation is linear in
// d, with a coefficient that grows with the turn. That is the 2-D hand-eye calibration of the
// laser against the odometry (Censi, Franchi, Marchionni, Oriolo, "Simultaneous calibration of
// odometry and sensor parameters for mobile robots", IEEE T-RO 29(2), 2013, where it is one part).
// Least squares over the increments, made robust by Tukey reweighting (slips and bad matches).
// Memory: 24 bytes per increment added.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"

namespace gridslam::scan_matching {

struct MountingResult {
  /// The laser's position beyond the mounting the front end used, in the robot frame [m].
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  /// Standard deviation of either component of `offset` [m] (the robust residual scale through
  /// the normal equations; the turns inform both directions alike); -1 when not measured.
  double sigma = -1.0;
  int increments = 0;  ///< Increments added (all of them enter the fit, reweighted).
  bool ok = false;     ///< The increments turned enough to measure the offset.
};

class MountingEstimate {
 public:
  /// One increment of the robot: as the odometry measured it and as the scan match found it
  /// (both in the previous pose's frame). The caller adds only increments it trusts (odometry
  /// consistent, a good match that constrains every direction).
  void Add(const Pose2& odometry_increment, const Pose2& matched_increment);

  /// The offset from the increments so far. Not ok before `min_increments` increments, or when
  /// their turns leave the normal equations singular.
  [[nodiscard]] MountingResult Estimate(int min_increments = 50) const;

  [[nodiscard]] int size() const { return static_cast<int>(samples_.size()); }

 private:
  struct Sample {
    double theta = 0.0;          ///< Odometry's turn [rad].
    Eigen::Vector2d difference;  ///< Matched minus odometry translation [m].
  };
  std::vector<Sample> samples_;
};

}  // namespace gridslam::scan_matching
