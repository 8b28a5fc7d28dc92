// Issue 17's g2o/TORO reproducers: huge values, edges to undeclared vertices and zero, singular
// or indefinite information matrices are rejected with file:line, in both formats (one parser).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/io/g2o_io.hpp"
#include "gridslam/io/toro_io.hpp"

namespace gridslam::io {
namespace {

struct Case {
  std::string text;
  long line;
  std::string fragment;
};

void ExpectRejected(const Case& c, bool toro) {
  const std::string file = toro ? "bad.graph" : "bad.g2o";
  const auto graph = toro ? ParseToro(c.text, file) : ParseG2o(c.text, file);
  ASSERT_FALSE(graph.ok()) << "accepted:\n" << c.text;
  EXPECT_EQ(graph.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(graph.error().file, file);
  EXPECT_EQ(graph.error().line, c.line) << graph.error().ToString();
  EXPECT_NE(graph.error().message.find(c.fragment), std::string::npos) << graph.error().ToString();
}

constexpr const char* kG2oVertices = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n";
constexpr const char* kToroVertices = "VERTEX2 0 0 0 0\nVERTEX2 1 1 0 0\n";

TEST(GraphBadInput, HugeValuesAreRejected) {
  const std::string g = kG2oVertices;
  for (const Case& c : std::vector<Case>{
           {"VERTEX_SE2 0 1e308 0 0\n", 1, "field 2 (x)"},
           {"VERTEX_SE2 0 0 0 -1e300\n", 1, "field 4 (theta)"},
           {g + "EDGE_SE2 0 1 1e308 0 0 1 0 0 1 0 1\n", 3, "field 3 (dx)"},
           {g + "EDGE_SE2 0 1 1 0 0 1e308 0 0 1 0 1\n", 3, "field 6 (I11)"},
           {g + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 inf\n", 3, "field 11 (I33)"},
       }) {
    ExpectRejected(c, false);
  }
  const std::string t = kToroVertices;
  ExpectRejected({"VERTEX2 0 0 -1e7 0\n", 1, "field 3 (y)"}, true);
  ExpectRejected({t + "EDGE2 0 1 1 0 0 1e308 0 1 1 0 0\n", 3, "field 6 (I_ff)"}, true);
}

TEST(GraphBadInput, EdgesToUndeclaredVerticesAreRejected) {
  ExpectRejected({std::string(kG2oVertices) + "EDGE_SE2 0 7 1 0 0 1 0 0 1 0 1\n", 3,
                  "vertex 7, which the file does not declare"},
                 false);
  ExpectRejected({std::string(kToroVertices) + "EDGE2 9 1 1 0 0 1 0 1 1 0 0\n", 3,
                  "vertex 9, which the file does not declare"},
                 true);
  // A vertex declared after the edge that uses it is fine.
  EXPECT_TRUE(ParseG2o("VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\nVERTEX_SE2 1 1 0 0\n",
                       "late.g2o")
                  .ok());
  // An edges-only file (manhattan.g2o) still gets its vertices at the origin.
  GraphReadStats stats;
  const auto edges_only = ParseG2o("EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n", "edges.g2o", &stats);
  ASSERT_TRUE(edges_only.ok());
  EXPECT_EQ(stats.created_vertices, 2);
}

TEST(GraphBadInput, InformationMustBePositiveDefinite) {
  const std::string g = kG2oVertices;
  for (const Case& c : std::vector<Case>{
           {g + "EDGE_SE2 0 1 1 0 0 0 0 0 0 0 0\n", 3, "not positive definite"},   // zero
           {g + "EDGE_SE2 0 1 1 0 0 1 1 0 1 0 1\n", 3, "not positive definite"},   // singular
           {g + "EDGE_SE2 0 1 1 0 0 1 2 0 1 0 1\n", 3, "not positive definite"},   // indefinite
           {g + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 -5\n", 3, "not positive definite"},  // negative
       }) {
    ExpectRejected(c, false);
  }
  const std::string t = kToroVertices;
  // TORO order ff fs ss rr fr sr: I12 = 2 with I11 = I22 = 1 is indefinite.
  ExpectRejected({t + "EDGE2 0 1 1 0 0 1 2 1 1 0 0\n", 3, "not positive definite"}, true);
  ExpectRejected({t + "EDGE2 0 1 1 0 0 0 0 0 0 0 0\n", 3, "zero on the information diagonal"},
                 true);
  // Strongly anisotropic but positive definite (as in input_INTEL_g2o.g2o) is accepted.
  EXPECT_TRUE(ParseG2o(g + "EDGE_SE2 0 1 1 0 0 2.7e12 0 0 2.7e12 0 1\n", "ok.g2o").ok());
}

TEST(GraphBadInput, BinaryGraphIsRejected) {
  std::string text = kG2oVertices;
  text += std::string("EDGE_SE2 0 1\0\x01\x02", 15) + "\n";
  ExpectRejected({text, 3, "NUL byte"}, false);
}

}  // namespace
}  // namespace gridslam::io
