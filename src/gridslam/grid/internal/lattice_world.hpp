// Test-only scans of an endless world: walls on the lines x = k * kSpacing + kWallOffset and
// y = k * kSpacing + kWallOffset (a city of square blocks), so a robot sees walls wherever it
// drives, however far a test moves a rolling window. Beams can be replaced at random by clutter
// (cells that turn obstacle and back) and by no-returns.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/scan_points.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::internal {

constexpr double kLatticeSpacing = 2.3;
constexpr double kLatticeWallOffset = 0.013;  ///< Keeps the walls off the cell borders.

/// Distance from `p` along the direction `angle` to the first wall of the lattice [m].
inline double LatticeRange(const Eigen::Vector2d& p, double angle) {
  double t = std::numeric_limits<double>::infinity();
  auto along = [&t](double from, double d) {
    if (std::abs(d) < 1e-9) {
      return;
    }
    const double u = (from - kLatticeWallOffset) / kLatticeSpacing;
    const double k = d > 0 ? std::floor(u) + 1.0 : std::ceil(u) - 1.0;
    t = std::min(t, (k * kLatticeSpacing + kLatticeWallOffset - from) / d);
  };
  along(p.x(), std::cos(angle));
  along(p.y(), std::sin(angle));
  return t;
}

/// A 180-beam scan all around from `pose` (laser at the base origin): the lattice's walls, a
/// fraction `clutter` of the beams at random ranges in [0.3, 7] m and 5 % without a return
/// (range_max 20 m, as walls beyond 19 m).
inline ScanPoints LatticeScan(const Pose2& pose, std::mt19937& rng, double clutter = 0.15) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi;
  scan.angle_increment = 2.0 * std::numbers::pi / 180;
  scan.range_min = 0.05;
  scan.range_max = 20.0;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<float> clutter_range(0.3F, 7.0F);
  for (std::size_t k = 0; k < 180; ++k) {
    const double u = unit(rng);
    float range = 20.0F;  // no return
    if (u < clutter) {
      range = clutter_range(rng);
    } else if (u >= clutter + 0.05) {
      const double r = LatticeRange(pose.translation(), pose.theta() + scan.Angle(k));
      range = r < 19.0 ? static_cast<float>(r) : 20.0F;
    }
    scan.ranges.push_back(range);
  }
  return ExtractScanPoints(scan, Pose2(), 30.0);
}

}  // namespace gridslam::internal
