#include "gridslam/io/internal/graph_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <Eigen/Eigenvalues>

#include "gridslam/common/logging.hpp"

namespace gridslam::io::internal {

void Tokenize(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && std::isspace(static_cast<unsigned char>(line[i])) != 0) {
      ++i;
    }
    if (i >= n || line[i] == '#') {
      return;
    }
    const std::size_t start = i;
    while (i < n && std::isspace(static_cast<unsigned char>(line[i])) == 0) {
      ++i;
    }
    tokens.push_back(line.substr(start, i - start));
  }
}

Result<pose_graph::PoseGraph> ParseGraphText(const std::string& text, const std::string& file,
                                             const GraphSyntax& syntax, GraphReadStats* stats) {
  static constexpr const char* kVertexFields[] = {"x", "y", "theta"};
  const auto is = [](const std::vector<std::string>& tags, const std::string& tag) {
    return std::find(tags.begin(), tags.end(), tag) != tags.end();
  };
  GraphAssembler assembler(file);
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
    if (line.find('\0') != std::string_view::npos) {
      return InvalidInput("a NUL byte in the line (a binary file, not a graph?)", file,
                          line_number);
    }
    Tokenize(line, tokens);
    if (tokens.empty()) {
      continue;
    }
    const std::string tag(tokens[0]);
    if (is(syntax.vertex_tags, tag)) {
      if (tokens.size() < 2) {
        return InvalidInput(tag + ": missing id", file, line_number);
      }
      const auto id = ParseId(tokens[1], tag, "1 (id)", file, line_number);
      GRIDSLAM_RETURN_IF_ERROR(id);
      double v[3];
      GRIDSLAM_RETURN_IF_ERROR(ParseNumbers(tokens, 2, 3, kVertexFields, file, line_number, v));
      GRIDSLAM_RETURN_IF_ERROR(
          assembler.AddVertex(id.value(), Pose2(v[0], v[1], v[2]), line_number));
    } else if (is(syntax.edge_tags, tag)) {
      if (tokens.size() < 3) {
        return InvalidInput(tag + ": missing vertex ids", file, line_number);
      }
      const std::string from_name = std::string("1 (") + syntax.edge_id_names[0] + ")";
      const std::string to_name = std::string("2 (") + syntax.edge_id_names[1] + ")";
      const auto from = ParseId(tokens[1], tag, from_name.c_str(), file, line_number);
      GRIDSLAM_RETURN_IF_ERROR(from);
      const auto to = ParseId(tokens[2], tag, to_name.c_str(), file, line_number);
      GRIDSLAM_RETURN_IF_ERROR(to);
      double v[9];
      GRIDSLAM_RETURN_IF_ERROR(
          ParseNumbers(tokens, 3, 9, syntax.edge_fields, file, line_number, v));
      Eigen::Matrix3d information;
      GRIDSLAM_RETURN_IF_ERROR(syntax.information(tag, v + 3, file, line_number, information));
      GRIDSLAM_RETURN_IF_ERROR(assembler.AddEdge(from.value(), to.value(), Pose2(v[0], v[1], v[2]),
                                                 information, line_number));
    } else if (!syntax.fix_tag.empty() && tag == syntax.fix_tag) {
      if (tokens.size() < 2) {
        return InvalidInput(tag + ": no vertex id", file, line_number);
      }
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::string field = std::to_string(k) + " (id)";
        const auto id = ParseId(tokens[k], tag, field.c_str(), file, line_number);
        GRIDSLAM_RETURN_IF_ERROR(id);
        GRIDSLAM_RETURN_IF_ERROR(assembler.Fix(id.value(), line_number));
      }
    } else {
      assembler.Skip(tag, line_number);
    }
  }
  return assembler.Finish(stats);
}

Status ParseNumbers(const std::vector<std::string_view>& tokens, std::size_t first,
                    std::size_t count, const char* const* names, const std::string& file, long line,
                    double* out) {
  const std::string tag(tokens.empty() ? std::string_view() : tokens[0]);
  if (tokens.size() != first + count) {
    return InvalidInput(tag + ": expected " + std::to_string(first + count - 1) +
                            " fields after the tag, found " + std::to_string(tokens.size() - 1),
                        file, line);
  }
  for (std::size_t k = 0; k < count; ++k) {
    std::string_view token = tokens[first + k];
    if (!token.empty() && token.front() == '+') {
      token.remove_prefix(1);
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) {
      return InvalidInput(tag + " field " + std::to_string(first + k) + " (" + names[k] +
                              "): not a finite number: '" + std::string(tokens[first + k]) + "'",
                          file, line);
    }
    // Fields named I..., or the (co)variance entries, hold the matrix; the rest are poses.
    const std::string name(names[k]);
    const bool angle = name.find("theta") != std::string::npos;
    const bool matrix = !angle && name != "x" && name != "y" && name != "dx" && name != "dy";
    const double bound =
        matrix ? kMaxGraphInformation : (angle ? kMaxGraphAngle : kMaxGraphCoordinate);
    if (std::abs(value) > bound) {
      char text[32];
      std::snprintf(text, sizeof(text), "%g", bound);
      return InvalidInput(tag + " field " + std::to_string(first + k) + " (" + names[k] +
                              "): " + std::string(tokens[first + k]) + " is beyond +-" + text,
                          file, line);
    }
    out[k] = value;
  }
  return Status::Ok();
}

