#include "gridslam/grid/ray_casting.hpp"

#include <algorithm>

namespace gridslam {

std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> ClipSegment(const MapLimits& limits,
                                                                       const Eigen::Vector2d& a,
                                                                       const Eigen::Vector2d& b) {
  // Liang-Barsky: keep the parameter interval [t0, t1] of a + t (b - a) inside every slab.
  const double margin = 1e-6 * limits.Resolution();
  const Eigen::Vector2d lo = limits.Origin() + Eigen::Vector2d::Constant(margin);
  const Eigen::Vector2d hi =
      limits.Origin() + Eigen::Vector2d(limits.Width(), limits.Height()) * limits.Resolution() -
      Eigen::Vector2d::Constant(margin);
  if (limits.Width() == 0 || limits.Height() == 0) {
    return std::nullopt;
  }
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0;
  double t1 = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (a[axis] < lo[axis] || a[axis] > hi[axis]) {
        return std::nullopt;
      }
      continue;
    }
    double ta = (lo[axis] - a[axis]) / d[axis];
    double tb = (hi[axis] - a[axis]) / d[axis];
    if (ta > tb) {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) {
      return std::nullopt;
    }
  }
  return std::make_pair(Eigen::Vector2d(a + t0 * d), Eigen::Vector2d(a + t1 * d));
}

}  // namespace gridslam
