// The key-map alignment benchmark (docs/design.md §3.2; issue 5): how well two key maps are aligned
// with no initial guess (description/keymap_describer.hpp, matching/align.hpp), measured on
// loop closures with known answers. The front end runs over a log; the revisits among the
// benchmark's relations give positive pairs and far-apart key maps give negative pairs
// (pair_selection.hpp). Each pair's key map b is aligned to key map a from precomputed
// descriptions (matching, RANSAC, verification), accepted alignments are refined on the distance
// field (loop_closure/grid_refinement.hpp) when enabled, as the mapper does, and the result is
// compared with the truth: correct when the error is below correct_translation and
// correct_rotation_deg, grossly wrong beyond gross_translation or gross_rotation_deg. Reported:
// pairs tried, accepted, correct, accepted-but-wrong, precision (correct / accepted), recall
// (correct / pairs), median error of the correct ones, false accepts among the negatives, features
// per key map, and the time per key map (description) and per pair (alignment with features
// precomputed).
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

#include "gridslam/benchmark/align_eval_options.hpp"
#include "gridslam/benchmark/pair_selection.hpp"
#include "gridslam/common/result.hpp"
#include "gridslam/description/description_options.hpp"
#include "gridslam/eval/relation.hpp"
#include "gridslam/eval/stamped_pose.hpp"
#include "gridslam/loop_closure/grid_refinement.hpp"
#include "gridslam/matching/align.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/scan_matching/front_end_options.hpp"

namespace gridslam::benchmark {

/// Everything the benchmark is configured with (sections of SlamOptions).
struct AlignEvalConfig {
  scan_matching::FrontEndOptions front_end;
  description::DescriptionOptions description;
  matching::AlignOptions matching;
  loop_closure::RefinementOptions refinement;  ///< Used when refinement.enabled.
  AlignEvalOptions eval;
  bool relations_in_laser_frame = false;  ///< The relations describe laser, not base, poses.
};

struct AlignEvalInput {
  std::span<const Frame> frames;                    ///< The log, in order.
  std::span<const eval::Relation> relations;        ///< Its benchmark relations.
  std::span<const eval::StampedPose> ground_truth;  ///< Optional T_world_base per scan.
};

/// The outcome of one pair.
struct PairOutcome {
  TestPair pair;
  bool positive = true;
  bool accepted = false;
  matching::RejectReason reason = matching::RejectReason::kTooFewMatches;
  Pose2 T_a_b_aligned;  ///< The aligner's transform.
  Pose2 T_a_b;          ///< The measurement: refined if refinement ran and succeeded.
  bool refined = false;
  int features_a = 0;
  int features_b = 0;
  int matches = 0;
  int inliers = 0;
  double agreement = 0.0;
  double contradiction = 0.0;
  /// Errors of T_a_b and of T_a_b_aligned [m], [rad] (negatives: against an approximate truth);
  /// correct: accepted and T_a_b within the limits.
  double error_translation = 0.0;
  double error_rotation = 0.0;
  double error_translation_aligned = 0.0;
  double error_rotation_aligned = 0.0;
  bool correct = false;
  /// Accepted with an error beyond gross_translation or gross_rotation_deg (for negatives: a
  /// false accept).
  bool gross = false;
  double seconds_align = 0.0;  ///< Matching + RANSAC + verification.
  double seconds_refine = 0.0;
};

struct AlignEvalSummary {
  long pairs = 0;
  long accepted = 0;
  long correct = 0;
  long wrong = 0;               ///< Accepted but wrong.
  long gross_wrong = 0;         ///< Accepted and grossly wrong (part of `wrong`).
  long correct_aligned = 0;     ///< Accepted with the aligner's transform already within limits.
  double precision = 0.0;       ///< correct / accepted (NaN if nothing accepted).
  double recall = 0.0;          ///< correct / pairs (NaN if no pairs).
  double median_error_m = 0.0;  ///< Over the correct pairs (NaN if none).
  double median_error_deg = 0.0;
  double median_error_aligned_m = 0.0;  ///< The aligner's error over the correct pairs.
  double median_error_aligned_deg = 0.0;
  long negatives = 0;
  long negatives_accepted = 0;       ///< Accepted negatives, false or (rarely) near the truth.
  long false_accepts = 0;            ///< Accepted negatives far from the truth.
  double features_per_keymap = 0.0;  ///< Mean over the described key maps.
  double features_median = 0.0;
  long described = 0;          ///< Key maps described.
  double ms_per_keymap = 0.0;  ///< Description (distance transform + features), mean.
  double ms_distance_per_keymap = 0.0;
  double ms_features_per_keymap = 0.0;
  double ms_per_pair = 0.0;  ///< Alignment with features precomputed, mean over all pairs.
  double ms_per_pair_median = 0.0;
  double ms_refine_per_accept = 0.0;     ///< Refinement, mean over refined alignments.
  std::map<std::string, long> rejected;  ///< Positives rejected, by RejectReason.
};

struct AlignEvalReport {
  long frames = 0;
  long key_maps = 0;
  double seconds_front_end = 0.0;  ///< One front-end run over the log.
  PositiveSelection selection;     ///< Counts only (pairs are in `positives`).
  long negative_candidates = 0;
  bool negatives_from_ground_truth = false;
  std::vector<PairOutcome> positives;
  std::vector<PairOutcome> negatives;
  AlignEvalSummary summary;
};

/// Runs the benchmark. Errors: InvalidInput for invalid options or an empty log; Runtime if the
/// front end is not deterministic (its second run hands out different key maps).
Result<AlignEvalReport> RunAlignEval(const AlignEvalInput& input, const AlignEvalConfig& config);

/// The pair statistics of a summary (every field but the description's: features_*, described,
/// ms_*_per_keymap), from a set of outcomes.
AlignEvalSummary Summarize(std::span<const PairOutcome> positives,
                           std::span<const PairOutcome> negatives);

}  // namespace gridslam::benchmark
