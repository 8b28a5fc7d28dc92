#include "gridslam/pose_graph/optimizer.hpp"

#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"

namespace gridslam::pose_graph {
namespace {

SyntheticGraph Make(unsigned seed) {
  SyntheticGraphOptions options;
  options.num_vertices = 250;
  options.seed = seed;
  options.sigma_xy = 0.05;
  options.sigma_theta = 0.02;
  return MakeSyntheticGraph(options);
}

TEST(OptimizerTest, GaussNewtonLevenbergAndSgdPlusGnAgree) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const SyntheticGraph synthetic = Make(seed);
    std::vector<double> finals;
    for (const char* method : {"gn", "lm", "sgd+gn"}) {
      PoseGraph graph = synthetic.graph;
      OptimizerOptions options;
      options.method = method;
      const OptimizationReport report = Optimize(graph, options);
      EXPECT_EQ(report.method, method);
      EXPECT_NEAR(report.chi2_initial, Chi2(synthetic.graph), 1e-9 * report.chi2_initial);
      EXPECT_NEAR(report.chi2_final, Chi2(graph), 1e-9 * report.chi2_final);
      EXPECT_TRUE(report.converged) << method;
      EXPECT_EQ(report.iterations, report.sgd_iterations + report.ls_iterations);
      EXPECT_GE(report.seconds, 0.0);
      EXPECT_EQ(report.components, 1);
      finals.push_back(report.chi2_final);
    }
    EXPECT_NEAR(finals[1], finals[0], 1e-6 * finals[0]) << "seed " << seed;
    EXPECT_NEAR(finals[2], finals[0], 1e-6 * finals[0]) << "seed " << seed;
  }
}

TEST(OptimizerTest, SgdAloneAndCallbacks) {
  const SyntheticGraph synthetic = Make(4);
  PoseGraph graph = synthetic.graph;
  OptimizerOptions options;
  options.method = "sgd";
  std::vector<IterationRecord> records;
  const OptimizationReport report =
      Optimize(graph, options, 25, [&](const IterationRecord& r) { records.push_back(r); });
  EXPECT_EQ(report.sgd_iterations, 25);
  EXPECT_EQ(report.ls_iterations, 0);
  EXPECT_FALSE(report.converged);
  ASSERT_EQ(records.size(), 25u);
  EXPECT_EQ(records.front().stage, "sgd");
  EXPECT_EQ(records.back().iteration, 25);
  EXPECT_NEAR(records.back().chi2, report.chi2_final, 1e-9 * report.chi2_final);
  EXPECT_LT(report.chi2_final, 1e-2 * report.chi2_initial);
}

TEST(OptimizerTest, OptionsValidate) {
  OptimizerOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.method = "cg";
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.sgd.tree = "mst";
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.warmup_iterations = -1;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace gridslam::pose_graph
