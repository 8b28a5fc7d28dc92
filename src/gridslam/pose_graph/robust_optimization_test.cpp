// The optimizer's defence against wrong loop closures (robust_options.hpp) on synthetic graphs.
#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/optimizer.hpp"
#include "gridslam/pose_graph/outliers.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"

namespace gridslam::pose_graph {
namespace {

SyntheticGraph Make() {
  SyntheticGraphOptions options;
  options.num_vertices = 400;
  options.seed = 3;
  options.sigma_xy = 0.02;
  options.sigma_theta = 0.005;
  return MakeSyntheticGraph(options);
}

OptimizerOptions Options(const std::string& method, const std::string& robust) {
  OptimizerOptions options;
  options.method = method;
  options.robust.mechanism = robust;
  return options;
}

PoseGraph CleanOptimum(const SyntheticGraph& synthetic) {
  PoseGraph graph = synthetic.graph;
  Optimize(graph, Options("gn", "none"));
  return graph;
}

TEST(RobustOptimizationTest, DcsSurvivesWrongLoopClosures) {
  const SyntheticGraph synthetic = Make();
  ASSERT_GE(synthetic.loop_closures, 40);
  const PoseGraph clean = CleanOptimum(synthetic);
  for (const OutlierKind kind : {OutlierKind::kRandom, OutlierKind::kLocal, OutlierKind::kGroup}) {
    PoseGraph corrupted = synthetic.graph;
    OutlierOptions outliers;
    outliers.count = 40;
    outliers.kind = kind;
    AddOutliers(corrupted, outliers);
    // Without a defence the wrong edges bend the map...
    PoseGraph plain = corrupted;
    Optimize(plain, Options("sgd+gn", "none"));
    EXPECT_GT(ComparePoses(plain, clean).mean_translation, 0.2) << static_cast<int>(kind);
    // ... with DCS on the loop closures they are found and the clean optimum is kept.
    PoseGraph robust = corrupted;
    const OptimizationReport report = Optimize(robust, Options("sgd+gn", "dcs"));
    EXPECT_LT(ComparePoses(robust, clean).mean_translation, 1e-4) << static_cast<int>(kind);
    EXPECT_EQ(report.rejected_edges, 40) << static_cast<int>(kind);
    EXPECT_NEAR(report.chi2_inliers, Chi2(clean), 1e-6 * Chi2(clean));
  }
}

TEST(RobustOptimizationTest, CleanGraphKeepsItsOptimum) {
  const SyntheticGraph synthetic = Make();
  const double chi2_star = Chi2(CleanOptimum(synthetic));
  for (const char* mechanism : {"dcs", "gnc"}) {
    PoseGraph graph = synthetic.graph;
    const OptimizationReport report = Optimize(graph, Options("gn", mechanism));
    EXPECT_EQ(report.rejected_edges, 0) << mechanism;
    EXPECT_NEAR(report.chi2_final, chi2_star, 1e-6 * chi2_star) << mechanism;
  }
}

TEST(RobustOptimizationTest, OdometryEdgesAreNeverDownWeighted) {
  // A wrong odometry edge (consecutive ids) is trusted: the robust mechanism leaves it in.
  SyntheticGraph synthetic = Make();
  PoseGraph graph = synthetic.graph;
  graph.AddEdge(10, 11, Pose2(3.0, 0.0, 0.5), graph.edge(0).information);
  const OptimizationReport report = Optimize(graph, Options("gn", "dcs"));
  EXPECT_EQ(report.rejected_edges, 0);
  EXPECT_NEAR(report.chi2_inliers, report.chi2_final, 1e-9 * report.chi2_final);
}

TEST(RobustOptimizationTest, WithChordalInitializationSurvivesOutliersAndKeepsTheOptimum) {
  const SyntheticGraph synthetic = Make();
  const PoseGraph clean = CleanOptimum(synthetic);
  OptimizerOptions options = Options("sgd+gn", "dcs");
  options.initialization = "chordal";
  PoseGraph graph = synthetic.graph;
  const OptimizationReport clean_report = Optimize(graph, options);
  EXPECT_TRUE(clean_report.initialized);
  EXPECT_EQ(clean_report.rejected_edges, 0);
  EXPECT_NEAR(clean_report.chi2_final, Chi2(clean), 1e-6 * Chi2(clean));
  PoseGraph corrupted = synthetic.graph;
  OutlierOptions outliers;
  outliers.count = 40;
  AddOutliers(corrupted, outliers);
  // Chordal alone (least squares) is bent by the wrong edges...
  PoseGraph plain = corrupted;
  OptimizerOptions no_defence = Options("gn", "none");
  no_defence.initialization = "chordal";
  Optimize(plain, no_defence);
  EXPECT_GT(ComparePoses(plain, clean).mean_translation, 0.2);
  // ... the robust stage with it is not.
  const OptimizationReport report = Optimize(corrupted, options);
  EXPECT_LT(ComparePoses(corrupted, clean).mean_translation, 1e-4);
  EXPECT_EQ(report.rejected_edges, 40);
}

TEST(RobustOptimizationTest, OptionsValidate) {
  OptimizerOptions options;
  options.robust.mechanism = "switchable";
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.robust.dcs_phi = {};
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.robust.gnc_factor = 1.0;
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.initialization = "spectral";
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.gn.robust_edges = "odometry";
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace gridslam::pose_graph
