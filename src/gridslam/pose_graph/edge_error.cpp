#include "gridslam/pose_graph/edge_error.hpp"

namespace gridslam::pose_graph {

Eigen::Vector3d EdgeError(const PoseGraph& graph, int edge_index) {
  const Edge& edge = graph.edge(edge_index);
  return EdgeError(graph.vertex(graph.FromIndex(edge_index)).T_map_v.ToVector(),
                   graph.vertex(graph.ToIndex(edge_index)).T_map_v.ToVector(),
                   edge.T_i_j.ToVector());
}

double EdgeChi2(const PoseGraph& graph, int edge_index) {
  const Eigen::Vector3d e = EdgeError(graph, edge_index);
  return e.dot(graph.edge(edge_index).information * e);
}

double Chi2(const PoseGraph& graph) {
  double chi2 = 0.0;
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    chi2 += EdgeChi2(graph, k);
  }
  return chi2;
}

}  // namespace gridslam::pose_graph