Result<int> ParseId(std::string_view token, const std::string& tag, const char* name,
                    const std::string& file, long line) {
  int id = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), id);
  if (ec != std::errc() || end != token.data() + token.size()) {
    return InvalidInput(
        tag + " field " + name + ": not an integer vertex id: '" + std::string(token) + "'", file,
        line);
  }
  return id;
}

Status GraphAssembler::AddVertex(int id, const Pose2& pose, long line) {
  if (const auto it = vertex_lines_.find(id); it != vertex_lines_.end()) {
    return InvalidInput("vertex " + std::to_string(id) + " declared twice (first on line " +
                            std::to_string(it->second) + ")",
                        file_, line);
  }
  vertex_lines_.emplace(id, line);
  vertices_.push_back(pose_graph::Vertex{id, pose, false});
  ++stats_.vertices;
  return Status::Ok();
}

Status GraphAssembler::AddEdge(int from, int to, const Pose2& T_i_j,
                               const Eigen::Matrix3d& information, long line) {
  if (from == to) {
    return InvalidInput("edge from vertex " + std::to_string(from) + " to itself", file_, line);
  }
  // Zero, singular or indefinite matrices make chi-square meaningless (LM reported -162006).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(information, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d lambda = eigen.eigenvalues();  // ascending
  if (!(lambda(2) > 0.0) || !(lambda(0) > 1e-14 * lambda(2))) {
    char text[96];
    std::snprintf(text, sizeof(text), "%g, %g, %g", lambda(0), lambda(1), lambda(2));
    return InvalidInput(
        "information matrix is not positive definite (eigenvalues " + std::string(text) + ")",
        file_, line);
  }
  edges_.push_back(PendingEdge{from, to, T_i_j, information, line});
  ++stats_.edges;
  return Status::Ok();
}

Status GraphAssembler::Fix(int id, long line) {
  fixed_.emplace_back(id, line);
  return Status::Ok();
}

void GraphAssembler::Skip(const std::string& tag, long line) {
  ++stats_.skipped_lines;
  if (stats_.skipped_tags.insert(tag).second) {
    GRIDSLAM_LOG_WARN("{}:{}: skipping unsupported tag '{}' (warned once per tag)", file_, line,
                      tag);
  }
}

Result<pose_graph::PoseGraph> GraphAssembler::Finish(GraphReadStats* stats) {
  pose_graph::PoseGraph graph;
  for (const auto& vertex : vertices_) {
    graph.AddVertex(vertex.id, vertex.T_map_v, false);
  }
  std::map<int, bool> missing;
  for (const auto& edge : edges_) {
    for (const int id : {edge.from, edge.to}) {
      if (!graph.HasVertex(id)) {
        if (!vertices_.empty()) {
          // Only an edges-only file gets its vertices created (at the origin).
          return InvalidInput(
              "edge to vertex " + std::to_string(id) + ", which the file does not declare", file_,
              edge.line);
        }
        missing[id] = true;
      }
    }
  }
  for (const auto& [id, unused] : missing) {
    graph.AddVertex(id, Pose2::Identity(), false);
    ++stats_.created_vertices;
  }
  for (const auto& edge : edges_) {
    graph.AddEdge(edge.from, edge.to, edge.T_i_j, edge.information);
  }
  for (const auto& [id, line] : fixed_) {
    const int index = graph.IndexOf(id);
    if (index < 0) {
      return InvalidInput("FIX of unknown vertex " + std::to_string(id), file_, line);
    }
    graph.SetFixed(index, true);
  }
  if (stats != nullptr) {
    *stats = stats_;
  }
  return graph;
}

std::string Number(double value) {
  // Shortest text that reads back to the same double (std::to_chars round-trip guarantee).
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value == 0.0 ? 0.0 : value);
  return {buffer, result.ptr};
}

}  // namespace gridslam::io::internal
