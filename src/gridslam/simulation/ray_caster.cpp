#include "gridslam/simulation/ray_caster.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace gridslam::simulation {

RayHit RayCaster::Cast(const Eigen::Vector2d& origin, double angle, double max_range) const {
  const MapLimits& limits = world_.walls.Limits();
  const double res = limits.Resolution();
  const double dx = std::cos(angle);
  const double dy = std::sin(angle);
  // Everything below is in cell units: g = (p - origin) / res, t = distance / res.
  const double gx0 = (origin.x() - limits.Origin().x()) / res;
  const double gy0 = (origin.y() - limits.Origin().y()) / res;
  const double t_max = max_range / res;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double inv_dx = dx != 0.0 ? 1.0 / std::abs(dx) : kInf;
  const double inv_dy = dy != 0.0 ? 1.0 / std::abs(dy) : kInf;
  const int step_x = dx > 0.0 ? 1 : -1;
  const int step_y = dy > 0.0 ? 1 : -1;
  // A cell whose centre is d cells from the nearest wall centre has no wall within
  // d - sqrt(2) cells of any of its points.
  const double skip_margin = std::numbers::sqrt2;
  const float min_skip_clearance = static_cast<float>((skip_margin + 2.0) * res);

  double t = 0.0;
  int ix = 0;
  int iy = 0;
  double next_x = 0.0;  // t at the next vertical cell boundary
  double next_y = 0.0;  // t at the next horizontal cell boundary
  auto start_at = [&](double t_start) {
    const double gx = gx0 + t_start * dx;
    const double gy = gy0 + t_start * dy;
    ix = static_cast<int>(std::floor(gx));
    iy = static_cast<int>(std::floor(gy));
    next_x = t_start + (dx > 0.0 ? (ix + 1 - gx) : (gx - ix)) * inv_dx;
    next_y = t_start + (dy > 0.0 ? (iy + 1 - gy) : (gy - iy)) * inv_dy;
    if (dx == 0.0) {
      next_x = kInf;
    }
    if (dy == 0.0) {
      next_y = kInf;
    }
    t = t_start;
  };
  start_at(0.0);
  const int width = limits.Width();
  const int height = limits.Height();
  while (t <= t_max) {
    if (ix < 0 || iy < 0 || ix >= width || iy >= height || world_.walls(ix, iy) != 0) {
      return {true, t * res};
    }
    if (use_clearance_) {
      const float clearance = world_.clearance(ix, iy);
      if (clearance > min_skip_clearance) {
        start_at(t + static_cast<double>(clearance) / res - skip_margin);
        continue;
      }
    }
    if (next_x < next_y) {
      t = next_x;
      next_x += inv_dx;
      ix += step_x;
    } else {
      t = next_y;
      next_y += inv_dy;
      iy += step_y;
    }
  }
  return {false, max_range};
}

bool RayCaster::LineOfSight(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const Eigen::Vector2d d = b - a;
  const double length = d.norm();
  if (world_.IsWall(a) || world_.IsWall(b)) {
    return false;
  }
  if (length == 0.0) {
    return true;
  }
  return !Cast(a, std::atan2(d.y(), d.x()), length).hit;
}

}  // namespace gridslam::simulation
