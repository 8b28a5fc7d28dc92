// Test pairs of the key-map alignment benchmark (docs/design.md §3.2; issue 5).
//
// Positive pairs come from the benchmark's relations (Kümmerle et al. 2009): a relation whose
// scans are more than min_time_gap apart is a revisit with a known answer. Its key maps a (holding
// the scan at t1) and b (holding the scan at t2) are related by
//   T_a_b = T_a_base(t1) * T_1_2 * T_b_base(t2)^-1,   T_k_base(t) = T_odom_k^-1 * T_odom_base(t),
// the relation T_1_2 carrying the truth across the loop and the locally consistent front end
// placing each scan in its key map. The pair is tested when the key maps overlap
// (|T_a_b.translation()| <= max_centre_distance, the distance of the window centres) and, unless
// include_shared, when the local map forgot a's cells before b was taken (so both key maps are
// built from different data). The truth rests on the front end being locally accurate, which is
// checked against the short relations around both scans (truth_check_*): pairs where it is not
// are left out. Each key-map pair is tested once; when several relations give it, its truth is
// their component-wise median (the relations' own noise, a few centimetres and tenths of a degree
// on the real logs, is then partly averaged out, and its spread is reported).
//
// Negative pairs have no correct answer: key maps whose true centres are farther apart than
// negative_min_distance (with 15 m windows and a 20 m default their windows cannot overlap), drawn
// at random. True centres come from ground truth (T_world_base per scan, e.g. a simulator's
// robot_<i>.gt.txt) when given; otherwise from the front end, allowing negative_drift per metre
// travelled between the key maps.
#pragma once

#include <span>
#include <vector>

#include "gridslam/benchmark/align_eval_options.hpp"
#include "gridslam/benchmark/key_map_catalog.hpp"
#include "gridslam/eval/relation.hpp"
#include "gridslam/eval/stamped_pose.hpp"

namespace gridslam::benchmark {

struct TestPair {
  int key_a = 0;  ///< Key map aligned to (the one around t1).
  int key_b = 0;  ///< Key map aligned (the one around t2).
  /// The true T_a_b (negatives: from ground truth, or the front end's estimate, which drifts)
  /// and, for positives, the (first) relation's timestamps.
  Pose2 T_a_b_true;
  Time t1;
  Time t2;
  /// Distance between the key maps' centres (true, or the front end's for negatives without
  /// ground truth) [m].
  double centre_distance = 0.0;
  /// Positive pairs: relations giving this key-map pair, and the largest difference between the
  /// truth one of them gives and T_a_b_true (the truth's own uncertainty) [m], [rad].
  int relations = 0;
  double truth_spread_translation = 0.0;
  double truth_spread_rotation = 0.0;
  /// Positive pairs: short relations checking the front end around t1 and t2, and the largest
  /// front-end error among them [m], [rad].
  int truth_checks = 0;
  double truth_error_translation = 0.0;
  double truth_error_rotation = 0.0;
};

struct PositiveSelection {
  std::vector<TestPair> pairs;
  long relations = 0;     ///< Relations read.
  long revisits = 0;      ///< Of them, with |t2 - t1| > min_time_gap.
  long missing_scan = 0;  ///< Revisits with a timestamp matching no scan.
  long same_key_map = 0;  ///< Revisits with both scans in one key map.
  long too_far = 0;       ///< Revisits whose key maps' centres are too far apart.
  long shared = 0;        ///< Revisits whose key maps share local-map data (skipped).
  long unreliable = 0;    ///< Revisits where the front end was locally inaccurate (skipped).
  long unchecked = 0;     ///< Pairs tested without a short relation to check the front end.
  long duplicates = 0;    ///< Revisits of a key-map pair already tested.
};

/// Positive pairs (see above). `relations_in_laser_frame`: the relations describe laser poses.
PositiveSelection SelectPositives(const KeyMapCatalog& catalog,
                                  std::span<const eval::Relation> relations,
                                  const AlignEvalOptions& options, bool relations_in_laser_frame);

struct NegativeSelection {
  std::vector<TestPair> pairs;  ///< Sorted by (key_a, key_b).
  long candidates = 0;          ///< Key-map pairs far enough apart to be negatives.
  bool from_ground_truth = false;
  int key_maps_with_truth = 0;  ///< Key maps whose true centre is known (ground truth only).
};

/// Up to options.negatives negative pairs, drawn uniformly (reservoir sampling, options.seed)
/// among all candidates. `ground_truth`: T_world_base per scan time, may be empty.
NegativeSelection SelectNegatives(const KeyMapCatalog& catalog,
                                  std::span<const eval::StampedPose> ground_truth,
                                  const AlignEvalOptions& options);

}  // namespace gridslam::benchmark
