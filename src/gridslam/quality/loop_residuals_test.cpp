#include "gridslam/quality/loop_residuals.hpp"

#include <numbers>

#include <gtest/gtest.h>

namespace gridslam::quality {
namespace {

TEST(LoopResiduals, ZeroWhenTheGraphExplainsTheClosures) {
  pose_graph::PoseGraph graph;
  graph.AddVertex(0, Pose2(0, 0, 0));
  graph.AddVertex(5, Pose2(2, 1, 0.5));
  graph.AddVertex(9, Pose2(-1, 3, -1.0));
  const std::vector<LoopMeasurement> loops = {
      {0, 5, Pose2(0, 0, 0).Inverse() * Pose2(2, 1, 0.5)},
      {5, 9, Pose2(2, 1, 0.5).Inverse() * Pose2(-1, 3, -1.0)}};
  const LoopResidualStats s = LoopResiduals(graph, loops);
  EXPECT_EQ(s.closures, 2);
  EXPECT_NEAR(s.max_translation, 0.0, 1e-12);
  EXPECT_NEAR(s.max_rotation, 0.0, 1e-12);
}

TEST(LoopResiduals, MeasuresTheDisagreement) {
  pose_graph::PoseGraph graph;
  graph.AddVertex(0, Pose2(0, 0, 0));
  graph.AddVertex(1, Pose2(1, 0, 0));
  graph.AddVertex(2, Pose2(0, 2, 0));
  // Closure 0-1 claims 1.3 m (graph: 1 m); closure 0-2 claims a 0.1 rad turn (graph: none);
  // closure 1-7 names a missing vertex.
  const std::vector<LoopMeasurement> loops = {
      {0, 1, Pose2(1.3, 0, 0)}, {0, 2, Pose2(0, 2, 0.1)}, {1, 7, Pose2()}};
  const LoopResidualStats s = LoopResiduals(graph, loops);
  EXPECT_EQ(s.closures, 2);
  EXPECT_NEAR(s.max_translation, 0.3, 1e-9);
  EXPECT_NEAR(s.max_rotation, 0.1, 1e-9);
  // Median of two values is their mean: translations 0.3 and 0, rotations 0 and 0.1.
  EXPECT_NEAR(s.median_translation, 0.15, 1e-9);
  EXPECT_NEAR(s.median_rotation, 0.05, 1e-9);
}

}  // namespace
}  // namespace gridslam::quality
