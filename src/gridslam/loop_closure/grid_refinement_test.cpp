#include "gridslam/loop_closure/grid_refinement.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"

namespace gridslam::loop_closure {
namespace {

// An L-shaped room plus a pillar: walls as obstacle cells of a 10 m grid.
Grid2D<std::uint8_t> Room() {
  Grid2D<std::uint8_t> obstacles(MapLimits(0.05, Eigen::Vector2d(-5.0, -5.0), 200, 200), 0);
  for (int k = 20; k < 180; ++k) {
    obstacles(k, 20) = 1;
    obstacles(20, k) = 1;
    obstacles(k, 179) = 1;
    obstacles(179, k / 2 + 90) = 1;
  }
  for (int i = 100; i < 110; ++i) {
    for (int j = 60; j < 64; ++j) {
      obstacles(i, j) = 1;
    }
  }
  return obstacles;
}

TEST(GridRefinement, RecoversSmallOffsetToSubCellAccuracy) {
  const Grid2D<std::uint8_t> obstacles = Room();
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
  std::vector<Eigen::Vector2d> points_a;
  for (int j = 0; j < obstacles.Height(); ++j) {
    for (int i = 0; i < obstacles.Width(); ++i) {
      if (obstacles(i, j) != 0) {
        points_a.push_back(obstacles.Limits().CellCenter({i, j}));
      }
    }
  }
  // Points of "b" are a's obstacles seen from frame b: p_b = T_a_b^-1 p_a.
  const Pose2 T_a_b(0.7, -0.4, 0.3);
  std::vector<Eigen::Vector2d> points_b;
  for (const auto& p : points_a) {
    points_b.push_back(T_a_b.Inverse() * p);
  }
  const Pose2 start = Pose2(0.08, -0.06, 0.02) * T_a_b;
  RefinementOptions options;
  const RefinementResult result = RefineOnDistanceField(points_b, distance, start, options);
  ASSERT_TRUE(result.ok);
  EXPECT_LT((result.T_a_b.translation() - T_a_b.translation()).norm(), 0.01);
  EXPECT_LT(std::abs(NormalizeAngle(result.T_a_b.theta() - T_a_b.theta())), 0.002);
  EXPECT_GT(result.inlier_fraction, 0.9);
  EXPECT_LT(result.rms, 0.02);
}

TEST(GridRefinement, FailsWithoutOverlap) {
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(Room());
  const std::vector<Eigen::Vector2d> far = {{100.0, 100.0}, {101.0, 100.0}, {100.0, 101.0}};
  const RefinementResult result =
      RefineOnDistanceField(far, distance, Pose2::Identity(), RefinementOptions{});
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.points, 0);  // failed for want of usable points
}

TEST(GridRefinement, ReportsHowManyPointsItCouldUseWhenTooFew) {
  const Grid2D<std::uint8_t> obstacles = Room();
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
  // 30 points on the bottom wall (y = -4 m), 20 far away.
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 30; ++k) {
    points.push_back(obstacles.Limits().CellCenter({40 + 3 * k, 20}));
  }
  for (int k = 0; k < 20; ++k) {
    points.emplace_back(100.0 + k, 100.0);
  }
  RefinementOptions options;
  options.min_points = 40;
  const RefinementResult few = RefineOnDistanceField(points, distance, Pose2::Identity(), options);
  EXPECT_FALSE(few.ok);
  EXPECT_EQ(few.points, 30);
  options.min_points = 20;
  const RefinementResult enough =
      RefineOnDistanceField(points, distance, Pose2::Identity(), options);
  EXPECT_TRUE(enough.ok);
  EXPECT_EQ(enough.points, 30);
}

TEST(GridRefinement, OptionsNameThePointsToRefine) {
  RefinementOptions options;
  EXPECT_EQ(options.points, "scans");
  EXPECT_TRUE(options.Validate().ok());
  options.points = "key_map";
  EXPECT_TRUE(options.Validate().ok());
  options.points = "cells";
  EXPECT_FALSE(options.Validate().ok());
  options.points = "scans";
  options.window_travel = -1.0;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace gridslam::loop_closure
