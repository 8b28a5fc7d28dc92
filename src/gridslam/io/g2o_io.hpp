// Reading and writing 2-D pose graphs in g2o's text format (docs/formats.md §2; g2o's VertexSE2 /
// EdgeSE2 read/write and OptimizableGraph::load): `VERTEX_SE2 id x y theta`,
// `EDGE_SE2 i j dx dy dtheta I11 I12 I13 I22 I23 I33` (information upper triangle, row-major,
// (x, y, theta) order), `FIX id...`, '#' comments. Other tags are skipped with one warning per tag.
// Angles are normalized on read; numbers are written in the shortest form that reads back
// exactly, so a write/read round trip is lossless. Also the format-agnostic entry points (g2o or
// TORO, chosen by extension or content) used by `gridslam optimize`.
#pragma once

#include <set>
#include <string>

#include "gridslam/common/result.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::io {

/// What a graph reader saw.
struct GraphReadStats {
  long vertices = 0;          ///< Vertex lines.
  long edges = 0;             ///< Edge lines.
  long created_vertices = 0;  ///< Vertices referenced by edges but never declared (at origin).
  long skipped_lines = 0;     ///< Lines with unknown or ignored tags.
  std::set<std::string> skipped_tags;
};

/// Parses g2o text; `file` names it in errors ("file:line: EDGE_SE2 field 5 (dtheta): ...").
/// Vertices referenced only by edges are created at the origin (see stats->created_vertices).
Result<pose_graph::PoseGraph> ParseG2o(const std::string& text, const std::string& file,
                                       GraphReadStats* stats = nullptr);
/// Reads a g2o file (NotFound if it cannot be opened).
Result<pose_graph::PoseGraph> ReadG2o(const std::string& path, GraphReadStats* stats = nullptr);
/// g2o text of a graph: vertices, then FIX for the fixed ones, then edges.
std::string FormatG2o(const pose_graph::PoseGraph& graph);
/// Writes a g2o file (atomically: a temporary file renamed into place).
Status WriteG2o(const std::string& path, const pose_graph::PoseGraph& graph);

enum class GraphFormat { kG2o, kToro };

/// Format from the extension (".g2o", ".graph"), else from the first tag in the text
/// (VERTEX_SE2/EDGE_SE2 -> g2o; VERTEX2/EDGE2/VERTEX/EDGE -> TORO); an error if neither.
Result<GraphFormat> DetectGraphFormat(const std::string& path, const std::string& text);
/// Reads a g2o or TORO file, detected as above.
Result<pose_graph::PoseGraph> ReadPoseGraphFile(const std::string& path,
                                                GraphReadStats* stats = nullptr);
/// Writes `graph` as TORO if `path` ends in ".graph", else as g2o.
Status WritePoseGraphFile(const std::string& path, const pose_graph::PoseGraph& graph);

}  // namespace gridslam::io
