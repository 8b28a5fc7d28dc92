// A tiny analytic 2D world of line segments and an exact laser simulator over it, for the scan
// matcher's tests and benchmarks (no files, no randomness unless a noise seed is given): a room
// with an L-shaped extension, pillars and slanted walls, so that every direction is constrained.
#pragma once

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::scan_matching::internal {

struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
};

/// Walls of a 10 m x 7 m room (corner near the origin) with a corridor, two pillars and a slanted
/// wall. The walls are moved off the 5 cm lattice by `offset` so that they do not lie exactly on
/// cell borders (where a wall fills two rows of cells).
inline std::vector<Segment> TestWorld(const Eigen::Vector2d& offset = {0.013, 0.021}) {
  std::vector<Segment> w;
  auto box = [&w](double x0, double y0, double x1, double y1) {
    w.push_back({{x0, y0}, {x1, y0}});
    w.push_back({{x1, y0}, {x1, y1}});
    w.push_back({{x1, y1}, {x0, y1}});
    w.push_back({{x0, y1}, {x0, y0}});
  };
  w.push_back({{0.0, 0.0}, {10.0, 0.0}});
  w.push_back({{10.0, 0.0}, {10.0, 3.0}});
  w.push_back({{10.0, 4.5}, {10.0, 7.0}});
  w.push_back({{10.0, 3.0}, {16.0, 3.0}});  // corridor to the east
  w.push_back({{10.0, 4.5}, {16.0, 4.5}});
  w.push_back({{16.0, 3.0}, {16.0, 4.5}});
  w.push_back({{10.0, 7.0}, {3.0, 7.0}});
  w.push_back({{3.0, 7.0}, {0.0, 5.0}});  // slanted
  w.push_back({{0.0, 5.0}, {0.0, 0.0}});
  box(3.0, 2.0, 3.6, 2.6);
  box(6.5, 4.2, 7.3, 4.6);
  w.push_back({{7.5, 0.0}, {8.2, 1.2}});  // a cabinet at an angle
  for (Segment& s : w) {
    s.a += offset;
    s.b += offset;
  }
  return w;
}

/// Range along the ray from `o` in direction `dir` to the nearest segment; +inf if none.
inline double CastRay(const std::vector<Segment>& world, const Eigen::Vector2d& o,
                      const Eigen::Vector2d& dir) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : world) {
    const Eigen::Vector2d e = s.b - s.a;
    const double denom = dir.x() * e.y() - dir.y() * e.x();
    if (std::abs(denom) < 1e-12) {
      continue;
    }
    const Eigen::Vector2d d = s.a - o;
    const double t = (d.x() * e.y() - d.y() * e.x()) / denom;
    const double u = (d.x() * dir.y() - d.y() * dir.x()) / denom;
    if (t > 1e-9 && u >= 0.0 && u <= 1.0) {
      best = std::min(best, t);
    }
  }
  return best;
}

/// A scan from the laser at `T_world_laser` with `beams` beams over 180 degrees (181/361 include
/// both ends), range_max `range_max` (no return beyond it: recorded as `no_return_value`), and
/// Gaussian range noise of `sigma` [m] drawn with `seed`.
inline LaserScan SimulateScan(const std::vector<Segment>& world, const Pose2& T_world_laser,
                              int beams = 181, double range_max = 30.0, double sigma = 0.0,
                              unsigned seed = 1, float no_return_value = 81.83F) {
  LaserScan scan;
  const bool both_ends = beams % 2 == 1;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / (both_ends ? beams - 1 : beams);
  scan.range_min = 0.02;
  scan.range_max = range_max;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  for (int k = 0; k < beams; ++k) {
    const double a = T_world_laser.theta() + scan.Angle(static_cast<std::size_t>(k));
    double r = CastRay(world, T_world_laser.translation(), {std::cos(a), std::sin(a)});
    if (sigma > 0.0) {
      r += noise(rng);
    }
    scan.ranges.push_back(r < range_max ? static_cast<float>(r) : no_return_value);
  }
  return scan;
}

}  // namespace gridslam::scan_matching::internal
