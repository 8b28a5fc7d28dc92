#include "gridslam/matching/rigid_fit.hpp"

#include <numeric>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <gtest/gtest.h>

namespace gridslam::matching {
namespace {

std::vector<int> All(int n) {
  std::vector<int> v(static_cast<std::size_t>(n));
  std::iota(v.begin(), v.end(), 0);
  return v;
}

// Points b spread over [-4, 4]^2 (plus `offset`) and a = T_a_b * b + noise.
Correspondences Make(const Pose2& T_a_b, int n, double noise, std::mt19937& rng,
                     const Eigen::Vector2d& offset = Eigen::Vector2d::Zero()) {
  std::uniform_real_distribution<double> pos(-4.0, 4.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Correspondences c;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d b = Eigen::Vector2d(pos(rng), pos(rng)) + offset;
    c.b.push_back(b);
    c.a.push_back(T_a_b * b + noise * Eigen::Vector2d(gauss(rng), gauss(rng)));
  }
  return c;
}

TEST(FitRigid2D, ExactOnNoiseFreeDataWithTheDocumentedConvention) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Pose2 T_a_b(u(rng), u(rng), u(rng));
    const Correspondences c = Make(T_a_b, 8, 0.0, rng);
    const Pose2 fit = FitRigid2D(c, All(8));
    EXPECT_TRUE(IsApprox(fit, T_a_b, 1e-9, 1e-9));
    for (int k = 0; k < 8; ++k) {  // p_a = T_a_b * p_b
      EXPECT_LT((fit * c.b[static_cast<std::size_t>(k)] - c.a[static_cast<std::size_t>(k)]).norm(),
                1e-9);
    }
    EXPECT_LT(RmsResidual(c, All(8), fit), 1e-9);
  }
}

TEST(FitRigid2D, SubsetAndSinglePoint) {
  std::mt19937 rng(2);
  const Pose2 T_a_b(1.0, 2.0, 0.5);
  Correspondences c = Make(T_a_b, 6, 0.0, rng);
  c.a[5] += Eigen::Vector2d(3.0, 0.0);  // an outlier outside the subset
  const std::vector<int> subset = {0, 1, 2, 3, 4};
  EXPECT_TRUE(IsApprox(FitRigid2D(c, subset), T_a_b, 1e-9, 1e-9));
  const std::vector<int> one = {0};
  const Pose2 single = FitRigid2D(c, one);
  EXPECT_EQ(single.theta(), 0.0);
  EXPECT_TRUE((single * c.b[0] - c.a[0]).norm() < 1e-12);
}

TEST(PrincipalSpread, DetectsCollinearAndCoincidentPoints) {
  Correspondences c;
  for (int k = 0; k < 5; ++k) {
    c.b.emplace_back(0.5 * k, 0.25 * k);
    c.a.emplace_back(0.0, 0.0);
  }
  const Eigen::Vector2d line = PrincipalSpread(c, All(5));
  EXPECT_NEAR(line.x(), 0.0, 1e-9);
  EXPECT_GT(line.y(), 0.5);
  c.b.assign(5, Eigen::Vector2d(1.0, 1.0));
  EXPECT_NEAR(PrincipalSpread(c, All(5)).y(), 0.0, 1e-9);
}

TEST(FitInformation, IsTheNormalMatrixOfTheRightPerturbation) {
  std::mt19937 rng(3);
  const Pose2 T_a_b(0.7, -1.2, 2.0);
  const Correspondences c = Make(T_a_b, 12, 0.0, rng, Eigen::Vector2d(3.0, 1.0));
  InformationOptions options;
  options.information_scale = 1.0;
  options.min_position_sigma = 0.1;
  const Eigen::Matrix3d info = FitInformation(c, All(12), T_a_b, options);
  // Numeric J of r_k(delta) = (T * Exp(delta)) * b_k - a_k.
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  const double eps = 1e-6;
  for (int k = 0; k < 12; ++k) {
    Eigen::Matrix<double, 2, 3> j;
    for (int d = 0; d < 3; ++d) {
      Eigen::Vector3d delta = Eigen::Vector3d::Zero();
      delta(d) = eps;
      const Eigen::Vector2d& b = c.b[static_cast<std::size_t>(k)];
      j.col(d) = ((T_a_b * Pose2::Exp(delta)) * b - (T_a_b * Pose2::Exp(-delta)) * b) / (2 * eps);
    }
    h += j.transpose() * j;
  }
  EXPECT_LT((info - h / (0.1 * 0.1)).norm(), 1e-5 * info.norm());
  EXPECT_TRUE(info.isApprox(info.transpose()));
}

TEST(FitInformation, InverseMatchesTheScatterOfNoisyFits) {
  // With information_scale = 1 and the true noise as sigma, the inverse information is the
  // covariance of Log(T_true^-1 * T_fit) (right perturbation) over noisy repetitions.
  std::mt19937 rng(4);
  const Pose2 T_a_b(2.0, 1.0, -0.8);
  const double sigma = 0.05;
  const int n = 15;
  InformationOptions options;
  options.information_scale = 1.0;
  options.min_position_sigma = sigma;
  const Correspondences layout = Make(T_a_b, n, 0.0, rng, Eigen::Vector2d(2.0, -1.0));
  const Eigen::Matrix3d predicted =
      FitInformation(layout, All(n), T_a_b, options).ldlt().solve(Eigen::Matrix3d::Identity());
  std::normal_distribution<double> gauss(0.0, sigma);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  const int trials = 4000;
  for (int t = 0; t < trials; ++t) {
    Correspondences c = layout;
    for (auto& a : c.a) {
      a += Eigen::Vector2d(gauss(rng), gauss(rng));
    }
    const Eigen::Vector3d e = (T_a_b.Inverse() * FitRigid2D(c, All(n))).Log();
    scatter += e * e.transpose();
  }
  scatter /= trials;
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(scatter(r, r), predicted(r, r), 0.1 * predicted(r, r)) << "row " << r;
  }
  // Off-diagonal terms (correlation of theta with x, y from the offset of the points).
  EXPECT_NEAR(scatter(0, 2), predicted(0, 2), 0.1 * std::sqrt(predicted(0, 0) * predicted(2, 2)));
  EXPECT_NEAR(scatter(1, 2), predicted(1, 2), 0.1 * std::sqrt(predicted(1, 1) * predicted(2, 2)));
}

TEST(FitInformation, GrowsWithInliersAndUsesTheSigmaFloor) {
  std::mt19937 rng(5);
  const Pose2 T_a_b(0.0, 0.0, 0.3);
  const Correspondences c = Make(T_a_b, 40, 0.0, rng);
  const InformationOptions options;
  const std::vector<int> few = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const Eigen::Matrix3d i10 = FitInformation(c, few, T_a_b, options);
  const Eigen::Matrix3d i40 = FitInformation(c, All(40), T_a_b, options);
  EXPECT_GT(i40.determinant(), i10.determinant());
  // Noise-free residuals: sigma is the floor, and the scale applies.
  EXPECT_NEAR(
      i10(0, 0),
      options.information_scale * 10.0 / (options.min_position_sigma * options.min_position_sigma),
      1e-9);
}

}  // namespace
}  // namespace gridslam::matching
