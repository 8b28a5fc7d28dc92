#include "gridslam/pose_graph/edge_error.hpp"

#include <random>

#include <gtest/gtest.h>

namespace gridslam::pose_graph {
namespace {

Eigen::Vector3d RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> position(-10.0, 10.0);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  return {position(rng), position(rng), angle(rng)};
}

TEST(EdgeErrorTest, MatchesTheRelativePoseDefinition) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector3d xi = RandomPose(rng);
    const Eigen::Vector3d xj = RandomPose(rng);
    const Eigen::Vector3d z = RandomPose(rng);
    // e = (x, y, theta) of Z^-1 X_i^-1 X_j (g2o EdgeSE2::computeError).
    const Pose2 expected =
        Pose2::FromVector(z).Inverse() * Pose2::FromVector(xi).Inverse() * Pose2::FromVector(xj);
    const Eigen::Vector3d e = EdgeError(xi, xj, z);
    EXPECT_NEAR(e.x(), expected.x(), 1e-9);
    EXPECT_NEAR(e.y(), expected.y(), 1e-9);
    EXPECT_NEAR(std::abs(NormalizeAngle(e.z() - expected.theta())), 0.0, 1e-9);
    EXPECT_GE(e.z(), -std::numbers::pi);
    EXPECT_LT(e.z(), std::numbers::pi);
  }
}

TEST(EdgeErrorTest, AnalyticJacobiansMatchNumericOnes) {
  std::mt19937 rng(11);
  constexpr double kStep = 1e-6;
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector3d xi = RandomPose(rng);
    const Eigen::Vector3d xj = RandomPose(rng);
    Eigen::Vector3d z = RandomPose(rng);
    // Keep the angular error away from the wrap-around, where it is not differentiable.
    z.z() = NormalizeAngle(xj.z() - xi.z() - 0.3);
    Eigen::Matrix3d J_i;
    Eigen::Matrix3d J_j;
    EdgeError(xi, xj, z, &J_i, &J_j);
    for (int d = 0; d < 3; ++d) {
      const Eigen::Vector3d h = kStep * Eigen::Vector3d::Unit(d);
      const Eigen::Vector3d numeric_i =
          (EdgeError(xi + h, xj, z) - EdgeError(xi - h, xj, z)) / (2.0 * kStep);
      const Eigen::Vector3d numeric_j =
          (EdgeError(xi, xj + h, z) - EdgeError(xi, xj - h, z)) / (2.0 * kStep);
      EXPECT_LT((J_i.col(d) - numeric_i).norm(), 1e-6) << "trial " << trial << " dim " << d;
      EXPECT_LT((J_j.col(d) - numeric_j).norm(), 1e-6) << "trial " << trial << " dim " << d;
    }
  }
}

TEST(EdgeErrorTest, Chi2IsTheWeightedSumOfSquaredErrors) {
  PoseGraph graph;
  graph.AddVertex(0, Pose2(0.0, 0.0, 0.0));
  graph.AddVertex(1, Pose2(1.0, 0.5, 0.2));
  Eigen::Matrix3d information;
  information << 4.0, 1.0, 0.5, 1.0, 9.0, 0.0, 0.5, 0.0, 16.0;
  graph.AddEdge(0, 1, Pose2(1.0, 0.0, 0.0), information);
  graph.AddEdge(1, 0, Between(graph.vertex(1).T_map_v, graph.vertex(0).T_map_v),
                information);  // Exact: no error.
  const Eigen::Vector3d e = EdgeError(graph, 0);
  EXPECT_NEAR(e.x(), 0.0, 1e-12);
  EXPECT_NEAR(e.y(), 0.5, 1e-12);
  EXPECT_NEAR(e.z(), 0.2, 1e-12);
  EXPECT_NEAR(EdgeChi2(graph, 1), 0.0, 1e-20);
  EXPECT_NEAR(Chi2(graph), e.dot(information * e), 1e-12);
}

}  // namespace
}  // namespace gridslam::pose_graph
