// PoseGraph: the 2-D constraint network optimized by the back end (docs/design.md §1.7). Vertices
// are poses T_map_v (x, y, theta) with an optional "fixed" flag; edges are relative measurements
// T_i_j (the pose of vertex j in vertex i's frame) with a 3x3 information matrix in (x, y, theta)
// order, exactly the semantics of g2o's EDGE_SE2 (docs/formats.md §2). Vertex ids are arbitrary
// integers (as in the files); the graph also numbers vertices and edges densely by insertion
// order ("indices"), which is what the optimizers work with. Connected components, anchors and
// the odometry-chained initial guess live in graph_utils.hpp; the error in edge_error.hpp.
#pragma once

#include <array>
#include <cstddef>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"

namespace gridslam::pose_graph {

struct Vertex {
  int id = 0;
  Pose2 T_map_v;       ///< Current estimate of the vertex pose in the map frame.
  bool fixed = false;  ///< Held constant by every optimizer (g2o FIX).
};

/// Whether the optimizer's outlier defence (robust_optimization.md: dynamic covariance scaling or
/// graduated non-convexity, OptimizerOptions::robust) may down-weight an edge.
enum class EdgeRole {
  kAuto,         ///< A loop closure iff the ids are not consecutive (|to - from| != 1).
  kOdometry,     ///< Trusted: never down-weighted.
  kLoopClosure,  ///< May be wrong: subject to the robust mechanism.
};

struct Edge {
  int from = 0;  ///< Vertex id i.
  int to = 0;    ///< Vertex id j.
  Pose2 T_i_j;   ///< Measured pose of j in i's frame.
  /// Information (inverse covariance) in (x, y, theta) order: symmetric, positive semi-definite.
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  EdgeRole role = EdgeRole::kAuto;
};

/// True if the edge counts as a loop closure (role kLoopClosure, or kAuto with non-consecutive
/// ids): the edges the robust mechanism may down-weight.
[[nodiscard]] inline bool IsLoopClosure(const Edge& edge) {
  if (edge.role != EdgeRole::kAuto) {
    return edge.role == EdgeRole::kLoopClosure;
  }
  const long gap = static_cast<long>(edge.to) - static_cast<long>(edge.from);
  return gap != 1 && gap != -1;
}

class PoseGraph {
 public:
  /// Adds a vertex and returns its index. The id must not exist yet (checked).
  int AddVertex(int id, const Pose2& T_map_v, bool fixed = false);
  /// Adds an edge between two existing vertices (checked), returns its index. `information` must
  /// be symmetric (checked to 1e-9 relative) with a non-negative diagonal. Self-loops are checked
  /// errors; several edges between the same pair are allowed (as in g2o).
  int AddEdge(int from, int to, const Pose2& T_i_j, const Eigen::Matrix3d& information,
              EdgeRole role = EdgeRole::kAuto);

  [[nodiscard]] bool HasVertex(int id) const { return index_.count(id) != 0; }
  /// Index of vertex `id`, or -1 when absent.
  [[nodiscard]] int IndexOf(int id) const;

  [[nodiscard]] std::size_t num_vertices() const { return vertices_.size(); }
  [[nodiscard]] std::size_t num_edges() const { return edges_.size(); }
  [[nodiscard]] const std::vector<Vertex>& vertices() const { return vertices_; }
  [[nodiscard]] const std::vector<Edge>& edges() const { return edges_; }
  [[nodiscard]] const Vertex& vertex(int index) const { return vertices_[Checked(index)]; }
  [[nodiscard]] const Edge& edge(int index) const { return edges_[CheckedEdge(index)]; }
  /// Vertex indices of edge `index`'s endpoints (from, to).
  [[nodiscard]] int FromIndex(int edge_index) const { return ends_[CheckedEdge(edge_index)][0]; }
  [[nodiscard]] int ToIndex(int edge_index) const { return ends_[CheckedEdge(edge_index)][1]; }

  void SetPose(int index, const Pose2& T_map_v) { vertices_[Checked(index)].T_map_v = T_map_v; }
  void SetFixed(int index, bool fixed) { vertices_[Checked(index)].fixed = fixed; }
  void SetEdgeRole(int edge_index, EdgeRole role) { edges_[CheckedEdge(edge_index)].role = role; }

  /// Per vertex index, the indices of the edges touching it (built on demand, kept up to date).
  [[nodiscard]] const std::vector<std::vector<int>>& Incidence() const;

 private:
  [[nodiscard]] std::size_t Checked(int index) const;
  [[nodiscard]] std::size_t CheckedEdge(int index) const;

  std::vector<Vertex> vertices_;
  std::vector<Edge> edges_;
  std::vector<std::array<int, 2>> ends_;
  std::unordered_map<int, int> index_;
  mutable std::vector<std::vector<int>> incidence_;
  mutable std::size_t incidence_edges_ = 0;
};

}  // namespace gridslam::pose_graph
