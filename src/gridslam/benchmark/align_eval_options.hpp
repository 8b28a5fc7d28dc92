// Options of the key-map alignment benchmark (docs/design.md §3.2; issue 5): which relations of a
// log become test pairs, when an alignment counts as correct, and how negative pairs (no correct
// answer exists) are drawn. Header-only so that SlamOptions can hold it without a link
// dependency.
#pragma once

#include "gridslam/common/options.hpp"

namespace gridslam::benchmark {

struct AlignEvalOptions {
  /// Relations with |t2 - t1| above this are revisits (loop closures) [s].
  double min_time_gap = 30.0;
  /// A relation timestamp finds its scan when they differ by at most this [s].
  double time_tolerance = 0.001;
  /// Overlap criterion: a revisit is a test pair when the true distance between the two key
  /// maps' centres (window centres) is at most this. With 15 m windows and the robot within
  /// about 1 m of its window's centre, 4 m keeps at least (11/15)^2 = 54 % of the windows'
  /// areas in common [m].
  double max_centre_distance = 4.0;
  /// Also test pairs whose windows never separated between t1 and t2 (the local map kept cells
  /// from t1 until t2, so the two key maps share data and are not independent) [-].
  bool include_shared = false;
  /// Check of the truth: the front end must be locally accurate where the two key maps were
  /// built. The short relations (|t2 - t1| <= truth_check_max_dt) lying within
  /// truth_check_history before a pair's scan and the end of its key map are compared with the
  /// front end; a pair is tested only if its largest error stays within truth_max_error and
  /// truth_max_error_deg (e.g. a front end sliding along a featureless corridor moves the robot
  /// against its map, which makes the truth of T_a_b meaningless). The defaults equal the
  /// correctness limits: where the front end is off by that much, the truth cannot tell a correct
  /// alignment from a wrong one [s], [s], [m], [deg].
  double truth_check_max_dt = 10.0;
  double truth_check_history = 30.0;
  double truth_max_error = 0.1;
  double truth_max_error_deg = 1.0;
  /// An accepted alignment is correct when its error is below both limits [m], [deg].
  double correct_translation = 0.1;
  double correct_rotation_deg = 1.0;
  /// An accepted alignment is grossly wrong when its error exceeds either limit: an error far
  /// beyond the truth's own uncertainty, which would damage a pose graph [m], [deg].
  double gross_translation = 0.5;
  double gross_rotation_deg = 5.0;
  /// Negative pairs drawn at random (0 = none) among key maps whose true centres are farther
  /// apart than negative_min_distance [-], [m].
  int negatives = 0;
  double negative_min_distance = 20.0;
  /// Without ground truth, centres come from the front end, whose drift is allowed for: a pair
  /// is negative when the front end puts its centres farther apart than negative_min_distance
  /// plus this much per metre travelled between them [m/m].
  double negative_drift = 0.05;
  /// Seed of the negative-pair draw [-].
  int seed = 1;

  template <class V>
  void Visit(V& v) {
    v("min_time_gap", min_time_gap, "Relations with |t2 - t1| above this are revisits [s]");
    v("time_tolerance", time_tolerance, "Largest |relation time - scan time| that matches [s]");
    v("max_centre_distance", max_centre_distance,
      "Overlap criterion: true key-map centres at most this far apart [m]");
    v("include_shared", include_shared,
      "Also test pairs whose local-map windows never separated between t1 and t2");
    v("truth_check_max_dt", truth_check_max_dt,
      "Truth check: relations at most this long check the front end [s]");
    v("truth_check_history", truth_check_history,
      "Truth check: relations this long before a pair's scan are checked [s]");
    v("truth_max_error", truth_max_error,
      "Truth check: largest front-end translation error allowed near a pair [m]");
    v("truth_max_error_deg", truth_max_error_deg,
      "Truth check: largest front-end rotation error allowed near a pair [deg]");
    v("correct_translation", correct_translation, "Correct: translation error below this [m]");
    v("correct_rotation_deg", correct_rotation_deg, "Correct: rotation error below this [deg]");
    v("gross_translation", gross_translation, "Grossly wrong: translation error above this [m]");
    v("gross_rotation_deg", gross_rotation_deg, "Grossly wrong: rotation error above this [deg]");
    v("negatives", negatives, "Random negative pairs (true centres far apart); 0 = none");
    v("negative_min_distance", negative_min_distance,
      "Negative pairs: true key-map centres farther apart than this [m]");
    v("negative_drift", negative_drift,
      "Without ground truth: front-end drift allowed per metre travelled [m/m]");
    v("seed", seed, "Seed of the negative-pair draw");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(min_time_gap >= 0.0, "align_eval.min_time_gap >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(time_tolerance >= 0.0, "align_eval.time_tolerance >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(max_centre_distance > 0.0, "align_eval.max_centre_distance > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(truth_check_max_dt >= 0.0, "align_eval.truth_check_max_dt >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(truth_check_history >= 0.0, "align_eval.truth_check_history >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(truth_max_error > 0.0, "align_eval.truth_max_error > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(truth_max_error_deg > 0.0, "align_eval.truth_max_error_deg > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(correct_translation > 0.0, "align_eval.correct_translation > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(correct_rotation_deg > 0.0, "align_eval.correct_rotation_deg > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(gross_translation >= correct_translation,
                                     "align_eval.gross_translation >= correct_translation"));
    GRIDSLAM_RETURN_IF_ERROR(Require(gross_rotation_deg >= correct_rotation_deg,
                                     "align_eval.gross_rotation_deg >= correct_rotation_deg"));
    GRIDSLAM_RETURN_IF_ERROR(Require(negatives >= 0, "align_eval.negatives >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(negative_min_distance > 0.0, "align_eval.negative_min_distance > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(negative_drift >= 0.0, "align_eval.negative_drift >= 0"));
    return Status::Ok();
  }
};

}  // namespace gridslam::benchmark
