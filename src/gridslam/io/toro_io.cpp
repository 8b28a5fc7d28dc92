#include "gridslam/io/toro_io.hpp"

#include <string_view>
#include <vector>

#include <Eigen/LU>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/internal/graph_text.hpp"
#include "gridslam/io/options_yaml.hpp"

namespace gridslam::io {

namespace {

constexpr const char* kEdgeFields[] = {"dx",   "dy",   "dtheta", "I_ff", "I_fs",
                                       "I_ss", "I_rr", "I_fr",   "I_sr"};

}  // namespace

Result<pose_graph::PoseGraph> ParseToro(const std::string& text, const std::string& file,
                                        GraphReadStats* stats, const ToroReadOptions& options) {
  internal::GraphSyntax syntax;
  syntax.vertex_tags = {"VERTEX2", "VERTEX"};
  syntax.edge_tags = {"EDGE2", "EDGE"};  // EQUIV (node merging) and anything else are skipped.
  syntax.edge_id_names[0] = "id1";
  syntax.edge_id_names[1] = "id2";
  syntax.edge_fields = kEdgeFields;
  syntax.information = [covariance = options.covariance](const std::string& tag, const double* v,
                                                         const std::string& at_file, long line,
                                                         Eigen::Matrix3d& information) -> Status {
    // TORO order ff fs ss rr fr sr = I11 I12 I22 I33 I13 I23 (docs/formats.md §3).
    Eigen::Matrix3d m;
    m << v[0], v[1], v[4], v[1], v[2], v[5], v[4], v[5], v[3];
    // GTSAM's sanity check: a zero on the diagonal means another order (or a bad file).
    if (m(0, 0) == 0.0 || m(1, 1) == 0.0 || m(2, 2) == 0.0) {
      return InvalidInput(tag + ": zero on the " +
                              std::string(covariance ? "covariance" : "information") +
                              " diagonal (I_ff, I_ss or I_rr): wrong field order?",
                          at_file, line);
    }
    information = m;
    if (covariance) {
      Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
      if (!lu.isInvertible()) {
        return InvalidInput(tag + ": singular covariance", at_file, line);
      }
      information = lu.inverse();
      information = 0.5 * (information + information.transpose()).eval();
    }
    return Status::Ok();
  };
  return internal::ParseGraphText(text, file, syntax, stats);
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
  return WriteFileAtomically(path, FormatToro(graph));
}

}  // namespace gridslam::io
