// Closed-form least-squares rigid fit in 2D and its information matrix (docs/design.md §1.5;
// docs/method.md §1.5.3, which fixes the authors' code: the LS transform is the measurement,
// and the information comes from the LS normal matrix). The fit is Umeyama/Kabsch without scale
// (Umeyama 1991, Eqs. (34)–(42) with c = 1): in 2D the optimal rotation is
// theta = atan2(sum cross(b_k', a_k'), sum dot(b_k', a_k')) over centred points, and the
// translation t = mean(a) - R(theta) mean(b). Convention: p_a = T_a_b * p_b.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"

namespace gridslam::matching {

/// Matched point pairs: a[k] in frame a corresponds to b[k] in frame b [m]. `rotation`
/// optionally holds the rotation implied by the keypoint orientations of pair k
/// (angle_a - angle_b [rad]); empty if unknown.
struct Correspondences {
  std::vector<Eigen::Vector2d> a;
  std::vector<Eigen::Vector2d> b;
  std::vector<double> rotation;
  [[nodiscard]] int size() const { return static_cast<int>(a.size()); }
};

struct InformationOptions {
  /// Lower bound of the keypoint position noise used in the information matrix, so that a fit
  /// with tiny residuals (few inliers, or quantized positions) is not over-confident [m].
  double min_position_sigma = 0.03;
  /// Factor applied to sum(J^T J) / sigma^2: keypoints of one key map are not independent
  /// measurements (their errors are correlated through the map), so the textbook information
  /// overstates the certainty; 0.1 makes the standard deviations ~3x larger [-].
  double information_scale = 0.1;

  template <class V>
  void Visit(V& v) {
    v("min_position_sigma", min_position_sigma,
      "Floor of the keypoint position noise in the information matrix [m]");
    v("information_scale", information_scale,
      "Scale of the least-squares information (correlated keypoint errors) [-]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(min_position_sigma > 0.0, "matching.information.min_position_sigma > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(information_scale > 0.0, "matching.information.information_scale > 0"));
    return Status::Ok();
  }
};

/// Least-squares rigid transform T_a_b minimizing sum |a_k - T_a_b * b_k|^2 over `indices`.
/// Contract: at least one index; with one index (or all b coincident) the rotation is 0.
Pose2 FitRigid2D(const Correspondences& c, std::span<const int> indices);

/// Root-mean-square residual |a_k - T_a_b * b_k| over `indices` [m]; 0 if empty.
double RmsResidual(const Correspondences& c, std::span<const int> indices, const Pose2& T_a_b);

/// Standard deviations of the b points of `indices` along their principal axes, (minor, major)
/// [m]: a minor value near 0 means the points are collinear or coincident.
Eigen::Vector2d PrincipalSpread(const Correspondences& c, std::span<const int> indices);

/// Information matrix of T_a_b in (x, y, theta) order, in the tangent space of the measurement
/// (right perturbation T_a_b * Exp(delta), the g2o EDGE_SE2 / pose-graph convention):
/// information_scale * sum_k J_k^T J_k / sigma^2 with J_k = d(T * Exp(delta) * b_k)/d(delta) at 0,
/// and sigma^2 = max(sum |r_k|^2 / (2n - 3), min_position_sigma^2). It grows with the number of
/// inliers and with their spread around the origin of frame b.
/// Contract: at least 2 indices.
Eigen::Matrix3d FitInformation(const Correspondences& c, std::span<const int> indices,
                               const Pose2& T_a_b, const InformationOptions& options);

}  // namespace gridslam::matching
