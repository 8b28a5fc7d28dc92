#include "gridslam/scan_matching/degeneracy.hpp"

#include <Eigen/Eigenvalues>

namespace gridslam::scan_matching {

DegeneracyResult RemoveDegenerateDirections(double point_variance, double min_points,
                                            Eigen::Matrix3d* H, Eigen::Vector3d* g) {
  const Eigen::Matrix3d information = *H;
  return RemoveDegenerateDirections(point_variance, min_points, information, H, g);
}

DegeneracyResult RemoveDegenerateDirections(double point_variance, double min_points,
                                            const Eigen::Matrix3d& information, Eigen::Matrix3d* H,
                                            Eigen::Vector3d* g) {
  DegeneracyResult result;
  // Translation information once the yaw is free (Schur complement); without yaw information
  // (no lever arm at all) the translation block itself.
  Eigen::Matrix2d translation = information.topLeftCorner<2, 2>();
  const double yaw = information(2, 2);
  if (yaw > 0.0) {
    const Eigen::Vector2d coupling = information.topRightCorner<2, 1>();
    translation -= coupling * coupling.transpose() / yaw;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(
      0.5 * (translation + translation.transpose()));
  if (eigen.info() != Eigen::Success) {
    return result;
  }
  const Eigen::Vector2d points = eigen.eigenvalues().cwiseMax(0.0) * point_variance;  // ascending
  result.weakest_points = points(0);
  result.strongest_points = points(1);
  result.weakest_direction = eigen.eigenvectors().col(0).normalized();
  if (min_points <= 0.0) {
    return result;
  }
  Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 2; ++i) {
    if (points(i) < min_points) {
      Eigen::Vector3d v = Eigen::Vector3d::Zero();
      v.head<2>() = eigen.eigenvectors().col(i).normalized();
      Q -= v * v.transpose();
      ++result.degenerate_directions;
    }
  }
  if (result.degenerate_directions > 0) {
    *H = Q * (*H) * Q;
    *g = Q * (*g);
  }
  return result;
}

}  // namespace gridslam::scan_matching
