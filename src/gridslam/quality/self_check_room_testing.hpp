// Test fixture of the self-check tests (map_self_check_test, local_confirmation_test): a robot
// drives out and back through a closed room, its scans simulated from the true poses and placed
// at estimated poses that may carry an error on the way back.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::quality::testing {

// A closed rectangular room [-6, 6] x [-3, 3] with a 2 m pillar wall at x = 0, y in [1, 3].
// Returns the range along the ray from `o` in direction `d` (unit) to the first wall.
inline double RayRange(const Eigen::Vector2d& o, const Eigen::Vector2d& d) {
  double best = std::numeric_limits<double>::infinity();
  const auto hit_x = [&](double x, double y_lo, double y_hi) {
    if (std::abs(d.x()) < 1e-12) return;
    const double t = (x - o.x()) / d.x();
    const double y = o.y() + t * d.y();
    if (t > 1e-9 && y >= y_lo && y <= y_hi) best = std::min(best, t);
  };
  const auto hit_y = [&](double y, double x_lo, double x_hi) {
    if (std::abs(d.y()) < 1e-12) return;
    const double t = (y - o.y()) / d.y();
    const double x = o.x() + t * d.x();
    if (t > 1e-9 && x >= x_lo && x <= x_hi) best = std::min(best, t);
  };
  hit_x(-6.0, -3.0, 3.0);
  hit_x(6.0, -3.0, 3.0);
  hit_y(-3.0, -6.0, 6.0);
  hit_y(3.0, -6.0, 6.0);
  hit_x(0.0, 1.0, 3.0);
  return best;
}

// A 360-beam scan of the room from the true pose `T_world_laser`.
inline LaserScan RoomScan(const Pose2& T_world_laser) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi;
  scan.angle_increment = 2.0 * std::numbers::pi / 360.0;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  for (int k = 0; k < 360; ++k) {
    const double a = T_world_laser.theta() + scan.Angle(static_cast<std::size_t>(k));
    scan.ranges.push_back(static_cast<float>(
        RayRange(T_world_laser.translation(), Eigen::Vector2d(std::cos(a), std::sin(a)))));
  }
  return scan;
}

// The robot drives along y = -1.5 to the right, then back along y = -0.5 (true poses).
inline std::vector<Pose2> TruePoses() {
  std::vector<Pose2> poses;
  for (double x = -5.0; x <= 5.0; x += 0.25) poses.emplace_back(x, -1.5, 0.0);
  for (double x = 5.0; x >= -5.0; x -= 0.25) poses.emplace_back(x, -0.5, std::numbers::pi);
  return poses;
}

struct SimRun {
  std::vector<LaserScan> scans;
  std::vector<fusion::PosedScan> posed;
};

// Scans from the true poses, placed at the estimated poses: the way back is estimated with a
// yaw error `yaw` [rad] about the turning point and an offset `shift` [m] along y.
inline SimRun MakeRun(double yaw, double shift) {
  const std::vector<Pose2> truth = TruePoses();
  SimRun run;
  run.scans.reserve(truth.size());
  for (const Pose2& p : truth) run.scans.push_back(RoomScan(p));
  const std::size_t half = truth.size() / 2;
  const Pose2 pivot(5.0, -1.0, 0.0);
  const Pose2 error = pivot * Pose2(0.0, shift, yaw) * pivot.Inverse();
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const Pose2 estimate = k < half ? truth[k] : error * truth[k];
    run.posed.push_back({estimate, Pose2(), &run.scans[k]});
  }
  return run;
}

}  // namespace gridslam::quality::testing
