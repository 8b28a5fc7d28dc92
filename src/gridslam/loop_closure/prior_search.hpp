// Correlative search for a loop closure around a predicted transform (docs/design.md §1.6), for the
// key maps whose feature alignment fails (sparse maps: open halls, rows of poles) while the
// graph's prediction is off by more than the distance-field refinement's basin (about the
// refinement's max_distance). After a long loop the prediction's error grows with the path
// length between the key maps; the search window does too: every pose on a regular grid of
// translations (linear_step) and rotations (angular_step) within the window is scored by the
// mean truncated distance of b's obstacle points in a's distance field, score = mean over the
// points of max(0, 1 - d / truncation) (points on a's unknown cells or outside it score 0), as
// in correlative scan matching (Olson, ICRA 2009), on a's exact distance transform. The best pose
// seeds RefineOnDistanceField. Because the window is large, the search also reports how
// distinct the best pose is: the best score among the poses farther than `distinct_distance`
// from it, so that a corridor or a row of identical bays (many equally good poses) can be refused.
#pragma once

#include <span>

#include <Eigen/Core>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::loop_closure {

struct PriorSearchOptions {
  bool enabled = true;
  /// Half-width of the translation window: this fraction of the uncertainty distance between
  /// the key maps (graph path length, a drift rate) ... [m/m]
  double window_per_m = 0.02;
  double max_window_xy = 3.0;   ///< ... capped here [m].
  double min_window_xy = 0.5;   ///< Smaller windows: the refinement alone is used [m].
  double window_theta = 0.1;    ///< Half-width of the rotation window [rad].
  double linear_step = 0.2;     ///< Translation step of the grid (rounded to cells) [m].
  double angular_step = 0.035;  ///< Rotation step [rad].
  double truncation = 0.3;      ///< Distances beyond this score 0 [m].
  int max_points = 400;         ///< b's points used at most (regular subsample) [-].
  double min_score = 0.3;       ///< Best scores below this: no match [-].
  /// The best score among poses farther than distinct_distance from the best must stay below
  /// max_ambiguity times the best [m], [-].
  double distinct_distance = 0.5;
  double max_ambiguity = 0.85;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled,
      "Search a window around the prediction when feature alignment fails and the prediction "
      "may be off by more than the refinement converges from");
    v("window_per_m", window_per_m,
      "Translation half-window per metre of uncertainty distance (drift rate) [m/m]");
    v("max_window_xy", max_window_xy, "... capped here [m]");
    v("min_window_xy", min_window_xy, "Smaller windows: refine the prediction only [m]");
    v("window_theta", window_theta, "Rotation half-window [rad]");
    v("linear_step", linear_step, "Translation step of the search grid [m]");
    v("angular_step", angular_step, "Rotation step of the search grid [rad]");
    v("truncation", truncation, "Points farther than this from an obstacle score 0 [m]");
    v("max_points", max_points, "Points of the newer key map used at most [-]");
    v("min_score", min_score, "Minimum best score (mean truncated closeness) [-]");
    v("distinct_distance", distinct_distance,
      "Poses farther than this from the best are its rivals [m]");
    v("max_ambiguity", max_ambiguity,
      "Refused when the best rival scores more than this fraction of the best [-]");
  }
  [[nodiscard]] Status Validate() const;
};

struct PriorSearchResult {
  bool ok = false;     ///< Best score >= min_score and distinct enough.
  Pose2 T_a_b;         ///< Best pose of the grid.
  double score = 0.0;  ///< Its score [-].
  double rival = 0.0;  ///< Best score farther than distinct_distance from it [-].
  long poses = 0;      ///< Poses scored.
};

/// Searches T_a_b (p_a = T_a_b * p_b) within +-window_xy [m] (translation of b's origin in a's
/// frame) and +-options.window_theta (rotation about b's origin) of `prior`. `distance_a`: metres
/// to a's nearest obstacle, negative on unknown cells. Deterministic; thread-safe.
PriorSearchResult SearchAroundPrior(std::span<const Eigen::Vector2d> points_b,
                                    const Grid2D<float>& distance_a, const Pose2& prior,
                                    double window_xy, const PriorSearchOptions& options);

}  // namespace gridslam::loop_closure
