#include "gridslam/pose_graph/initialization.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "gridslam/common/angles.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/gauss_newton.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"

namespace gridslam::pose_graph {
namespace {

double MeanRotationError(const PoseGraph& graph, const std::vector<Pose2>& truth) {
  double sum = 0.0;
  for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
    sum += std::abs(NormalizeAngle(graph.vertex(v).T_map_v.theta() -
                                   truth[static_cast<std::size_t>(v)].theta()));
  }
  return sum / static_cast<double>(graph.num_vertices());
}

TEST(InitializationTest, ExactMeasurementsGiveTheTruth) {
  SyntheticGraphOptions options;
  options.num_vertices = 200;
  const SyntheticGraph synthetic = MakeSyntheticGraph(options);
  for (const Initialization method : {Initialization::kChordal, Initialization::kLago}) {
    PoseGraph graph = synthetic.graph;
    // Scramble the guess: the initialization must not depend on it (anchor aside).
    for (int v = 1; v < static_cast<int>(graph.num_vertices()); ++v) {
      graph.SetPose(v, Pose2(0.0, 0.0, 2.0));
    }
    ASSERT_TRUE(InitializeOrientationFirst(graph, method));
    for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
      EXPECT_TRUE(IsApprox(graph.vertex(v).T_map_v, synthetic.truth[static_cast<std::size_t>(v)],
                           1e-6, 1e-9));
    }
  }
}

TEST(InitializationTest, RecoversOrientationsUnderLargeOrientationNoise) {
  SyntheticGraphOptions options;
  options.num_vertices = 600;
  options.seed = 7;
  options.sigma_xy = 0.02;
  options.sigma_theta = 0.1;  // Per edge: the odometry chain drifts by radians.
  options.information = Eigen::Vector3d(2500.0, 2500.0, 100.0).asDiagonal();
  const SyntheticGraph synthetic = MakeSyntheticGraph(options);
  // The optimum, by Gauss-Newton from the truth.
  PoseGraph optimum = synthetic.graph;
  for (int v = 0; v < static_cast<int>(optimum.num_vertices()); ++v) {
    optimum.SetPose(v, synthetic.truth[static_cast<std::size_t>(v)]);
  }
  GaussNewtonSolver(optimum, EffectiveFixed(optimum), {}).Run(optimum, false);
  std::vector<Pose2> best;
  for (const Vertex& v : optimum.vertices()) {
    best.push_back(v.T_map_v);
  }
  const double chained = MeanRotationError(synthetic.graph, best);
  ASSERT_GT(chained, 0.5);  // The odometry guess is far off.
  for (const Initialization method : {Initialization::kChordal, Initialization::kLago}) {
    PoseGraph graph = synthetic.graph;
    ASSERT_TRUE(InitializeOrientationFirst(graph, method));
    EXPECT_LT(MeanRotationError(graph, best), 0.5 * chained) << static_cast<int>(method);
    GaussNewtonSolver(graph, EffectiveFixed(graph), {}).Run(graph, false);
    EXPECT_NEAR(Chi2(graph), Chi2(optimum), 1e-6 * Chi2(optimum)) << static_cast<int>(method);
  }
}

TEST(InitializationTest, Parse) {
  Initialization m = Initialization::kNone;
  EXPECT_TRUE(ParseInitialization("lago", &m));
  EXPECT_EQ(m, Initialization::kLago);
  EXPECT_TRUE(ParseInitialization("chordal", &m));
  EXPECT_EQ(m, Initialization::kChordal);
  EXPECT_FALSE(ParseInitialization("spectral", &m));
}

}  // namespace
}  // namespace gridslam::pose_graph
