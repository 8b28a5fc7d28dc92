#include "gridslam/pose_graph/pose_graph.hpp"

#include <cmath>

#include "gridslam/common/check.hpp"

namespace gridslam::pose_graph {

int PoseGraph::AddVertex(int id, const Pose2& T_map_v, bool fixed) {
  GRIDSLAM_CHECK(!HasVertex(id)) << "vertex " << id << " already exists";
  const int index = static_cast<int>(vertices_.size());
  vertices_.push_back(Vertex{id, T_map_v, fixed});
  index_.emplace(id, index);
  return index;
}

int PoseGraph::AddEdge(int from, int to, const Pose2& T_i_j, const Eigen::Matrix3d& information,
                       EdgeRole role) {
  const int i = IndexOf(from);
  const int j = IndexOf(to);
  GRIDSLAM_CHECK(i >= 0 && j >= 0) << "edge " << from << " -> " << to << " to a missing vertex";
  GRIDSLAM_CHECK(i != j) << "self-loop edge on vertex " << from;
  const double scale = information.cwiseAbs().maxCoeff();
  GRIDSLAM_CHECK(information.allFinite() &&
                 (information - information.transpose()).cwiseAbs().maxCoeff() <=
                     1e-9 * std::max(scale, 1.0))
      << "edge " << from << " -> " << to << ": information not symmetric";
  GRIDSLAM_CHECK((information.diagonal().array() >= 0.0).all())
      << "edge " << from << " -> " << to << ": negative information diagonal";
  const int index = static_cast<int>(edges_.size());
  edges_.push_back(Edge{from, to, T_i_j, information, role});
  ends_.push_back({i, j});
  return index;
}

int PoseGraph::IndexOf(int id) const {
  const auto it = index_.find(id);
  return it == index_.end() ? -1 : it->second;
}

const std::vector<std::vector<int>>& PoseGraph::Incidence() const {
  incidence_.resize(vertices_.size());
  for (; incidence_edges_ < edges_.size(); ++incidence_edges_) {
    const auto& ends = ends_[incidence_edges_];
    incidence_[static_cast<std::size_t>(ends[0])].push_back(static_cast<int>(incidence_edges_));
    incidence_[static_cast<std::size_t>(ends[1])].push_back(static_cast<int>(incidence_edges_));
  }
  return incidence_;
}

std::size_t PoseGraph::Checked(int index) const {
  GRIDSLAM_CHECK(index >= 0 && static_cast<std::size_t>(index) < vertices_.size())
      << "vertex index " << index << " out of range";
  return static_cast<std::size_t>(index);
}

std::size_t PoseGraph::CheckedEdge(int index) const {
  GRIDSLAM_CHECK(index >= 0 && static_cast<std::size_t>(index) < edges_.size())
      << "edge index " << index << " out of range";
  return static_cast<std::size_t>(index);
}

}  // namespace gridslam::pose_graph
