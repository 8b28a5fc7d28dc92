#include "gridslam/geometry/pose2.hpp"

#include <random>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

Pose2 RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> xy(-10.0, 10.0);
  std::uniform_real_distribution<double> th(-4.0, 4.0);
  return {xy(rng), xy(rng), th(rng)};
}

TEST(Pose2, ComposeMatchesHomogeneousMatrices) {
  std::mt19937 rng(42);
  for (int i = 0; i < 10000; ++i) {
    const Pose2 a = RandomPose(rng);
    const Pose2 b = RandomPose(rng);
    const Eigen::Matrix3d m = a.Matrix() * b.Matrix();
    EXPECT_TRUE((m - (a * b).Matrix()).norm() < 1e-9);
  }
}

TEST(Pose2, InverseAndAssociativity) {
  std::mt19937 rng(7);
  for (int i = 0; i < 10000; ++i) {
    const Pose2 a = RandomPose(rng);
    const Pose2 b = RandomPose(rng);
    const Pose2 c = RandomPose(rng);
    EXPECT_TRUE(IsApprox(a * a.Inverse(), Pose2::Identity(), 1e-9, 1e-12));
    EXPECT_TRUE(IsApprox((a * b) * c, a * (b * c), 1e-9, 1e-12));
    EXPECT_TRUE(IsApprox(a * Between(a, b), b, 1e-9, 1e-12));
    const Eigen::Vector2d p(1.5, -2.0);
    EXPECT_TRUE(((a * b) * p - a * (b * p)).norm() < 1e-9);
  }
}

TEST(Pose2, ExpLogRoundTripIncludingSmallAngles) {
  std::mt19937 rng(3);
  for (int i = 0; i < 10000; ++i) {
    Pose2 a = RandomPose(rng);
    if (i % 3 == 0) {
      a = Pose2(a.x(), a.y(), 1e-9 * a.theta());
    }
    EXPECT_TRUE(IsApprox(Pose2::Exp(a.Log()), a, 1e-9, 1e-12));
  }
  EXPECT_TRUE(IsApprox(Pose2::Exp(Eigen::Vector3d(1.0, 0.0, 0.0)), Pose2(1.0, 0.0, 0.0)));
  // A quarter turn while moving pi/2 forward ends at (1, 1).
  const Pose2 quarter =
      Pose2::Exp(Eigen::Vector3d(std::numbers::pi / 2, 0.0, std::numbers::pi / 2));
  EXPECT_TRUE(IsApprox(quarter, Pose2(1.0, 1.0, std::numbers::pi / 2), 1e-12, 1e-12));
}

TEST(Pose2, InterpolatesAlongShortestArc) {
  const Pose2 a(0.0, 0.0, 3.0);
  const Pose2 b(2.0, 4.0, -3.0);
  const Pose2 mid = Interpolate(a, b, 0.5);
  EXPECT_NEAR(mid.x(), 1.0, 1e-12);
  EXPECT_NEAR(mid.y(), 2.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.theta()), std::numbers::pi, 1e-9);
}

TEST(Pose2, NormalizesTheta) {
  const Pose2 p(0.0, 0.0, 7.0);
  EXPECT_NEAR(p.theta(), 7.0 - 2.0 * std::numbers::pi, 1e-12);
}

}  // namespace
}  // namespace gridslam
