#include "gridslam/matching/rigid_fit.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "gridslam/common/check.hpp"

namespace gridslam::matching {
namespace {

const Eigen::Vector2d& At(const std::vector<Eigen::Vector2d>& v, int k) {
  return v[static_cast<std::size_t>(k)];
}

}  // namespace

Pose2 FitRigid2D(const Correspondences& c, std::span<const int> indices) {
  GRIDSLAM_CHECK(!indices.empty()) << "FitRigid2D needs at least one correspondence";
  Eigen::Vector2d mean_a = Eigen::Vector2d::Zero();
  Eigen::Vector2d mean_b = Eigen::Vector2d::Zero();
  for (const int k : indices) {
    mean_a += At(c.a, k);
    mean_b += At(c.b, k);
  }
  const double n = static_cast<double>(indices.size());
  mean_a /= n;
  mean_b /= n;
  // Umeyama without scale in 2D: the rotation maximizing sum a'·R b' (centred points).
  double sum_dot = 0.0;
  double sum_cross = 0.0;
  for (const int k : indices) {
    const Eigen::Vector2d pa = At(c.a, k) - mean_a;
    const Eigen::Vector2d pb = At(c.b, k) - mean_b;
    sum_dot += pb.dot(pa);
    sum_cross += pb.x() * pa.y() - pb.y() * pa.x();
  }
  const double theta = (sum_dot == 0.0 && sum_cross == 0.0) ? 0.0 : std::atan2(sum_cross, sum_dot);
  const Pose2 rotation(0.0, 0.0, theta);
  return {mean_a - rotation * mean_b, theta};
}

double RmsResidual(const Correspondences& c, std::span<const int> indices, const Pose2& T_a_b) {
  if (indices.empty()) {
    return 0.0;
  }
  double sum = 0.0;
  for (const int k : indices) {
    sum += (At(c.a, k) - T_a_b * At(c.b, k)).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(indices.size()));
}

Eigen::Vector2d PrincipalSpread(const Correspondences& c, std::span<const int> indices) {
  if (indices.size() < 2) {
    return Eigen::Vector2d::Zero();
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const int k : indices) {
    mean += At(c.b, k);
  }
  mean /= static_cast<double>(indices.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const int k : indices) {
    const Eigen::Vector2d d = At(c.b, k) - mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(indices.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(cov, Eigen::EigenvaluesOnly);
  const Eigen::Vector2d ev = solver.eigenvalues().cwiseMax(0.0);  // ascending
  return ev.cwiseSqrt();
}

Eigen::Matrix3d FitInformation(const Correspondences& c, std::span<const int> indices,
                               const Pose2& T_a_b, const InformationOptions& options) {
  GRIDSLAM_CHECK(indices.size() >= 2) << "FitInformation needs at least two correspondences";
  // Residual r_k = T * Exp(delta) * b_k - a_k; at delta = 0, J_k = R [I, perp(b_k)] with
  // perp(b) = (-b_y, b_x). R cancels in J^T J, so each pair adds
  // [[1, 0, -b_y], [0, 1, b_x], [-b_y, b_x, |b|^2]].
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  double sum_sq = 0.0;
  for (const int k : indices) {
    const Eigen::Vector2d& b = At(c.b, k);
    h(0, 0) += 1.0;
    h(1, 1) += 1.0;
    h(0, 2) -= b.y();
    h(1, 2) += b.x();
    h(2, 2) += b.squaredNorm();
    sum_sq += (At(c.a, k) - T_a_b * b).squaredNorm();
  }
  h(2, 0) = h(0, 2);
  h(2, 1) = h(1, 2);
  const double dof = std::max(2.0 * static_cast<double>(indices.size()) - 3.0, 1.0);
  const double sigma2 =
      std::max(sum_sq / dof, options.min_position_sigma * options.min_position_sigma);
  return options.information_scale / sigma2 * h;
}

}  // namespace gridslam::matching
