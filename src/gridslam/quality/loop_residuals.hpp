// Loop-closure residuals after optimization (docs/self_check.md): how far the optimized graph
// departs from each accepted loop-closure measurement. Reported beside the self-check score; a
// consistent graph explains its closures to within the alignment noise.
#pragma once

#include <vector>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::quality {

/// A loop-closure measurement: the pose of vertex `to` in vertex `from`'s frame.
struct LoopMeasurement {
  int from = 0;
  int to = 0;
  Pose2 T_from_to;
};

struct LoopResidualStats {
  long closures = 0;                ///< Measurements whose vertices are in the graph.
  double median_translation = 0.0;  ///< [m]
  double max_translation = 0.0;     ///< [m]
  double median_rotation = 0.0;     ///< |angle| [rad]
  double max_rotation = 0.0;        ///< [rad]
};

/// Residual T_from_to^-1 * (T_map_from^-1 * T_map_to) of every measurement against the graph's
/// vertex estimates; measurements naming a missing vertex are skipped.
LoopResidualStats LoopResiduals(const pose_graph::PoseGraph& graph,
                                const std::vector<LoopMeasurement>& loops);

}  // namespace gridslam::quality
