// Options of the front end (front_end.hpp): its local map, scan matcher, key maps, the motion
// filter deciding which scans are inserted, and the odometry model of the matcher's prior.
#pragma once

#include "gridslam/common/options.hpp"
#include "gridslam/grid/local_map_options.hpp"
#include "gridslam/keymap/key_map_builder.hpp"
#include "gridslam/scan_matching/match_score_monitor.hpp"
#include "gridslam/scan_matching/motion_check.hpp"
#include "gridslam/scan_matching/scan_matcher_options.hpp"

namespace gridslam::scan_matching {

/// The wide search run when the odometry is missing and the constant velocity explains the scan
/// poorly, or when a match with odometry is poor (poor_match below)
/// (correlative_search.hpp): a coarse lattice of +-linear_window, +-angular_window around the
/// prediction; the best `candidates` distinct lattice poses are refined and the best-scoring
/// refinement wins if it explains the scan clearly better.
struct WideSearchOptions {
  bool enabled = true;
  double linear_window = 1.0;      ///< Half-width in x and y [m].
  int linear_step = 3;             ///< Lattice step [cells] (within Gauss-Newton's basin).
  double angular_window = 1.5708;  ///< Half-width in yaw [rad].
  double angular_step = 0.035;     ///< Lattice step [rad].
  double sigma = 0.15;             ///< Width of a point's Gaussian score [m].
  int max_points = 90;             ///< Points scored per lattice pose [-].
  int candidates = 5;              ///< Distinct lattice maxima refined [-].

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled, "Search widely when there is no odometry and the match is poor");
    v("linear_window", linear_window, "Half-width of the wide search in x and y [m]");
    v("linear_step", linear_step, "Translation step of its lattice [cells]");
    v("angular_window", angular_window, "Half-width of the wide search in yaw [rad]");
    v("angular_step", angular_step, "Yaw step of its lattice [rad]");
    v("sigma", sigma, "Width of a point's Gaussian score in the wide search [m]");
    v("max_points", max_points, "Points scored per lattice pose [-]");
    v("candidates", candidates, "Distinct lattice maxima refined by Gauss-Newton [-]");
  }
};

struct FrontEndOptions {
  bool match = true;  ///< false: poses are raw odometry (the baseline), the map is still built.
  LocalMapOptions local_map;
  ScanMatcherOptions matcher;
  keymap::KeyMapOptions keymap;
  double insert_distance = 0.05;  ///< Insert a scan when the robot moved this far [m] ...
  double insert_angle = 0.03;     ///< ... or turned this much [rad] ...
  double insert_period = 5.0;     ///< ... or this much time passed since the last insertion [s].
  /// Odometry prior of the matcher: standard deviations of the predicted pose, a floor plus a
  /// part proportional to the motion since the previous scan.
  double odometry_sigma_forward = 0.05;  ///< Along the robot's heading [m].
  double odometry_sigma_lateral = 0.05;  ///< Sideways (a wheeled robot hardly slips) [m].
  double odometry_sigma_theta = 0.05;    ///< [rad]
  double odometry_drift_xy = 0.2;        ///< [m per m travelled]
  double odometry_drift_theta = 0.2;     ///< [rad per rad turned]
  /// Scale the yaw prior to the odometry at hand (odometry_noise.hpp): the yaw std above is
  /// multiplied by the robust RMS of the last `adaptive_window` matches' yaw corrections in units
  /// of that std, clamped to [adaptive_min_scale, 1]. Translation is not adapted.
  bool adaptive_odometry = true;
  int adaptive_window = 200;  ///< [matched scans]
  /// The floor only keeps the prior finite: the corrections include the matcher's own error, so
  /// the scale cannot fall below what odometry and matcher disagree by. 0.1 let fr-clinic's
  /// near-exact odometry yaw random-walk by 0.005 rad per scan (docs/front_end.md) [-].
  double adaptive_min_scale = 0.02;
  /// Plausibility of each odometry increment against the recent motion (motion_check.hpp).
  MotionCheckOptions odometry_check;
  WideSearchOptions wide_search;
  /// When a match with odometry is poor against the recent matches, the wide search runs
  /// around the odometry's prediction (match_score_monitor.hpp).
  PoorMatchOptions poor_match;
  double max_correction_xy = 0.5;      ///< Larger corrections of the prediction are rejected [m].
  double max_correction_theta = 0.35;  ///< [rad]

  template <class V>
  void Visit(V& v) {
    v("match", match, "Match scans (false: raw odometry poses, for baselines)");
    v.Section("local_map", local_map, "Rolling-window local occupancy map (docs/design.md §1.3)");
    v.Section("matcher", matcher, "Scan-to-local-map matcher (docs/design.md §1.2)");
    v.Section("keymap", keymap, "Key-map selection (docs/design.md §1.3)");
    v("insert_distance", insert_distance, "Insert a scan after this much travel [m]");
    v("insert_angle", insert_angle, "... or this much rotation [rad]");
    v("insert_period", insert_period, "... or this much time [s]");
    v("odometry_sigma_forward", odometry_sigma_forward,
      "Prior: std of a prediction along the robot's heading [m]");
    v("odometry_sigma_lateral", odometry_sigma_lateral,
      "Prior: std of a prediction across the robot's heading [m]");
    v("odometry_sigma_theta", odometry_sigma_theta, "Prior: yaw std of a prediction [rad]");
    v("odometry_drift_xy", odometry_drift_xy, "Prior: added position std per metre [m/m]");
    v("odometry_drift_theta", odometry_drift_theta, "Prior: added yaw std per radian [rad/rad]");
    v("adaptive_odometry", adaptive_odometry,
      "Scale the yaw prior by the recent agreement of odometry and scan matching");
    v("adaptive_window", adaptive_window, "... over this many matched scans [-]");
    v("adaptive_min_scale", adaptive_min_scale, "... never below this fraction of the yaw std [-]");
    v.Section("odometry_check", odometry_check,
              "Plausibility of each odometry increment against the recent motion");
    v.Section("wide_search", wide_search,
              "Wide correlative search when the odometry is doubtful or missing");
    v.Section("poor_match", poor_match,
              "Wide search when a match with odometry is poor against the recent ones");
    v("max_correction_xy", max_correction_xy,
      "Matches moving the prediction farther are rejected (odometry fallback) [m]");
    v("max_correction_theta", max_correction_theta, "... or turning it more [rad]");
  }
  [[nodiscard]] Status Validate() const;
};

}  // namespace gridslam::scan_matching
