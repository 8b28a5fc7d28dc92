// Options of the scan-to-local-map matcher (scan_matcher.hpp) and of its correlative search.
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/options.hpp"

namespace gridslam::scan_matching {

struct ScanMatcherOptions {
  /// "distance_field": the bilinearly interpolated distance to the nearest obstacle cell;
  /// "point_to_line": residual along the map cell's surface normal, to the mean hit point of the
  /// nearest obstacle cell (point-to-point where the normal is ill-defined). docs/front_end.md
  /// compares them: point_to_line is slightly more precise locally but drifts more.
  std::string residual = "distance_field";
  double max_correspondence_distance = 0.3;  ///< Truncation of the distance field [m].
  /// Robust (Cauchy) scales of the successive stages [m]; each stage iterates to convergence.
  std::vector<double> robust_scales = {0.15, 0.05};
  int max_iterations = 10;    ///< Gauss-Newton iterations per stage.
  double point_sigma = 0.03;  ///< Standard deviation of one point's residual [m].
  /// Normals less consistent than this (0..1) are not used: a map cell's for point_to_line, a
  /// scan point's (which restricts the distance gradient to it) for distance_field.
  double min_planarity = 0.5;
  double convergence_translation = 1e-4;  ///< Stop when a step is smaller [m] ...
  double convergence_rotation = 1e-4;     ///< ... and [rad].
  int min_points = 20;                    ///< Fewer returns: the frame falls back to odometry.
  int min_correspondences = 15;           ///< Fewer matched points: the match is rejected.
  /// A translation direction is degenerate when the points constraining it (the scan's Hessian
  /// times point_sigma^2, yaw marginalized: an inlier on a wall facing the direction counts about
  /// one) are fewer than this fraction of the matched points; the odometry prior then carries the
  /// estimate along it (degeneracy.hpp). A fraction, not a count, so that the test is one of the
  /// scene's geometry, not of the laser's beam density. A long corridor's axis collects 0.1-2 %;
  /// chosen on the whole robustness matrix (docs/robustness.md). 0 disables [-].
  double degenerate_fraction = 0.02;
  double inlier_distance = 0.1;  ///< Points this close to the map count in the score [m].
  double good_score = 0.5;  ///< A score below this after refining the prior triggers the search.
  bool correlative_search = true;       ///< Enable the coarse search for poor priors.
  double search_linear_window = 0.3;    ///< Half-width of the search in x and y [m].
  double search_angular_window = 0.25;  ///< Half-width of the search in yaw [rad].
  double search_angular_step = 0.0175;  ///< Yaw step of the search [rad].
  int search_linear_step = 2;           ///< Translation step of the search [cells].
  double search_sigma = 0.1;            ///< Width of the search's Gaussian score of a point [m].

  template <class V>
  void Visit(V& v) {
    v("residual", residual, "distance_field (default) or point_to_line");
    v("max_correspondence_distance", max_correspondence_distance,
      "Truncation of the distance field: farther points have no correspondence [m]");
    v("robust_scales", robust_scales,
      "Cauchy kernel scales of the successive Gauss-Newton stages [m]");
    v("max_iterations", max_iterations, "Gauss-Newton iterations per stage");
    v("point_sigma", point_sigma, "Standard deviation of one point's residual [m]");
    v("min_planarity", min_planarity,
      "Normals less consistent than this (0..1) are not used (map cells' for point_to_line, "
      "scan points' for distance_field)");
    v("convergence_translation", convergence_translation, "Convergence threshold [m]");
    v("convergence_rotation", convergence_rotation, "Convergence threshold [rad]");
    v("min_points", min_points, "Scans with fewer returns fall back to odometry");
    v("min_correspondences", min_correspondences,
      "Matches with fewer matched points are rejected (fall back to odometry)");
    v("degenerate_fraction", degenerate_fraction,
      "Translation directions constrained by fewer than this fraction of the matched points are "
      "left to the odometry prior (degenerate, e.g. along a corridor); 0 disables [-]");
    v("inlier_distance", inlier_distance, "Points this close to the map count in the score [m]");
    v("good_score", good_score,
      "Below this score (fraction of points near the map) the correlative search runs");
    v("correlative_search", correlative_search, "Enable the correlative search for poor priors");
    v("search_linear_window", search_linear_window, "Half-width of the search in x and y [m]");
    v("search_angular_window", search_angular_window, "Half-width of the search in yaw [rad]");
    v("search_angular_step", search_angular_step, "Yaw step of the search [rad]");
    v("search_linear_step", search_linear_step, "Translation step of the search [cells]");
    v("search_sigma", search_sigma, "Width of a point's Gaussian score in the search [m]");
  }
  [[nodiscard]] Status Validate() const;
};

}  // namespace gridslam::scan_matching
