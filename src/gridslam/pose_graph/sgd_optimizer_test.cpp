#include "gridslam/pose_graph/sgd_optimizer.hpp"

#include <random>

#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/gauss_newton.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"

namespace gridslam::pose_graph {
namespace {

void Perturb(PoseGraph& graph, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int v = 1; v < static_cast<int>(graph.num_vertices()); ++v) {
    const Pose2& p = graph.vertex(v).T_map_v;
    graph.SetPose(v, Pose2(p.x() + 0.2 * normal(rng), p.y() + 0.2 * normal(rng),
                           p.theta() + 0.05 * normal(rng)));
  }
}

double OptimumChi2(PoseGraph graph) {
  GaussNewtonSolver solver(graph, EffectiveFixed(graph), {});
  return solver.Run(graph, true).chi2_final;
}

SyntheticGraph Noisy(int n, unsigned seed, int first_id = 0) {
  SyntheticGraphOptions options;
  options.num_vertices = n;
  options.seed = seed;
  options.sigma_xy = 0.05;
  options.sigma_theta = 0.02;
  options.first_id = first_id;
  return MakeSyntheticGraph(options);
}

TEST(SgdOptimizerTest, ExactMeasurementsConvergeTowardsZeroError) {
  SyntheticGraphOptions options;
  options.num_vertices = 100;
  SyntheticGraph synthetic = MakeSyntheticGraph(options);
  Perturb(synthetic.graph, 3);
  for (const char* variant : {"g2o", "toro"}) {
    SgdOptions sgd_options;
    sgd_options.variant = variant;
    SgdOptimizer sgd(synthetic.graph, sgd_options);
    const double before = sgd.Chi2();
    sgd.Iterate(300);
    EXPECT_EQ(sgd.iterations(), 300);
    EXPECT_LT(sgd.Chi2(), 1e-4 * before) << variant;
    EXPECT_NEAR(Chi2(sgd.graph()), sgd.Chi2(), 1e-9 * before);
  }
}

TEST(SgdOptimizerTest, LowersChi2ByOrdersOfMagnitudeForEveryTree) {
  const SyntheticGraph synthetic = Noisy(400, 2);
  const double odometry = Chi2(synthetic.graph);
  for (const char* tree : {"auto", "toro", "bfs", "chain"}) {
    SgdOptions options;
    options.tree = tree;
    SgdOptimizer sgd(synthetic.graph, options);
    sgd.Iterate(100);
    EXPECT_LT(sgd.Chi2(), 1e-2 * odometry) << tree;
    EXPECT_GT(sgd.TotalPathLength(), 0);
  }
}

TEST(SgdOptimizerTest, KeepsFixedVerticesAndHandlesDisconnectedGraphs) {
  const SyntheticGraph a = Noisy(80, 4);
  const SyntheticGraph b = Noisy(80, 5, 1000);
  PoseGraph graph = a.graph;
  for (const auto& v : b.graph.vertices()) {
    graph.AddVertex(v.id, v.T_map_v, v.id == 1040);  // A fixed vertex inside component b.
  }
  for (const auto& e : b.graph.edges()) {
    graph.AddEdge(e.from, e.to, e.T_i_j, e.information);
  }
  graph.AddVertex(5000, Pose2(1.0, 2.0, 3.0));  // Isolated.
  ASSERT_EQ(ConnectedComponents(graph).count, 3);
  Perturb(graph, 7);
  const double before = Chi2(graph);
  SgdOptimizer sgd(graph, {});
  sgd.Iterate(200);
  EXPECT_LT(sgd.Chi2(), 1e-2 * before);
  EXPECT_LT(sgd.Chi2(), 3.0 * OptimumChi2(graph));
  const PoseGraph& result = sgd.graph();
  EXPECT_TRUE(IsApprox(result.vertex(0).T_map_v, graph.vertex(0).T_map_v, 1e-12, 1e-12));
  const int pinned = graph.IndexOf(1040);
  EXPECT_TRUE(IsApprox(result.vertex(pinned).T_map_v, graph.vertex(pinned).T_map_v, 1e-12, 1e-12));
  const int isolated = graph.IndexOf(5000);
  EXPECT_TRUE(
      IsApprox(result.vertex(isolated).T_map_v, graph.vertex(isolated).T_map_v, 1e-12, 1e-12));
}

TEST(SgdOptimizerTest, IncrementalGrowthInitializesNewVerticesFromTheirEdge) {
  const SyntheticGraph synthetic = Noisy(300, 6);
  const PoseGraph& full = synthetic.graph;
  SgdOptimizer sgd;
  // Vertices arrive with a useless guess; the first edge places them.
  sgd.AddVertex(full.vertex(0).id, full.vertex(0).T_map_v);
  std::size_t next_edge = 0;
  for (int v = 1; v < static_cast<int>(full.num_vertices()); ++v) {
    sgd.AddVertex(full.vertex(v).id, Pose2(100.0, -100.0, 2.0));
    bool first = true;
    while (next_edge < full.num_edges() &&
           std::max(full.FromIndex(static_cast<int>(next_edge)),
                    full.ToIndex(static_cast<int>(next_edge))) <= v) {
      const Edge& e = full.edge(static_cast<int>(next_edge++));
      sgd.AddEdge(e.from, e.to, e.T_i_j, e.information);
      if (first) {
        // Placed from its parent edge: the new odometry edge has no error.
        const int k = static_cast<int>(sgd.graph().num_edges()) - 1;
        EXPECT_LT(EdgeChi2(sgd.graph(), k), 1e-18);
        first = false;
      }
    }
    if (v % 10 == 0) {
      sgd.Iterate(5);
    }
  }
  sgd.Iterate(20);
  EXPECT_EQ(sgd.graph().num_vertices(), full.num_vertices());
  EXPECT_EQ(sgd.graph().num_edges(), full.num_edges());
  // Comparable to a batch run of the same total work on the complete graph, and far below the
  // odometry guess.
  SgdOptimizer batch(full, {});
  batch.Iterate(sgd.iterations());
  EXPECT_LT(sgd.Chi2(), 1e-2 * Chi2(full));
  EXPECT_LT(sgd.Chi2(), 3.0 * batch.Chi2());
}

// Grows `full` in `sgd` vertex by vertex with its edges, iterating every 10 vertices.
void GrowIncrementally(const PoseGraph& full, SgdOptimizer& sgd) {
  sgd.AddVertex(full.vertex(0).id, full.vertex(0).T_map_v);
  std::size_t next_edge = 0;
  for (int v = 1; v < static_cast<int>(full.num_vertices()); ++v) {
    sgd.AddVertex(full.vertex(v).id, full.vertex(v).T_map_v);
    while (next_edge < full.num_edges() &&
           std::max(full.FromIndex(static_cast<int>(next_edge)),
                    full.ToIndex(static_cast<int>(next_edge))) <= v) {
      const Edge& e = full.edge(static_cast<int>(next_edge++));
      sgd.AddEdge(e.from, e.to, e.T_i_j, e.information);
    }
    if (v % 10 == 0) {
      sgd.Iterate(5);
    }
  }
}

TEST(SgdOptimizerTest, LoopEdgesRebuildTheTreeOfTheGrownGraph) {
  // Grown leaf by leaf, the tree is the path, and a loop edge's path runs around its loop; the
  // first iteration after a loop edge builds the tree of the whole graph, as a batch run would.
  const SyntheticGraph synthetic = Noisy(400, 12);
  SgdOptions rebuild;
  rebuild.rebuild_tree = true;
  SgdOptimizer grown;  // the default keeps the tree as it grew
  SgdOptimizer rebuilt(rebuild);
  GrowIncrementally(synthetic.graph, grown);
  GrowIncrementally(synthetic.graph, rebuilt);
  ASSERT_GT(synthetic.graph.num_edges(), synthetic.graph.num_vertices());  // loops
  rebuilt.Iterate(1);
  grown.Iterate(1);
  const SgdOptimizer batch(rebuilt.graph(), {});
  EXPECT_EQ(rebuilt.TotalPathLength(), batch.TotalPathLength());
  EXPECT_LT(2 * rebuilt.TotalPathLength(), grown.TotalPathLength());
  // The schedule goes on: the estimate is as good as with the tree as it grew.
  EXPECT_LT(rebuilt.Chi2(), 1e-2 * Chi2(synthetic.graph));
  EXPECT_LT(rebuilt.Chi2(), 1.5 * grown.Chi2());
}

TEST(SgdOptimizerTest, InconsistentNewEdgesSpeedUpOnlyTheirPath) {
  // With the schedule continuing, a late loop closure with a large error still gets corrected.
  const SyntheticGraph synthetic = Noisy(200, 8);
  PoseGraph odometry_only;
  std::vector<const Edge*> loops;
  for (const auto& v : synthetic.graph.vertices()) {
    odometry_only.AddVertex(v.id, v.T_map_v);
  }
  for (const auto& e : synthetic.graph.edges()) {
    if (e.to == e.from + 1) {
      odometry_only.AddEdge(e.from, e.to, e.T_i_j, e.information);
    } else {
      loops.push_back(&e);
    }
  }
  ASSERT_FALSE(loops.empty());
  std::vector<double> results;
  for (const double threshold : {7.81, 1e300}) {  // Rates raised, and never raised.
    SgdOptions options;
    options.incremental_chi2_threshold = threshold;
    SgdOptimizer sgd(odometry_only, options);
    sgd.Iterate(300);  // Late in the schedule: 1 / t is small.
    for (const Edge* e : loops) {
      sgd.AddEdge(e->from, e->to, e->T_i_j, e->information);
    }
    const double with_loops = sgd.Chi2();
    sgd.Iterate(30);
    EXPECT_LT(sgd.Chi2(), with_loops);
    results.push_back(sgd.Chi2());
  }
  EXPECT_LT(results[0], 0.5 * results[1]);
  EXPECT_LT(results[0], 3.0 * OptimumChi2(synthetic.graph));
}

TEST(SgdOptimizerTest, JoiningTwoComponentsMovesTheUnanchoredOne) {
  const SyntheticGraph a = Noisy(50, 9);
  const SyntheticGraph b = Noisy(50, 10, 500);
  SgdOptimizer sgd(a.graph, {});
  for (const auto& v : b.graph.vertices()) {
    sgd.AddVertex(v.id, Pose2(v.T_map_v.x() + 30.0, v.T_map_v.y(), v.T_map_v.theta() + 1.0));
  }
  for (const auto& e : b.graph.edges()) {
    sgd.AddEdge(e.from, e.to, e.T_i_j, e.information);
  }
  sgd.Iterate(20);
  EXPECT_EQ(ConnectedComponents(sgd.graph()).count, 2);
  // An inter-robot edge: b's first vertex is 2 m ahead of a's last.
  const Pose2 T_a_b(2.0, 0.0, 0.5);
  sgd.AddEdge(49, 500, T_a_b, Eigen::Matrix3d::Identity() * 100.0);
  EXPECT_EQ(ConnectedComponents(sgd.graph()).count, 1);
  const PoseGraph& joined = sgd.graph();
  const Pose2 relative = Between(joined.vertex(joined.IndexOf(49)).T_map_v,
                                 joined.vertex(joined.IndexOf(500)).T_map_v);
  EXPECT_TRUE(IsApprox(relative, T_a_b, 1e-9, 1e-9));
  sgd.Iterate(100);
  EXPECT_LT(sgd.Chi2(), 3.0 * OptimumChi2(sgd.graph()));
}

}  // namespace
}  // namespace gridslam::pose_graph
