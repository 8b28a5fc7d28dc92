#include "gridslam/io/g2o_io.hpp"

#include <fstream>

#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/synthetic_graph.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

using pose_graph::PoseGraph;

TEST(G2oIoTest, ParsesVerticesEdgesFixAndComments) {
  const std::string text =
      "# a comment\n"
      "VERTEX_SE2 0 0 0 0\n"
      "VERTEX_SE2 1 1.03 0.01 7.0   # theta is normalized\n"
      "\n"
      "EDGE_SE2 0 1 1.0 0.0 0.05236 500.0 1.0 10.0 400.0 20.0 5000.0\n"
      "FIX 0\n";
  GraphReadStats stats;
  const auto graph = ParseG2o(text, "mem.g2o", &stats);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  const PoseGraph& g = graph.value();
  ASSERT_EQ(g.num_vertices(), 2u);
  ASSERT_EQ(g.num_edges(), 1u);
  EXPECT_TRUE(g.vertex(0).fixed);
  EXPECT_FALSE(g.vertex(1).fixed);
  EXPECT_NEAR(g.vertex(1).T_map_v.theta(), NormalizeAngle(7.0), 1e-15);
  const auto& e = g.edge(0);
  EXPECT_EQ(e.from, 0);
  EXPECT_EQ(e.to, 1);
  EXPECT_DOUBLE_EQ(e.T_i_j.theta(), 0.05236);
  Eigen::Matrix3d expected;
  expected << 500.0, 1.0, 10.0, 1.0, 400.0, 20.0, 10.0, 20.0, 5000.0;
  EXPECT_EQ(e.information, expected);
  EXPECT_EQ(stats.vertices, 2);
  EXPECT_EQ(stats.edges, 1);
  EXPECT_EQ(stats.created_vertices, 0);
}

TEST(G2oIoTest, SkipsUnknownTagsAndCreatesUndeclaredVertices) {
  const std::string text =
      "EDGE_SE2 4 5 1 0 0 1 0 0 1 0 1\n"
      "VERTEX_XY 9 1 2\n"
      "EDGE_SE2_XY 4 9 1 2 1 0 1\n"
      "ROBOTLASER1 whatever\n"
      "VERTEX_XY 10 1 2\n"
      "EDGE_SE2 5 6 1 0 0 1 0 0 1 0 1\n";
  GraphReadStats stats;
  const auto graph = ParseG2o(text, "edges_only.g2o", &stats);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(graph.value().num_vertices(), 3u);
  EXPECT_EQ(stats.created_vertices, 3);
  EXPECT_EQ(stats.skipped_lines, 4);
  EXPECT_EQ(stats.skipped_tags, (std::set<std::string>{"VERTEX_XY", "EDGE_SE2_XY", "ROBOTLASER1"}));
}

TEST(G2oIoTest, ErrorsNameFileLineAndField) {
  struct Case {
    std::string text;
    long line;
    std::string fragment;
  };
  const std::vector<Case> cases = {
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 zero 0\n", 2, "field 3 (y)"},
      {"VERTEX_SE2 0 0 0\n", 1, "expected 4 fields"},
      {"VERTEX_SE2 x 0 0 0\n", 1, "not an integer vertex id"},
      {"EDGE_SE2 0 1 1 0 0 1 0 0 1 0\n", 1, "expected 11 fields"},
      {"EDGE_SE2 0 1 1 0 0 1 0 0 1 0 nan\n", 1, "field 11 (I33)"},
      {"EDGE_SE2 0 0 1 0 0 1 0 0 1 0 1\n", 1, "to itself"},
      {"EDGE_SE2 0 1 1 0 0 -1 0 0 1 0 1\n", 1, "not positive definite"},
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 0 1 1 1\n", 2, "declared twice"},
      {"VERTEX_SE2 0 0 0 0\nFIX 3\n", 2, "FIX of unknown vertex 3"},
  };
  for (const auto& c : cases) {
    const auto graph = ParseG2o(c.text, "bad.g2o", nullptr);
    ASSERT_FALSE(graph.ok()) << c.text;
    EXPECT_EQ(graph.error().code, ErrorCode::kInvalidInput);
    EXPECT_EQ(graph.error().file, "bad.g2o");
    EXPECT_EQ(graph.error().line, c.line) << c.text;
    EXPECT_NE(graph.error().message.find(c.fragment), std::string::npos)
        << graph.error().ToString();
  }
}

