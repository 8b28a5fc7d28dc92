#include "gridslam/io/toro_io.hpp"

#include <string_view>
#include <vector>

#include <Eigen/LU>

#include "gridslam/io/internal/graph_text.hpp"
#include "gridslam/io/options_yaml.hpp"

namespace gridslam::io {

namespace {

constexpr const char* kVertexFields[] = {"x", "y", "theta"};
constexpr const char* kEdgeFields[] = {"dx",   "dy",   "dtheta", "I_ff", "I_fs",
                                       "I_ss", "I_rr", "I_fr",   "I_sr"};

}  // namespace

Result<pose_graph::PoseGraph> ParseToro(const std::string& text, const std::string& file,
                                        GraphReadStats* stats, const ToroReadOptions& options) {
  internal::GraphAssembler assembler(file);
  std::vector<std::string_view> tokens;
  long line_number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) {
      end = text.size();
    }
    const std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_number;
    internal::Tokenize(line, tokens);
    if (tokens.empty()) {
      continue;
    }
    const std::string tag(tokens[0]);
    if (tag == "VERTEX2" || tag == "VERTEX") {
      if (tokens.size() < 2) {
        return InvalidInput(tag + ": missing id", file, line_number);
      }
      const auto id = internal::ParseId(tokens[1], tag, "1 (id)", file, line_number);
      GRIDSLAM_RETURN_IF_ERROR(id);
      double v[3];
      GRIDSLAM_RETURN_IF_ERROR(
          internal::ParseNumbers(tokens, 2, 3, kVertexFields, file, line_number, v));
      GRIDSLAM_RETURN_IF_ERROR(
          assembler.AddVertex(id.value(), Pose2(v[0], v[1], v[2]), line_number));
    } else if (tag == "EDGE2" || tag == "EDGE") {
      if (tokens.size() < 3) {
        return InvalidInput(tag + ": missing vertex ids", file, line_number);
      }
      const auto from = internal::ParseId(tokens[1], tag, "1 (id1)", file, line_number);
      GRIDSLAM_RETURN_IF_ERROR(from);
      const auto to = internal::ParseId(tokens[2], tag, "2 (id2)", file, line_number);
      GRIDSLAM_RETURN_IF_ERROR(to);
      double v[9];
      GRIDSLAM_RETURN_IF_ERROR(
          internal::ParseNumbers(tokens, 3, 9, kEdgeFields, file, line_number, v));
      // TORO order ff fs ss rr fr sr = I11 I12 I22 I33 I13 I23 (FORMATS.md §3).
      Eigen::Matrix3d m;
      m << v[3], v[4], v[7], v[4], v[5], v[8], v[7], v[8], v[6];
      // GTSAM's sanity check: a zero on the diagonal means another order (or a bad file).
      if (m(0, 0) == 0.0 || m(1, 1) == 0.0 || m(2, 2) == 0.0) {
        return InvalidInput(tag + ": zero on the " +
                                std::string(options.covariance ? "covariance" : "information") +
                                " diagonal (I_ff, I_ss or I_rr): wrong field order?",
                            file, line_number);
      }
      Eigen::Matrix3d information = m;
      if (options.covariance) {
        Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
        if (!lu.isInvertible()) {
          return InvalidInput(tag + ": singular covariance", file, line_number);
        }
        information = lu.inverse();
        information = 0.5 * (information + information.transpose()).eval();
      }
      GRIDSLAM_RETURN_IF_ERROR(assembler.AddEdge(from.value(), to.value(), Pose2(v[0], v[1], v[2]),
                                                 information, line_number));
    } else {
      assembler.Skip(tag, line_number);  // EQUIV (node merging) and anything else.
    }
  }
  return assembler.Finish(stats);
}

Result<pose_graph::PoseGraph> ReadToro(const std::string& path, GraphReadStats* stats,
                                       const ToroReadOptions& options) {
  const auto text = ReadTextFile(path);
  GRIDSLAM_RETURN_IF_ERROR(text);
  return ParseToro(text.value(), path, stats, options);
}

std::string FormatToro(const pose_graph::PoseGraph& graph) {
  using internal::Number;
  std::string out;
  out.reserve(graph.num_vertices() * 48 + graph.num_edges() * 160);
  for (const auto& v : graph.vertices()) {
    out += "VERTEX2 " + std::to_string(v.id) + ' ' + Number(v.T_map_v.x()) + ' ' +
           Number(v.T_map_v.y()) + ' ' + Number(v.T_map_v.theta()) + '\n';
  }
  for (const auto& e : graph.edges()) {
    const Eigen::Matrix3d& m = e.information;
    out += "EDGE2 " + std::to_string(e.from) + ' ' + std::to_string(e.to) + ' ' +
           Number(e.T_i_j.x()) + ' ' + Number(e.T_i_j.y()) + ' ' + Number(e.T_i_j.theta()) + ' ' +
           Number(m(0, 0)) + ' ' + Number(m(0, 1)) + ' ' + Number(m(1, 1)) + ' ' + Number(m(2, 2)) +
           ' ' + Number(m(0, 2)) + ' ' + Number(m(1, 2)) + '\n';
  }
  return out;
}

Status WriteToro(const std::string& path, const pose_graph::PoseGraph& graph) {
  return internal::WriteFileAtomically(path, FormatToro(graph));
}

}  // namespace gridslam::io
