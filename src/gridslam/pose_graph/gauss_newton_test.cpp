#include "gridslam/pose_graph/gauss_newton.hpp"

#include <random>

#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"

namespace gridslam::pose_graph {
namespace {

// Perturbs every vertex except the first.
void Perturb(PoseGraph& graph, double sigma_xy, double sigma_theta, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int v = 1; v < static_cast<int>(graph.num_vertices()); ++v) {
    const Pose2& p = graph.vertex(v).T_map_v;
    graph.SetPose(v, Pose2(p.x() + sigma_xy * normal(rng), p.y() + sigma_xy * normal(rng),
                           p.theta() + sigma_theta * normal(rng)));
  }
}

std::vector<double> RunAndRecord(PoseGraph& graph, bool levenberg,
                                 const GaussNewtonOptions& options, LeastSquaresSummary* out) {
  GaussNewtonSolver solver(graph, EffectiveFixed(graph), options);
  std::vector<double> history{Chi2(graph)};
  *out = solver.Run(graph, levenberg, 0,
                    [&](const LeastSquaresIteration& it) { history.push_back(it.chi2); });
  return history;
}

TEST(GaussNewtonTest, ExactMeasurementsOptimizeToZeroError) {
  SyntheticGraphOptions options;
  options.num_vertices = 150;
  SyntheticGraph synthetic = MakeSyntheticGraph(options);
  PoseGraph& graph = synthetic.graph;
  Perturb(graph, 0.3, 0.1, 5);
  ASSERT_GT(Chi2(graph), 1.0);
  for (const bool levenberg : {false, true}) {
    PoseGraph copy = graph;
    LeastSquaresSummary summary;
    RunAndRecord(copy, levenberg, {}, &summary);
    EXPECT_TRUE(summary.converged);
    EXPECT_LT(summary.chi2_final, 1e-12);
    for (int v = 0; v < static_cast<int>(copy.num_vertices()); ++v) {
      EXPECT_TRUE(IsApprox(copy.vertex(v).T_map_v, synthetic.truth[static_cast<std::size_t>(v)],
                           1e-6, 1e-6));
    }
  }
}

TEST(GaussNewtonTest, NeverRaisesTheCost) {
  SyntheticGraphOptions options;
  options.num_vertices = 300;
  options.sigma_xy = 0.05;
  options.sigma_theta = 0.03;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    options.seed = seed;
    SyntheticGraph synthetic = MakeSyntheticGraph(options);
    Perturb(synthetic.graph, 2.0, 0.8, seed);  // Far from the basin.
    for (const bool levenberg : {false, true}) {
      PoseGraph copy = synthetic.graph;
      LeastSquaresSummary summary;
      const std::vector<double> history = RunAndRecord(copy, levenberg, {}, &summary);
      for (std::size_t k = 1; k < history.size(); ++k) {
        EXPECT_LE(history[k], history[k - 1] * (1.0 + 1e-12))
            << (levenberg ? "LM" : "GN") << " seed " << seed << " iteration " << k;
      }
      EXPECT_LE(summary.chi2_final, summary.chi2_initial);
      EXPECT_FALSE(summary.numerical_failure);
    }
  }
}

TEST(GaussNewtonTest, FixedVerticesStayAndComponentsAreAnchored) {
  SyntheticGraphOptions options;
  options.num_vertices = 40;
  options.sigma_xy = 0.02;
  SyntheticGraph a = MakeSyntheticGraph(options);
  options.first_id = 100;
  options.seed = 9;
  SyntheticGraph b = MakeSyntheticGraph(options);
  // Two components in one graph; the second has a user-fixed vertex in the middle.
  PoseGraph graph = a.graph;
  for (const auto& v : b.graph.vertices()) {
    graph.AddVertex(v.id, v.T_map_v, v.id == 120);
  }
  for (const auto& e : b.graph.edges()) {
    graph.AddEdge(e.from, e.to, e.T_i_j, e.information);
  }
  Perturb(graph, 0.1, 0.05, 3);
  const Pose2 first = graph.vertex(0).T_map_v;
  const Pose2 pinned = graph.vertex(graph.IndexOf(120)).T_map_v;
  GaussNewtonSolver solver(graph, EffectiveFixed(graph), {});
  const LeastSquaresSummary summary = solver.Run(graph, false);
  EXPECT_TRUE(summary.converged);
  EXPECT_LT(summary.chi2_final, summary.chi2_initial);
  EXPECT_TRUE(IsApprox(graph.vertex(0).T_map_v, first, 0.0, 0.0));
  EXPECT_TRUE(IsApprox(graph.vertex(graph.IndexOf(120)).T_map_v, pinned, 0.0, 0.0));
}

TEST(GaussNewtonTest, CauchyKernelResistsAWrongLoopClosure) {
  SyntheticGraphOptions options;
  options.num_vertices = 120;
  options.sigma_xy = 0.01;
  options.sigma_theta = 0.005;
  SyntheticGraph synthetic = MakeSyntheticGraph(options);
  PoseGraph graph = synthetic.graph;
  // A false loop closure between two far-apart vertices, claiming they coincide.
  graph.AddEdge(10, 100, Pose2(0.0, 0.0, 0.0), options.information);
  auto error_to_truth = [&](const PoseGraph& g) {
    double worst = 0.0;
    for (int v = 0; v < static_cast<int>(g.num_vertices()); ++v) {
      worst = std::max(worst, (g.vertex(v).T_map_v.translation() -
                               synthetic.truth[static_cast<std::size_t>(v)].translation())
                                  .norm());
    }
    return worst;
  };
  PoseGraph plain = graph;
  GaussNewtonSolver(plain, EffectiveFixed(plain), {}).Run(plain, true);
  ASSERT_GT(error_to_truth(plain), 1.0);
  // Cauchy is redescending: the wrong edge's pull vanishes. (Huber only bounds it, which a long
  // chain cannot resist; it is no defence against a far-off false closure.)
  PoseGraph robust = graph;
  GaussNewtonOptions options_robust;
  options_robust.robust_kernel = "cauchy";
  options_robust.robust_width = 3.0;
  const LeastSquaresSummary summary =
      GaussNewtonSolver(robust, EffectiveFixed(robust), options_robust).Run(robust, true);
  PoseGraph clean = synthetic.graph;  // Without the false closure.
  GaussNewtonSolver(clean, EffectiveFixed(clean), {}).Run(clean, true);
  double worst = 0.0;
  for (int v = 0; v < static_cast<int>(clean.num_vertices()); ++v) {
    worst = std::max(
        worst,
        (robust.vertex(v).T_map_v.translation() - clean.vertex(v).T_map_v.translation()).norm());
  }
  EXPECT_LT(worst, 0.05 * error_to_truth(plain));
  // The plain chi^2 includes the wrong edge's large error; the estimate is still what it was.
  EXPECT_GT(summary.chi2_final, 100.0);
}

TEST(GaussNewtonTest, OptionsValidate) {
  GaussNewtonOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.robust_kernel = "tukey";
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.robust_width = 0.0;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace gridslam::pose_graph
