#include "gridslam/io/internal/graph_text.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>

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
  for (int d = 0; d < 3; ++d) {
    if (information(d, d) < 0.0) {
      return InvalidInput("information matrix has a negative diagonal entry", file_, line);
    }
  }
  edges_.push_back(PendingEdge{from, to, T_i_j, information});
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

Status WriteFileAtomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      return RuntimeError("cannot open '" + temporary + "' for writing");
    }
    out << text;
    out.flush();
    if (!out) {
      return RuntimeError("cannot write '" + temporary + "'");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    return RuntimeError("cannot rename '" + temporary + "' to '" + path + "'");
  }
  return Status::Ok();
}

std::string Number(double value) {
  // Shortest text that reads back to the same double (std::to_chars round-trip guarantee).
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value == 0.0 ? 0.0 : value);
  return {buffer, result.ptr};
}

}  // namespace gridslam::io::internal
