#include "gridslam/pose_graph/outliers.hpp"

#include <gtest/gtest.h>

#include "gridslam/pose_graph/synthetic_graph.hpp"

namespace gridslam::pose_graph {
namespace {

PoseGraph Base() {
  SyntheticGraphOptions options;
  options.num_vertices = 120;
  return MakeSyntheticGraph(options).graph;
}

TEST(OutliersTest, AddsTheRequestedWrongLoopClosures) {
  for (const OutlierKind kind : {OutlierKind::kRandom, OutlierKind::kLocal, OutlierKind::kGroup}) {
    PoseGraph graph = Base();
    const std::size_t before = graph.num_edges();
    OutlierOptions options;
    options.count = 25;
    options.kind = kind;
    const std::vector<int> added = AddOutliers(graph, options);
    ASSERT_EQ(added.size(), 25u);
    EXPECT_EQ(graph.num_edges(), before + 25);
    for (const int k : added) {
      const Edge& e = graph.edge(k);
      EXPECT_TRUE(IsLoopClosure(e));
      EXPECT_EQ(e.information, graph.edge(0).information);  // The odometry's information.
      if (kind == OutlierKind::kLocal) {
        EXPECT_LE(std::abs(e.to - e.from), options.local_window);
      }
    }
    if (kind == OutlierKind::kGroup) {
      // The edges of a group share one measurement (they agree with each other).
      int same = 0;
      for (std::size_t k = 1; k < added.size(); ++k) {
        same += IsApprox(graph.edge(added[k - 1]).T_i_j, graph.edge(added[k]).T_i_j, 0.0, 0.0);
      }
      EXPECT_GE(same, 15);
    }
  }
}

TEST(OutliersTest, DeterministicForASeed) {
  PoseGraph a = Base();
  PoseGraph b = Base();
  PoseGraph c = Base();
  OutlierOptions options;
  AddOutliers(a, options);
  AddOutliers(b, options);
  options.seed = 2;
  AddOutliers(c, options);
  const int last = static_cast<int>(a.num_edges()) - 1;
  EXPECT_EQ(a.edge(last).from, b.edge(last).from);
  EXPECT_TRUE(IsApprox(a.edge(last).T_i_j, b.edge(last).T_i_j, 0.0, 0.0));
  EXPECT_FALSE(IsApprox(a.edge(last).T_i_j, c.edge(last).T_i_j, 1e-9, 1e-9));
}

TEST(OutliersTest, ComparePoses) {
  PoseGraph a = Base();
  PoseGraph b = a;
  EXPECT_DOUBLE_EQ(ComparePoses(a, b).mean_translation, 0.0);
  b.SetPose(3, b.vertex(3).T_map_v * Pose2(1.2, 0.0, 0.0));
  const PoseErrors errors = ComparePoses(b, a);
  EXPECT_NEAR(errors.max_translation, 1.2, 1e-12);
  EXPECT_NEAR(errors.mean_translation, 1.2 / static_cast<double>(a.num_vertices()), 1e-12);
}

TEST(EdgeRoleTest, AutoMeansNonConsecutiveIds) {
  Edge e;
  e.from = 4;
  e.to = 5;
  EXPECT_FALSE(IsLoopClosure(e));
  e.to = 3;
  EXPECT_FALSE(IsLoopClosure(e));
  e.to = 9;
  EXPECT_TRUE(IsLoopClosure(e));
  e.role = EdgeRole::kOdometry;
  EXPECT_FALSE(IsLoopClosure(e));
  e.to = 5;
  e.role = EdgeRole::kLoopClosure;
  EXPECT_TRUE(IsLoopClosure(e));
}

}  // namespace
}  // namespace gridslam::pose_graph
