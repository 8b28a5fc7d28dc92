// Refinement of a key-map alignment by matching one map's obstacle points to the other map's
// distance field (docs/design.md §1.5, "optional refinement of the accepted transform by
// grid-to-grid matching"): Gauss-Newton on sum_k rho(d_a(T_a_b * p_k)^2), with d_a the bilinearly
// interpolated metric distance to a's nearest obstacle, a Huber kernel, and points that land on a's
// unknown cells or farther than `max_distance` from its obstacles left out. Feature alignment is
// accurate to a few centimetres; this brings it to the grid's sub-cell accuracy, as the front end's
// scan-to-map matcher does for scans.
#pragma once

#include <span>
#include <string>

#include <Eigen/Core>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::loop_closure {

struct RefinementOptions {
  bool enabled = true;        ///< Refine accepted alignments.
  int max_iterations = 15;    ///< Gauss-Newton iterations [-].
  double huber = 0.05;        ///< Huber kernel width [m].
  double max_distance = 0.3;  ///< Points farther than this from a's obstacles are ignored [m].
  int max_points = 1500;      ///< Points used at most (regular subsample) [-].
  int min_points = 50;        ///< Fewer usable points: refinement fails [-].
  double max_step = 0.5;      ///< Refinement may move the transform at most this far [m].
  /// Which points of b the caller matches to a's distance field: "key_map" (b's obstacle cells,
  /// the whole window) or "scans" (the returns of the scans b holds, seen from where its
  /// trajectory poses are; the key map's cells when it holds too few). A key map is distorted by
  /// the front end's drift across its window, so the transform that fits the whole window is not
  /// the one that fits the neighbourhood of b's scans, which is what the corrected trajectory
  /// needs (docs/results.md: intel 0.0203 -> 0.0186 m).
  std::string points = "scans";
  /// When the refinement of "scans" fails for want of usable points (a key map of one or two
  /// scans, a partial overlap), it is run again on b's returns together with those of the
  /// robot's preceding key maps within this much path [m] (the scans b's cells were made of,
  /// placed by the front end), at most `max_points` returns. 0: off, the default: measured on
  /// the robustness matrix at 7.5 and 3 m, it moves large loops both ways (docs/robustness.md,
  /// "Round 19").
  double window_travel = 0.0;
  template <class V>
  void Visit(V& v) {
    v("enabled", enabled, "Refine accepted alignments on the distance field");
    v("max_iterations", max_iterations, "Gauss-Newton iterations [-]");
    v("huber", huber, "Huber kernel width [m]");
    v("max_distance", max_distance, "Points farther than this from obstacles are ignored [m]");
    v("max_points", max_points, "Points used at most [-]");
    v("min_points", min_points, "Minimum usable points [-]");
    v("max_step", max_step, "Refinement may move the transform at most this far [m]");
    v("points", points, "Points of b refined: key_map (obstacle cells) or scans (its returns)");
    v("window_travel", window_travel,
      "Too few usable returns: add the preceding key maps' returns within this path [m]; 0 off");
  }
  [[nodiscard]] Status Validate() const;
};

struct RefinementResult {
  bool ok = false;
  Pose2 T_a_b;                                        ///< Refined transform.
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();  ///< J^T W J at the solution, per point.
  double rms = 0.0;                                   ///< RMS distance of the used points [m].
  double inlier_fraction = 0.0;  ///< Used points within `huber` of an obstacle [-].
  /// Points used at the solution; when not ok, at the last linearization (fewer than
  /// min_points: the refinement failed for want of points).
  int points = 0;
  int iterations = 0;
};

/// Refines T_a_b (p_a = T_a_b * p_b). `distance_a`: metres to the nearest obstacle of a, negative
/// on unknown cells (matching::kUnknownDistance). Deterministic; thread-safe.
RefinementResult RefineOnDistanceField(std::span<const Eigen::Vector2d> points_b,
                                       const Grid2D<float>& distance_a, const Pose2& T_a_b,
                                       const RefinementOptions& options);

}  // namespace gridslam::loop_closure
