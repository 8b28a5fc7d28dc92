// Integration test of the pose-graph back end on the shared graphs (docs/design.md §3.3): from the
// odometry-chained guess, SGD lowers chi^2 by orders of magnitude, Gauss-Newton and LM never raise
// it, sgd+gn ends at least as low as Gauss-Newton alone, and the TORO graphs optimize and
// round-trip. No figures of a particular dataset are hard-coded (docs/optimizer.md has them).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/io/g2o_io.hpp"
#include "gridslam/io/toro_io.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/optimizer.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam {
namespace {

using pose_graph::OptimizationReport;
using pose_graph::OptimizerOptions;
using pose_graph::PoseGraph;

std::vector<std::string> AvailableGraphs(const std::vector<std::string>& names) {
  std::vector<std::string> paths;
  for (const auto& name : names) {
    const auto path = testing::DataDir() / "graphs" / name;
    if (std::filesystem::exists(path)) {
      paths.push_back(path.string());
    }
  }
  return paths;
}

PoseGraph LoadChained(const std::string& path) {
  auto graph = io::ReadPoseGraphFile(path);
  EXPECT_TRUE(graph.ok()) << graph.error().ToString();
  PoseGraph result = std::move(graph).value();
  pose_graph::InitializeByChaining(result);
  return result;
}

OptimizationReport RunMethod(PoseGraph& graph, const std::string& method, int iterations,
                             std::vector<double>* history = nullptr) {
  OptimizerOptions options;
  options.method = method;
  return pose_graph::Optimize(graph, options, iterations,
                              [&](const pose_graph::IterationRecord& r) {
                                if (history != nullptr) {
                                  history->push_back(r.chi2);
                                }
                              });
}

TEST(PoseGraphOptimizeTest, SharedG2oGraphsFromTheOdometryGuess) {
  GRIDSLAM_REQUIRE_DATA();
  const auto paths =
      AvailableGraphs({"intel.g2o", "input_MITb_g2o.g2o", "manhattan.g2o", "ais2klinik.g2o"});
  if (paths.empty()) {
    GTEST_SKIP() << "no shared graph found";
  }
  for (const auto& path : paths) {
    SCOPED_TRACE(path);
    const PoseGraph start = LoadChained(path);
    const double chi2_start = pose_graph::Chi2(start);

    PoseGraph sgd = start;
    const OptimizationReport sgd_report = RunMethod(sgd, "sgd", 100);
    EXPECT_LT(sgd_report.chi2_final, 1e-3 * chi2_start);

    double gn_final = 0.0;
    for (const char* method : {"gn", "lm"}) {
      PoseGraph graph = start;
      std::vector<double> history{chi2_start};
      const OptimizationReport report = RunMethod(graph, method, 0, &history);
      for (std::size_t k = 1; k < history.size(); ++k) {
        EXPECT_LE(history[k], history[k - 1] * (1.0 + 1e-12)) << method << " iteration " << k;
      }
      if (std::string(method) == "gn") {
        gn_final = report.chi2_final;
      }
    }

    PoseGraph polished = start;
    const OptimizationReport report = RunMethod(polished, "sgd+gn", 0);
    EXPECT_TRUE(report.converged);
    EXPECT_LE(report.chi2_final, gn_final * (1.0 + 1e-6));
    EXPECT_LE(report.chi2_final, sgd_report.chi2_final);
    // A local minimum: another Gauss-Newton run does not move it.
    const OptimizationReport again = RunMethod(polished, "gn", 0);
    EXPECT_NEAR(again.chi2_final, report.chi2_final, 1e-6 * report.chi2_final);
  }
}

TEST(PoseGraphOptimizeTest, SharedToroGraphsOptimizeAndRoundTrip) {
  GRIDSLAM_REQUIRE_DATA();
  const auto paths = AvailableGraphs({"INTEL_P_toro.graph", "FR079_P_toro.graph"});
  if (paths.empty()) {
    GTEST_SKIP() << "no shared TORO graph found";
  }
  const auto dir = testing::MakeTempDir("toro_optimize");
  for (const auto& path : paths) {
    SCOPED_TRACE(path);
    auto read = io::ReadToro(path);
    ASSERT_TRUE(read.ok()) << read.error().ToString();
    PoseGraph graph = std::move(read).value();
    const OptimizationReport report = RunMethod(graph, "sgd+gn", 0);
    EXPECT_TRUE(report.converged);
    EXPECT_LT(report.chi2_final, report.chi2_initial);
    for (const char* name : {"out.g2o", "out.graph"}) {
      const std::string out = (dir / name).string();
      ASSERT_TRUE(io::WritePoseGraphFile(out, graph).ok());
      const auto back = io::ReadPoseGraphFile(out);
      ASSERT_TRUE(back.ok()) << back.error().ToString();
      EXPECT_EQ(pose_graph::Chi2(back.value()), pose_graph::Chi2(graph)) << name;
    }
  }
}

}  // namespace
}  // namespace gridslam
