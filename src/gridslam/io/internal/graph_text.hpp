// Shared machinery of the g2o (FORMATS.md §2) and TORO (§3) graph readers: whitespace
// tokenizing, strict number parsing with file:line:field errors, and assembling a PoseGraph from
// declared vertices, edges and FIX lines (vertices referenced only by edges are created at the
// origin and reported, so that edges-only files such as manhattan.g2o can be chained later).
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/result.hpp"
#include "gridslam/io/g2o_io.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::io::internal {

/// Splits `line` at whitespace into `tokens` (views into `line`); '#' starts a comment.
void Tokenize(std::string_view line, std::vector<std::string_view>& tokens);

/// Parses tokens[first..first+count) as finite doubles into `out`, or an error
/// "<tag> field <k> (<name>): ..." at file:line. `names` has `count` entries.
Status ParseNumbers(const std::vector<std::string_view>& tokens, std::size_t first,
                    std::size_t count, const char* const* names, const std::string& file, long line,
                    double* out);

/// Parses an integer vertex id.
Result<int> ParseId(std::string_view token, const std::string& tag, const char* name,
                    const std::string& file, long line);

/// Collects a file's elements and builds the graph at the end.
class GraphAssembler {
 public:
  explicit GraphAssembler(std::string file) : file_(std::move(file)) {}
  Status AddVertex(int id, const Pose2& pose, long line);
  Status AddEdge(int from, int to, const Pose2& T_i_j, const Eigen::Matrix3d& information,
                 long line);
  Status Fix(int id, long line);
  void Skip(const std::string& tag, long line);
  /// The graph: declared vertices in file order, then created ones by id, then edges.
  Result<pose_graph::PoseGraph> Finish(GraphReadStats* stats);

 private:
  struct PendingEdge {
    int from;
    int to;
    Pose2 T_i_j;
    Eigen::Matrix3d information;
  };
  std::string file_;
  std::vector<pose_graph::Vertex> vertices_;
  std::map<int, long> vertex_lines_;
  std::vector<PendingEdge> edges_;
  std::vector<std::pair<int, long>> fixed_;
  GraphReadStats stats_;
};

/// Writes `text` to `path` through a temporary file and a rename (no half file on failure).
Status WriteFileAtomically(const std::string& path, const std::string& text);

/// Formats a double losslessly (the shortest text that reads back to the same value).
std::string Number(double value);

}  // namespace gridslam::io::internal
