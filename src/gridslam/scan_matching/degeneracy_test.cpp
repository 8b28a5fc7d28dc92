#include "gridslam/scan_matching/degeneracy.hpp"

#include <gtest/gtest.h>

namespace gridslam::scan_matching {
namespace {

constexpr double kPointVariance = 0.03 * 0.03;

// Normal equations of points with unit gradients `normals` at positions `at` (weight 1).
void AddPoints(const std::vector<Eigen::Vector2d>& normals, const std::vector<Eigen::Vector2d>& at,
               double residual, Eigen::Matrix3d* H, Eigen::Vector3d* g) {
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const Eigen::Vector2d& n = normals[i];
    const Eigen::Vector3d J(n.x(), n.y(), -n.x() * at[i].y() + n.y() * at[i].x());
    *H += J * J.transpose() / kPointVariance;
    *g += residual * J / kPointVariance;
  }
}

TEST(Degeneracy, CorridorAxisIsRemoved) {
  // 100 points on two walls along x (normals along y), one point with a normal along x.
  std::vector<Eigen::Vector2d> normals;
  std::vector<Eigen::Vector2d> at;
  for (int i = 0; i < 100; ++i) {
    normals.emplace_back(0.0, i % 2 == 0 ? 1.0 : -1.0);
    at.emplace_back(-5.0 + 0.1 * i, i % 2 == 0 ? -1.0 : 1.0);
  }
  normals.emplace_back(1.0, 0.0);
  at.emplace_back(8.0, 0.5);
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  AddPoints(normals, at, 0.01, &H, &g);
  const DegeneracyResult result = RemoveDegenerateDirections(kPointVariance, 3.0, &H, &g);
  EXPECT_EQ(result.degenerate_directions, 1);
  EXPECT_NEAR(std::abs(result.weakest_direction.x()), 1.0, 1e-6);
  EXPECT_LT(result.weakest_points, 1.0 + 1e-9);
  EXPECT_NEAR(result.strongest_points, 100.0, 1.0);
  // Nothing of the scan is left along x: no information, no pull, no coupling.
  // (Up to the yaw coupling of the one point, which tilts the axis by 1e-5 rad.)
  const double scale = H(1, 1);
  EXPECT_NEAR(H(0, 0) / scale, 0.0, 1e-4);
  EXPECT_NEAR(H(0, 1) / scale, 0.0, 1e-4);
  EXPECT_NEAR(H(0, 2) / scale, 0.0, 1e-4);
  EXPECT_NEAR(g(0) / std::abs(g(1)), 0.0, 1e-4);
  EXPECT_GT(H(1, 1), 0.0);
  EXPECT_GT(H(2, 2), 0.0);
}

TEST(Degeneracy, ARoomKeepsEverything) {
  std::vector<Eigen::Vector2d> normals;
  std::vector<Eigen::Vector2d> at;
  for (int i = 0; i < 40; ++i) {
    const double a = 0.157 * i;
    normals.emplace_back(std::cos(a), std::sin(a));
    at.emplace_back(3.0 * std::cos(a), 2.0 * std::sin(a));
  }
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  AddPoints(normals, at, 0.01, &H, &g);
  const Eigen::Matrix3d H0 = H;
  const Eigen::Vector3d g0 = g;
  const DegeneracyResult result = RemoveDegenerateDirections(kPointVariance, 3.0, &H, &g);
  EXPECT_EQ(result.degenerate_directions, 0);
  EXPECT_GT(result.weakest_points, 3.0);
  EXPECT_EQ(H, H0);
  EXPECT_EQ(g, g0);
}

TEST(Degeneracy, NothingAtAllRemovesBothAndZeroDisables) {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  H(2, 2) = 10.0;
  Eigen::Vector3d g(1.0, 2.0, 3.0);
  Eigen::Matrix3d H1 = H;
  Eigen::Vector3d g1 = g;
  EXPECT_EQ(RemoveDegenerateDirections(kPointVariance, 3.0, &H1, &g1).degenerate_directions, 2);
  EXPECT_EQ(g1, Eigen::Vector3d(0.0, 0.0, 3.0));
  Eigen::Matrix3d H2 = H;
  Eigen::Vector3d g2 = g;
  EXPECT_EQ(RemoveDegenerateDirections(kPointVariance, 0.0, &H2, &g2).degenerate_directions, 0);
  EXPECT_EQ(g2, g);
}

}  // namespace
}  // namespace gridslam::scan_matching
