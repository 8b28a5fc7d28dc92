// Orientation-first initial guesses for pose-graph optimization (robust_optimization.md; Carlone
// et al. 2014, "A fast and accurate approximation for planar pose graph optimization" (LAGO);
// Carlone et al. 2015, "Initialization techniques for 3D SLAM: a survey on rotation estimation").
// Gauss-Newton from the odometry-chained guess ends in a local minimum when the relative
// orientations are noisy (M3500 with 0.2-0.3 rad of extra noise); estimating all orientations
// first, from a problem without local minima, and then the positions, puts it in the global basin.
//  1. Orientations:
//     - "chordal": each rotation R_i is relaxed to an unconstrained 2-vector r_i = (cos, sin) and
//       sum w_ij |r_j - R(theta_ij) r_i|^2 is minimized (linear least squares), then each r_i is
//       projected back (atan2);
//     - "lago": sum w_ij (theta_j - theta_i - theta_ij - 2 pi k_ij)^2 is minimized (linear), with
//       each edge's integer k_ij taken from the orientations composed along the chaining tree
//       (graph_utils.hpp) so that every cycle is regularized as in LAGO.
//     w_ij is the edge's rotational information Omega(2, 2).
//  2. Positions: with the orientations fixed, the translation part of the g2o error is linear in
//     the positions; its weighted least-squares solution (Omega's translation block) is taken.
// Anchors (EffectiveFixed) keep their poses. Gauss-Newton from this guess finishes the job.
#pragma once

#include <string>

#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::pose_graph {

enum class Initialization { kNone, kChordal, kLago };

/// Parses "none", "chordal" or "lago"; false otherwise.
bool ParseInitialization(const std::string& name, Initialization* out);

/// Replaces the poses of every non-anchor vertex by the orientation-first estimate (kNone: leaves
/// the graph alone). Returns false (graph unchanged) if a linear system could not be solved.
bool InitializeOrientationFirst(PoseGraph& graph, Initialization method);

}  // namespace gridslam::pose_graph
