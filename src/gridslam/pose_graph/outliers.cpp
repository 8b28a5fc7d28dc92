#include "gridslam/pose_graph/outliers.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "gridslam/common/angles.hpp"
#include "gridslam/common/check.hpp"

namespace gridslam::pose_graph {

bool ParseOutlierKind(const std::string& name, OutlierKind* kind) {
  if (name == "random") {
    *kind = OutlierKind::kRandom;
  } else if (name == "local") {
    *kind = OutlierKind::kLocal;
  } else if (name == "group") {
    *kind = OutlierKind::kGroup;
  } else {
    return false;
  }
  return true;
}

std::vector<int> AddOutliers(PoseGraph& graph, const OutlierOptions& options) {
  const int n = static_cast<int>(graph.num_vertices());
  GRIDSLAM_CHECK(n >= 3 && graph.num_edges() > 0) << "outliers need >= 3 vertices and an edge";
  GRIDSLAM_CHECK(options.count >= 0 && options.group_size >= 1 && options.local_window >= 2)
      << "bad outlier options";
  Eigen::Matrix3d information = graph.edge(0).information;
  for (const Edge& e : graph.edges()) {
    if (std::abs(static_cast<long>(e.to) - static_cast<long>(e.from)) == 1) {
      information = e.information;
      break;
    }
  }
  std::mt19937 rng(options.seed);
  std::uniform_int_distribution<int> vertex(0, n - 1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_pose = [&](double half_width) {
    return Pose2(half_width * unit(rng), half_width * unit(rng), std::numbers::pi * unit(rng));
  };
  auto loop_pair = [&](int i, int j) {
    const long gap = static_cast<long>(graph.vertex(j).id) - graph.vertex(i).id;
    return i != j && gap != 1 && gap != -1;
  };
  std::vector<int> added;
  auto add = [&](int i, int j, const Pose2& z) {
    added.push_back(graph.AddEdge(graph.vertex(i).id, graph.vertex(j).id, z, information,
                                  EdgeRole::kLoopClosure));
  };
  while (static_cast<int>(added.size()) < options.count) {
    if (options.kind == OutlierKind::kRandom) {
      const int i = vertex(rng);
      const int j = vertex(rng);
      if (loop_pair(i, j)) {
        add(i, j, random_pose(options.max_translation));
      }
    } else if (options.kind == OutlierKind::kLocal) {
      const int i = vertex(rng);
      const int gap = std::uniform_int_distribution<int>(2, options.local_window)(rng);
      const int j = i + gap;
      if (j < n && loop_pair(i, j)) {
        add(i, j, random_pose(options.local_translation));
      }
    } else {
      const int i = vertex(rng);
      const int j = vertex(rng);
      const Pose2 z = random_pose(options.max_translation);
      for (int k = 0; k < options.group_size && static_cast<int>(added.size()) < options.count;
           ++k) {
        if (i + k < n && j + k < n && loop_pair(i + k, j + k)) {
          add(i + k, j + k, z);
        }
      }
    }
  }
  return added;
}

PoseErrors ComparePoses(const PoseGraph& graph, const PoseGraph& reference) {
  GRIDSLAM_CHECK(graph.num_vertices() == reference.num_vertices())
      << "graphs differ in their vertex count";
  PoseErrors errors;
  const int n = static_cast<int>(graph.num_vertices());
  for (int v = 0; v < n; ++v) {
    const Vertex& a = graph.vertex(v);
    const Vertex& b = reference.vertex(v);
    GRIDSLAM_CHECK(a.id == b.id) << "vertex " << v << ": ids differ (" << a.id << ", " << b.id
                                 << ")";
    const double d = (a.T_map_v.translation() - b.T_map_v.translation()).norm();
    errors.mean_translation += d;
    errors.max_translation = std::max(errors.max_translation, d);
    errors.mean_rotation += std::abs(NormalizeAngle(a.T_map_v.theta() - b.T_map_v.theta()));
  }
  if (n > 0) {
    errors.mean_translation /= n;
    errors.mean_rotation /= n;
  }
  return errors;
}

}  // namespace gridslam::pose_graph
