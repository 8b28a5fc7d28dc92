#include "gridslam/io/toro_io.hpp"

#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

using pose_graph::PoseGraph;

TEST(ToroIoTest, ConvertsTheInformationOrder) {
  // docs/formats.md §3: the same edge in both formats, I13 = 10 and I23 = 20.
  const auto toro =
      ParseToro("VERTEX2 0 0 0 0\nVERTEX 1 1 0 0\nEDGE2 0 1 1.0 0.0 0.05236 500 0 500 5000 10 20\n",
                "mem.graph");
  const auto g2o = ParseG2o(
      "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nEDGE_SE2 0 1 1.0 0.0 0.05236 500 0 10 500 20 5000\n",
      "mem.g2o");
  ASSERT_TRUE(toro.ok()) << toro.error().ToString();
  ASSERT_TRUE(g2o.ok());
  EXPECT_EQ(toro.value().edge(0).information, g2o.value().edge(0).information);
  EXPECT_EQ(toro.value().edge(0).information(0, 2), 10.0);
  EXPECT_EQ(toro.value().edge(0).information(2, 1), 20.0);
}

TEST(ToroIoTest, AcceptsTheUnnumberedTagsAndSkipsEquiv) {
  GraphReadStats stats;
  const auto graph = ParseToro(
      "VERTEX 0 0 0 0\nVERTEX 1 1 0 0\nEDGE 0 1 1 0 0 1 0 1 1 0 0\nEQUIV 0 1\n", "t.graph", &stats);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(graph.value().num_edges(), 1u);
  EXPECT_EQ(stats.skipped_tags, (std::set<std::string>{"EQUIV"}));
}

TEST(ToroIoTest, RejectsAZeroDiagonalLikeGtsam) {
  // A g2o-ordered line read as TORO puts I13 = 0 where I_ss belongs.
  const auto graph = ParseToro("EDGE2 0 1 1 0 0 500 0 0 500 0 5000\n", "wrong.graph");
  ASSERT_FALSE(graph.ok());
  EXPECT_EQ(graph.error().line, 1);
  EXPECT_NE(graph.error().message.find("wrong field order"), std::string::npos);
  const auto bad_number = ParseToro("VERTEX2 0 0 0 0\nEDGE2 0 1 1 0 x 1 0 1 1 0 0\n", "b.graph");
  ASSERT_FALSE(bad_number.ok());
  EXPECT_EQ(bad_number.error().line, 2);
  EXPECT_NE(bad_number.error().message.find("field 5 (dtheta)"), std::string::npos);
}

TEST(ToroIoTest, CovarianceOptionInvertsTheMatrix) {
  ToroReadOptions options;
  options.covariance = true;
  const auto graph =
      ParseToro("EDGE2 0 1 1 0 0 0.01 0 0.04 0.001 0 0\n", "c.graph", nullptr, options);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  const Eigen::Matrix3d expected = Eigen::Vector3d(100.0, 25.0, 1000.0).asDiagonal();
  EXPECT_LT((graph.value().edge(0).information - expected).norm(), 1e-9);
}

TEST(ToroIoTest, RoundTripKeepsChi2AndMatchesG2o) {
  pose_graph::SyntheticGraphOptions options;
  options.num_vertices = 80;
  options.sigma_xy = 0.1;
  options.sigma_theta = 0.05;
  options.information << 44.6, -7.9, 0.3, -7.9, 376.5, 1.2, 0.3, 1.2, 9745.8;
  const PoseGraph graph = pose_graph::MakeSyntheticGraph(options).graph;
  const auto dir = testing::MakeTempDir("toro_round_trip");
  const std::string path = (dir / "graph.graph").string();
  ASSERT_TRUE(WritePoseGraphFile(path, graph).ok());  // .graph -> TORO.
  const auto back = ReadPoseGraphFile(path);
  ASSERT_TRUE(back.ok()) << back.error().ToString();
  EXPECT_EQ(pose_graph::Chi2(back.value()), pose_graph::Chi2(graph));
  EXPECT_EQ(FormatG2o(back.value()), FormatG2o(graph));
}

TEST(ToroIoTest, ReadsTheSharedTOROGraphs) {
  GRIDSLAM_REQUIRE_DATA();
  const auto graphs = testing::DataDir() / "graphs";
  for (const char* name : {"INTEL_P_toro.graph", "FR079_P_toro.graph"}) {
    const auto path = graphs / name;
    if (!std::filesystem::exists(path)) {
      continue;
    }
    GraphReadStats stats;
    const auto graph = ReadToro(path.string(), &stats);
    ASSERT_TRUE(graph.ok()) << graph.error().ToString();
    EXPECT_EQ(stats.created_vertices, 0) << name;
    EXPECT_GT(graph.value().num_edges(), graph.value().num_vertices() - 1) << name;
  }
}

}  // namespace
}  // namespace gridslam::io