TEST(G2oIoTest, RoundTripIsLosslessAndKeepsChi2) {
  pose_graph::SyntheticGraphOptions options;
  options.num_vertices = 120;
  options.sigma_xy = 0.1;
  options.sigma_theta = 0.05;
  options.information << 44.6, -7.9, 0.3, -7.9, 376.5, 1.2, 0.3, 1.2, 9745.8;
  PoseGraph graph = pose_graph::MakeSyntheticGraph(options).graph;
  graph.SetFixed(3, true);
  const auto dir = testing::MakeTempDir("g2o_round_trip");
  const std::string path = (dir / "graph.g2o").string();
  ASSERT_TRUE(WriteG2o(path, graph).ok());
  const auto read = ReadG2o(path);
  ASSERT_TRUE(read.ok()) << read.error().ToString();
  const PoseGraph& back = read.value();
  ASSERT_EQ(back.num_vertices(), graph.num_vertices());
  ASSERT_EQ(back.num_edges(), graph.num_edges());
  for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
    EXPECT_EQ(back.vertex(v).id, graph.vertex(v).id);
    EXPECT_EQ(back.vertex(v).fixed, graph.vertex(v).fixed);
    EXPECT_EQ(back.vertex(v).T_map_v.ToVector(), graph.vertex(v).T_map_v.ToVector());
  }
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    EXPECT_EQ(back.edge(k).T_i_j.ToVector(), graph.edge(k).T_i_j.ToVector());
    EXPECT_EQ(back.edge(k).information, graph.edge(k).information);
  }
  EXPECT_EQ(pose_graph::Chi2(back), pose_graph::Chi2(graph));
  // Writing again gives the same bytes.
  EXPECT_EQ(FormatG2o(back), FormatG2o(graph));
}

TEST(G2oIoTest, DetectsTheFormatByExtensionThenContent) {
  EXPECT_EQ(DetectGraphFormat("a.g2o", "EDGE2 0 1").value(), GraphFormat::kG2o);
  EXPECT_EQ(DetectGraphFormat("a.graph", "").value(), GraphFormat::kToro);
  EXPECT_EQ(DetectGraphFormat("a.txt", "# c\n\nEDGE_SE2 0 1").value(), GraphFormat::kG2o);
  EXPECT_EQ(DetectGraphFormat("a.txt", "VERTEX2 0 0 0 0").value(), GraphFormat::kToro);
  EXPECT_FALSE(DetectGraphFormat("a.txt", "hello world\n").ok());
  EXPECT_FALSE(ReadPoseGraphFile("/nonexistent/graph.g2o").ok());
}

TEST(G2oIoTest, ReadsTheSharedGraphs) {
  GRIDSLAM_REQUIRE_DATA();
  const auto graphs = testing::DataDir() / "graphs";
  for (const char* name : {"intel.g2o", "manhattan.g2o", "input_MITb_g2o.g2o"}) {
    const auto path = graphs / name;
    if (!std::filesystem::exists(path)) {
      continue;
    }
    GraphReadStats stats;
    const auto graph = ReadG2o(path.string(), &stats);
    ASSERT_TRUE(graph.ok()) << graph.error().ToString();
    EXPECT_GT(graph.value().num_edges(), 0u) << name;
    EXPECT_EQ(stats.skipped_lines, 0) << name;
    EXPECT_EQ(stats.vertices + stats.created_vertices,
              static_cast<long>(graph.value().num_vertices()));
  }
}

}  // namespace
}  // namespace gridslam::io
