#include "gridslam/io/g2o_io.hpp"

#include <string_view>
#include <vector>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/internal/graph_text.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/io/toro_io.hpp"

namespace gridslam::io {

namespace {

constexpr const char* kEdgeFields[] = {"dx",  "dy",  "dtheta", "I11", "I12",
                                       "I13", "I22", "I23",    "I33"};

}  // namespace

Result<pose_graph::PoseGraph> ParseG2o(const std::string& text, const std::string& file,
                                       GraphReadStats* stats) {
  internal::GraphSyntax syntax;
  syntax.vertex_tags = {"VERTEX_SE2"};
  syntax.edge_tags = {"EDGE_SE2"};
  syntax.fix_tag = "FIX";
  syntax.edge_fields = kEdgeFields;
  syntax.information = [](const std::string& /*tag*/, const double* m, const std::string& /*file*/,
                          long /*line*/, Eigen::Matrix3d& information) {
    // Upper triangle, row-major, mirrored (g2o readInformationMatrix).
    information << m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], m[5];
    return Status::Ok();
  };
  return internal::ParseGraphText(text, file, syntax, stats);
}

Result<pose_graph::PoseGraph> ReadG2o(const std::string& path, GraphReadStats* stats) {
  const auto text = ReadTextFile(path);
  GRIDSLAM_RETURN_IF_ERROR(text);
  return ParseG2o(text.value(), path, stats);
}

std::string FormatG2o(const pose_graph::PoseGraph& graph) {
  using internal::Number;
  std::string out;
  out.reserve(graph.num_vertices() * 48 + graph.num_edges() * 160);
  for (const auto& v : graph.vertices()) {
    out += "VERTEX_SE2 " + std::to_string(v.id) + ' ' + Number(v.T_map_v.x()) + ' ' +
           Number(v.T_map_v.y()) + ' ' + Number(v.T_map_v.theta()) + '\n';
  }
  for (const auto& v : graph.vertices()) {
    if (v.fixed) {
      out += "FIX " + std::to_string(v.id) + '\n';
    }
  }
  for (const auto& e : graph.edges()) {
    out += "EDGE_SE2 " + std::to_string(e.from) + ' ' + std::to_string(e.to) + ' ' +
           Number(e.T_i_j.x()) + ' ' + Number(e.T_i_j.y()) + ' ' + Number(e.T_i_j.theta());
    for (int r = 0; r < 3; ++r) {
      for (int c = r; c < 3; ++c) {  // g2o writeInformationMatrix: upper triangle, row-major.
        out += ' ' + Number(e.information(r, c));
      }
    }
    out += '\n';
  }
  return out;
}

Status WriteG2o(const std::string& path, const pose_graph::PoseGraph& graph) {
  return WriteFileAtomically(path, FormatG2o(graph));
}

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Result<GraphFormat> DetectGraphFormat(const std::string& path, const std::string& text) {
  if (EndsWith(path, ".g2o")) {
    return GraphFormat::kG2o;
  }
  if (EndsWith(path, ".graph")) {
    return GraphFormat::kToro;
  }
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) {
      end = text.size();
    }
    internal::Tokenize(std::string_view(text.data() + pos, end - pos), tokens);
    pos = end + 1;
    if (tokens.empty()) {
      continue;
    }
    if (tokens[0] == "VERTEX_SE2" || tokens[0] == "EDGE_SE2") {
      return GraphFormat::kG2o;
    }
    if (tokens[0] == "VERTEX2" || tokens[0] == "EDGE2" || tokens[0] == "VERTEX" ||
        tokens[0] == "EDGE") {
      return GraphFormat::kToro;
    }
  }
  return InvalidInput(
      "neither a g2o nor a TORO 2-D graph (no VERTEX_SE2/EDGE_SE2/VERTEX2/EDGE2 "
      "line, and the extension is not .g2o or .graph)",
      path);
}

Result<pose_graph::PoseGraph> ReadPoseGraphFile(const std::string& path, GraphReadStats* stats) {
  const auto text = ReadTextFile(path);
  GRIDSLAM_RETURN_IF_ERROR(text);
  const auto format = DetectGraphFormat(path, text.value());
  GRIDSLAM_RETURN_IF_ERROR(format);
  if (format.value() == GraphFormat::kToro) {
    return ParseToro(text.value(), path, stats);
  }
  return ParseG2o(text.value(), path, stats);
}

Status WritePoseGraphFile(const std::string& path, const pose_graph::PoseGraph& graph) {
  return EndsWith(path, ".graph") ? WriteToro(path, graph) : WriteG2o(path, graph);
}

}  // namespace gridslam::io
