// End to end, the final optimization (issue 13): the graph written beside a map (graph.g2o) is
// the optimum of exactly the loop edges that survived pruning, and report.json's chi2_final is
// its chi2. Pruning is forced into the last round (one round, a low chi2 threshold), where the
// mapper once removed an edge without optimizing again.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "gridslam/io/g2o_io.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/optimizer.hpp"
#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"

namespace gridslam {
namespace {

TEST(FinalGraph, WrittenGraphIsAtItsOptimumAndCarriesTheReportedChi2) {
  simulation::SimulationOptions sim;
  sim.seed = 1;
  auto world = simulation::MakeBuiltinWorld("office", sim.resolution);
  ASSERT_TRUE(world.ok());
  auto simulated = simulation::Simulate(world.value(), {}, sim);
  ASSERT_TRUE(simulated.ok()) << simulated.error().ToString();

  SlamOptions options;
  options.graph.prune_rounds = 1;
  options.loop_closure.prune_chi2 = 0.5;  // some loop edge is above it: pruning in the last round
  pipeline::Mapper mapper(options.Mapper(), 1);
  for (const Frame& frame : simulated.value().robots.at(0).frames) {
    mapper.AddFrame(0, frame);
  }
  const pipeline::MapperResult result = mapper.Finish();
  ASSERT_GE(result.stats.pruned, 1);

  const std::string path =
      (std::filesystem::path(::testing::TempDir()) / "final_graph_test.g2o").string();
  ASSERT_TRUE(io::WriteG2o(path, result.graph).ok());
  auto written = io::ReadG2o(path);
  ASSERT_TRUE(written.ok()) << written.error().ToString();
  const double chi2 = pose_graph::Chi2(written.value());
  EXPECT_NEAR(chi2, result.stats.chi2_final, 1e-6 * result.stats.chi2_final + 1e-9);

  pose_graph::PoseGraph reoptimized = written.value();
  pose_graph::OptimizerOptions gn;
  gn.method = "gn";
  pose_graph::Optimize(reoptimized, gn);
  EXPECT_GE(pose_graph::Chi2(reoptimized), chi2 * (1.0 - 1e-4) - 1e-6);
}

}  // namespace
}  // namespace gridslam
