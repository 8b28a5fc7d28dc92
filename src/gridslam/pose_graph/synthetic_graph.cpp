#include "gridslam/pose_graph/synthetic_graph.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include "gridslam/common/check.hpp"

namespace gridslam::pose_graph {

SyntheticGraph MakeSyntheticGraph(const SyntheticGraphOptions& options) {
  GRIDSLAM_CHECK(options.num_vertices >= 1) << "need at least one vertex";
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto noisy = [&](const Pose2& z) {
    return Pose2(z.x() + options.sigma_xy * normal(rng), z.y() + options.sigma_xy * normal(rng),
                 z.theta() + options.sigma_theta * normal(rng));
  };

  SyntheticGraph result;
  Pose2 pose;
  for (int k = 0; k < options.num_vertices; ++k) {
    if (k > 0) {
      double turn = 0.0;
      if (uniform(rng) < options.turn_probability) {
        turn = uniform(rng) < 0.5 ? std::numbers::pi / 2 : -std::numbers::pi / 2;
      }
      pose = pose * Pose2(options.step, 0.0, turn);
      // Snap to the grid so that revisits coincide exactly.
      pose = Pose2(std::round(pose.x() / options.step) * options.step,
                   std::round(pose.y() / options.step) * options.step, pose.theta());
    }
    result.truth.push_back(pose);
  }
  auto add_edge = [&](int i, int j) {
    const Pose2 z = noisy(Between(result.truth[static_cast<std::size_t>(i)],
                                  result.truth[static_cast<std::size_t>(j)]));
    result.graph.AddEdge(options.first_id + i, options.first_id + j, z, options.information);
    return z;
  };
  Pose2 chained = result.truth.front();
  result.graph.AddVertex(options.first_id, chained);
  for (int k = 1; k < options.num_vertices; ++k) {
    result.graph.AddVertex(options.first_id + k, chained);
    chained = chained * add_edge(k - 1, k);
    result.graph.SetPose(k, chained);
    int loops = 0;
    for (int j = 0; j + options.min_loop_gap <= k && loops < options.max_loops_per_vertex; ++j) {
      const auto& a = result.truth[static_cast<std::size_t>(j)];
      const auto& b = result.truth[static_cast<std::size_t>(k)];
      if ((a.translation() - b.translation()).norm() < options.loop_distance) {
        add_edge(j, k);
        ++loops;
        ++result.loop_closures;
      }
    }
  }
  return result;
}

}  // namespace gridslam::pose_graph
