// Synthetic pose graphs with known ground truth, for tests, benchmarks and the later end-to-end
// checks: a robot walks a Manhattan-world grid (unit steps, turns of +-90 degrees), odometry edges
// join consecutive poses, and loop-closure edges join poses that come close to an earlier one
// (as in Olson et al. 2006's M3500). Measurements are the true relative poses plus optional
// Gaussian noise; the vertices start at the odometry-chained guess. Deterministic for a seed.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::pose_graph {

struct SyntheticGraphOptions {
  int num_vertices = 200;
  unsigned seed = 1;
  double step = 1.0;  ///< Grid spacing [m].
  double turn_probability = 0.3;
  double loop_distance = 0.5;  ///< Loop closures to earlier poses closer than this [m].
  int min_loop_gap = 5;        ///< Minimum id gap of a loop closure.
  int max_loops_per_vertex = 1;
  double sigma_xy = 0.0;     ///< Measurement noise, translation [m].
  double sigma_theta = 0.0;  ///< Measurement noise, rotation [rad].
  /// Information of every edge, (x, y, theta) order.
  Eigen::Matrix3d information = Eigen::Vector3d(100.0, 100.0, 1000.0).asDiagonal();
  int first_id = 0;  ///< Vertex ids are first_id, first_id + 1, ...
};

struct SyntheticGraph {
  PoseGraph graph;           ///< Vertices at the odometry-chained guess; nothing fixed.
  std::vector<Pose2> truth;  ///< True T_map_v per vertex index.
  int loop_closures = 0;
};

SyntheticGraph MakeSyntheticGraph(const SyntheticGraphOptions& options);

}  // namespace gridslam::pose_graph
