#include "gridslam/pose_graph/graph_utils.hpp"

#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"

namespace gridslam::pose_graph {
namespace {

const Eigen::Matrix3d kInfo = Eigen::Matrix3d::Identity();

TEST(GraphUtilsTest, ComponentsAndOneAnchorEach) {
  PoseGraph graph;
  for (const int id : {10, 3, 7, 5, 8}) {
    graph.AddVertex(id, Pose2());
  }
  graph.AddEdge(10, 3, Pose2(), kInfo);
  graph.AddEdge(7, 5, Pose2(), kInfo);
  // 8 is isolated.
  const Components components = ConnectedComponents(graph);
  EXPECT_EQ(components.count, 3);
  EXPECT_EQ(components.component[0], components.component[1]);
  EXPECT_EQ(components.component[2], components.component[3]);
  EXPECT_NE(components.component[0], components.component[2]);

  std::vector<bool> fixed = EffectiveFixed(graph);
  // Lowest id of each component: 3, 5 and 8.
  EXPECT_EQ(fixed, (std::vector<bool>{false, true, false, true, true}));

  graph.SetFixed(0, true);  // FIX 10: component {10, 3} is anchored by it alone.
  fixed = EffectiveFixed(graph);
  EXPECT_EQ(fixed, (std::vector<bool>{true, false, false, true, true}));
}

TEST(GraphUtilsTest, ChainingFollowsTheOdometryAndReproducesExactPoses) {
  SyntheticGraphOptions options;
  options.num_vertices = 60;
  const SyntheticGraph synthetic = MakeSyntheticGraph(options);
  ASSERT_GT(synthetic.loop_closures, 0);
  PoseGraph graph = synthetic.graph;
  for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
    graph.SetPose(v, Pose2(5.0, -3.0, 1.0));  // Forget the guess.
  }
  graph.SetPose(0, synthetic.truth[0]);
  const std::vector<int> tree = ChainingTree(graph, EffectiveFixed(graph));
  EXPECT_EQ(tree[0], -1);
  for (int v = 1; v < static_cast<int>(graph.num_vertices()); ++v) {
    const int e = tree[static_cast<std::size_t>(v)];
    ASSERT_GE(e, 0);
    const int other = graph.FromIndex(e) == v ? graph.ToIndex(e) : graph.FromIndex(e);
    EXPECT_EQ(other, v - 1) << "vertex " << v << " is not chained to its predecessor";
  }
  InitializeByChaining(graph);
  for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
    EXPECT_TRUE(
        IsApprox(graph.vertex(v).T_map_v, synthetic.truth[static_cast<std::size_t>(v)], 1e-9, 1e-9))
        << "vertex " << v;
  }
  EXPECT_NEAR(Chi2(graph), 0.0, 1e-12);
}

TEST(GraphUtilsTest, ChainingUsesReversedEdgesAndKeepsFixedVertices) {
  PoseGraph graph;
  graph.AddVertex(0, Pose2(1.0, 2.0, 0.5));
  graph.AddVertex(1, Pose2());
  graph.AddVertex(2, Pose2(9.0, 9.0, 0.0), /*fixed=*/true);
  graph.AddEdge(0, 1, Pose2(0.0, -1.0, 0.1), kInfo);  // Points to the parent: inverted.
  graph.AddEdge(2, 1, Pose2(3.0, 0.0, 0.0), kInfo);
  InitializeByChaining(graph);
  // The fixed vertex 2 is the root; 0 gets its pose through 1.
  EXPECT_TRUE(IsApprox(graph.vertex(2).T_map_v, Pose2(9.0, 9.0, 0.0)));
  EXPECT_TRUE(IsApprox(graph.vertex(1).T_map_v, Pose2(12.0, 9.0, 0.0)));
  EXPECT_NEAR(Chi2(graph), 0.0, 1e-20);
}

}  // namespace
}  // namespace gridslam::pose_graph
