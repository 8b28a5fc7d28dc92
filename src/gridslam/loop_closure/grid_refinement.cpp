#include "gridslam/loop_closure/grid_refinement.hpp"

#include <cmath>

#include <Eigen/Cholesky>

namespace gridslam::loop_closure {

Status RefinementOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(max_iterations >= 1, "refinement.max_iterations >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(huber > 0.0, "refinement.huber > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_distance > 0.0, "refinement.max_distance > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_points >= 1, "refinement.max_points >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(min_points >= 3, "refinement.min_points >= 3"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_step > 0.0, "refinement.max_step > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(window_travel >= 0.0, "refinement.window_travel >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(points == "key_map" || points == "scans", "refinement.points is key_map or scans"));
  return Status::Ok();
}

namespace {

// Bilinear interpolation of the distance field at p (metres) with its gradient. False when any of
// the four cells is unknown or outside the grid.
bool Interpolate(const Grid2D<float>& field, const Eigen::Vector2d& p, double* value,
                 Eigen::Vector2d* gradient) {
  const MapLimits& limits = field.Limits();
  const Eigen::Vector2d c = limits.ToCellCoordinates(p);
  // floor(c) within [0, width - 2] x [0, height - 2], tested on c itself (floor(x) >= 0 iff
  // x >= 0, floor(x) < n iff x < n for an integer n; NaN fails): on the grid, truncation is
  // floor, without floor's work for negative numbers.
  if (!(c.x() >= 0.0 && c.y() >= 0.0 && c.x() < limits.Width() - 1 &&
        c.y() < limits.Height() - 1)) {
    return false;
  }
  const int i = static_cast<int>(c.x());
  const int j = static_cast<int>(c.y());
  const float* row = field.data() +
                     static_cast<std::size_t>(j) * static_cast<std::size_t>(limits.Width()) +
                     static_cast<std::size_t>(i);
  const float* next_row = row + limits.Width();
  const double v00 = row[0];
  const double v10 = row[1];
  const double v01 = next_row[0];
  const double v11 = next_row[1];
  if (v00 < 0.0 || v10 < 0.0 || v01 < 0.0 || v11 < 0.0) {
    return false;
  }
  const double fx = c.x() - i;
  const double fy = c.y() - j;
  *value = (1 - fx) * (1 - fy) * v00 + fx * (1 - fy) * v10 + (1 - fx) * fy * v01 + fx * fy * v11;
  const double dx = (1 - fy) * (v10 - v00) + fy * (v11 - v01);
  const double dy = (1 - fx) * (v01 - v00) + fx * (v11 - v10);
  *gradient = Eigen::Vector2d(dx, dy) / limits.Resolution();
  return true;
}

struct System {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double cost = 0.0;
  double sum_sq = 0.0;
  int used = 0;
  int inliers = 0;
};

System Linearize(std::span<const Eigen::Vector2d> points, int stride, const Grid2D<float>& field,
                 const Pose2& T, const RefinementOptions& options) {
  // The sums in locals, not in the returned System: they stay in registers instead of being
  // stored and reloaded around every point (the points might alias the System).
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double cost = 0.0;
  double sum_sq = 0.0;
  int used = 0;
  int inliers = 0;
  const double huber = options.huber;
  const double max_distance = options.max_distance;
  const PointTransform transform(T);
  for (std::size_t k = 0; k < points.size(); k += static_cast<std::size_t>(stride)) {
    const Eigen::Vector2d q = transform(points[k]);
    double d = 0.0;
    Eigen::Vector2d grad;
    if (!Interpolate(field, q, &d, &grad) || d > max_distance) {
      continue;
    }
    // Left perturbation q' = R(dtheta) q + dt: dq'/d(dx, dy, dtheta) = [I, (-q_y, q_x)].
    const Eigen::Vector2d dq_dtheta(-q.y(), q.x());
    const Eigen::Vector3d J(grad.x(), grad.y(), grad.dot(dq_dtheta));
    const double w = d <= huber ? 1.0 : huber / d;
    H += w * J * J.transpose();
    g += w * J * d;
    cost += d <= huber ? d * d : huber * (2.0 * d - huber);
    sum_sq += d * d;
    ++used;
    inliers += d <= huber ? 1 : 0;
  }
  System s;
  s.H = H;
  s.g = g;
  s.cost = cost;
  s.sum_sq = sum_sq;
  s.used = used;
  s.inliers = inliers;
  return s;
}

}  // namespace

RefinementResult RefineOnDistanceField(std::span<const Eigen::Vector2d> points_b,
                                       const Grid2D<float>& distance_a, const Pose2& T_a_b,
                                       const RefinementOptions& options) {
  RefinementResult result;
  result.T_a_b = T_a_b;
  const int stride =
      std::max<int>(1, static_cast<int>(points_b.size()) / std::max(1, options.max_points));
  Pose2 T = T_a_b;
  System s = Linearize(points_b, stride, distance_a, T, options);
  for (int it = 0; it < options.max_iterations; ++it) {
    if (s.used < options.min_points) {
      result.points = s.used;
      return result;
    }
    Eigen::Matrix3d H = s.H;
    H.diagonal() += Eigen::Vector3d::Constant(1e-6 * (H.trace() + 1e-9));
    const Eigen::Vector3d delta = -H.ldlt().solve(s.g);
    // Left update: T <- exp(delta) applied in a's frame (delta = (dx, dy, dtheta) about a's
    // origin).
    const Pose2 step(delta.x(), delta.y(), delta.z());
    Pose2 candidate = step * T;
    System next = Linearize(points_b, stride, distance_a, candidate, options);
    ++result.iterations;
    if (next.used < options.min_points ||
        next.cost / std::max(1, next.used) > s.cost / std::max(1, s.used) + 1e-12) {
      break;
    }
    T = candidate;
    s = next;
    if (delta.head<2>().norm() < 1e-5 && std::abs(delta.z()) < 1e-6) {
      break;
    }
  }
  if (s.used < options.min_points ||
      (T.translation() - T_a_b.translation()).norm() > options.max_step) {
    result.points = s.used;
    return result;
  }
  result.ok = true;
  result.T_a_b = T;
  result.points = s.used;
  result.rms = std::sqrt(s.sum_sq / s.used);
  result.inlier_fraction = static_cast<double>(s.inliers) / s.used;
  result.hessian = s.H / s.used;
  return result;
}

}  // namespace gridslam::loop_closure
