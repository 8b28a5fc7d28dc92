// Shared machinery of the g2o (docs/formats.md §2) and TORO (§3) graph readers: one line loop for
// both formats (a GraphSyntax names the tags and fields and builds the information matrix),
// whitespace tokenizing, strict number parsing with file:line:field errors, and assembling a
// PoseGraph from declared vertices, edges and FIX lines. Numbers must be finite and within
// kMaxGraphCoordinate / kMaxGraphAngle / kMaxGraphInformation; information matrices must be
// symmetric positive definite. A file that declares vertices must declare every vertex its
// edges use; only a file with no vertex line at all (edges-only, such as manhattan.g2o) gets
// its vertices created at the origin (reported in GraphReadStats::created_vertices).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/result.hpp"
#include "gridslam/io/g2o_io.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::io::internal {

/// Bounds on a graph file's numbers: beyond them a value is a corrupt number (and would
/// overflow chi-square), not a pose graph.
constexpr double kMaxGraphCoordinate = 1e6;    ///< |x|, |y| of vertices and edges [m].
constexpr double kMaxGraphAngle = 1e4;         ///< |theta| [rad].
constexpr double kMaxGraphInformation = 1e18;  ///< |information entry|.

/// A graph format's line syntax, for ParseGraphText.
struct GraphSyntax {
  std::vector<std::string> vertex_tags;  ///< "TAG id x y theta".
  std::vector<std::string> edge_tags;    ///< "TAG id id dx dy dtheta m0 .. m5".
  std::string fix_tag;                   ///< "FIX id..." (empty: none).
  const char* edge_id_names[2] = {"i", "j"};
  const char* const* edge_fields = nullptr;  ///< The 9 number fields' names.
  /// The information matrix from the six matrix numbers `m`, or an error naming file:line.
  std::function<Status(const std::string& tag, const double* m, const std::string& file, long line,
                       Eigen::Matrix3d& information)>
      information;
};

/// Parses a g2o or TORO text with `syntax`; other tags are skipped with one warning per tag.
Result<pose_graph::PoseGraph> ParseGraphText(const std::string& text, const std::string& file,
                                             const GraphSyntax& syntax, GraphReadStats* stats);

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
    long line;
  };
  std::string file_;
  std::vector<pose_graph::Vertex> vertices_;
  std::map<int, long> vertex_lines_;
  std::vector<PendingEdge> edges_;
  std::vector<std::pair<int, long>> fixed_;
  GraphReadStats stats_;
};

/// Formats a double losslessly (the shortest text that reads back to the same value).
std::string Number(double value);

}  // namespace gridslam::io::internal
