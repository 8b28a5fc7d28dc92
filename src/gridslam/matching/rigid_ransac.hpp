// Robust SE(2) estimation from putative point matches (docs/design.md §1.5; docs/method.md §1.5.3).
// Hypotheses come from two matches: the rotation aligns b_i - b_j with a_i - a_j and the
// translation maps the pair's midpoint, so both members have the same residual. Pairs closer than
// `min_pair_separation` are skipped, as are pairs whose lengths differ by more than
// 2 * inlier_radius (both members could not be inliers; the authors' test, fixed) and, when
// keypoint orientations are known, pairs whose orientations disagree with the rotation. Few
// matches: every pair is tried (the authors' exhaustive search, O(M^3)); otherwise RANSAC with
// the adaptive iteration count N = log(1 - p) / log(1 - w^2) (Hartley & Zisserman §4.7.1) from a
// fixed seed. Hypotheses are ranked by inlier count, ties by the smaller sum of squared inlier
// residuals. The best one is refined by least squares on its inliers and re-scored
// `refine_iterations` times; the refined transform is the result.
#pragma once

#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/matching/rigid_fit.hpp"

namespace gridslam::matching {

struct RansacOptions {
  /// A match is an inlier when |a - T_a_b * b| is below this [m] (4 cells of 5 cm, as the
  /// authors' code).
  double inlier_radius = 0.2;
  /// Two matches form a hypothesis only if their points are at least this far apart in both
  /// maps [m] (10 cells of 5 cm, as the authors' code).
  double min_pair_separation = 0.5;
  /// With keypoint orientations on both sides: skip a hypothesis whose rotation differs from
  /// either match's orientation difference by more than this [rad]; 0 disables the check.
  double max_orientation_difference = 0.5;
  /// Up to this many matches every pair is tried; above it, random sampling.
  int exhaustive_max_matches = 40;
  /// Upper bound of sampled hypotheses (RANSAC mode).
  int max_iterations = 1000;
  /// Probability of drawing at least one all-inlier pair, for the adaptive count [-].
  double confidence = 0.999;
  /// Seed of the sampler (std::mt19937): runs are deterministic.
  int seed = 42;
  /// Least-squares refinement rounds on the inliers (each: fit, then re-select inliers).
  int refine_iterations = 2;

  template <class V>
  void Visit(V& v) {
    v("inlier_radius", inlier_radius, "Inlier distance after transforming b into a [m]");
    v("min_pair_separation", min_pair_separation,
      "Minimum distance between the two points of a 2-point hypothesis [m]");
    v("max_orientation_difference", max_orientation_difference,
      "Keypoint orientation consistency of a hypothesis (0 disables) [rad]");
    v("exhaustive_max_matches", exhaustive_max_matches,
      "Try every pair up to this many matches, else RANSAC [-]");
    v("max_iterations", max_iterations, "Maximum RANSAC hypotheses [-]");
    v("confidence", confidence, "RANSAC success probability for the adaptive count [-]");
    v("seed", seed, "RANSAC random seed [-]");
    v("refine_iterations", refine_iterations, "Least-squares refinement rounds on the inliers [-]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(inlier_radius > 0.0, "matching.ransac.inlier_radius > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(min_pair_separation >= 0.0, "matching.ransac.min_pair_separation >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_orientation_difference >= 0.0,
                                     "matching.ransac.max_orientation_difference >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(exhaustive_max_matches >= 0, "matching.ransac.exhaustive_max_matches >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_iterations >= 1, "matching.ransac.max_iterations >= 1"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(confidence > 0.0 && confidence < 1.0, "matching.ransac.confidence in (0, 1)"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(refine_iterations >= 0, "matching.ransac.refine_iterations >= 0"));
    return Status::Ok();
  }
};

struct RansacResult {
  bool found = false;          ///< A hypothesis passed the pre-checks (>= 2 inliers).
  Pose2 T_a_b;                 ///< The refined transform (p_a = T_a_b * p_b).
  Pose2 T_a_b_hypothesis;      ///< The best 2-point hypothesis, before refinement.
  std::vector<int> inliers;    ///< Indices into the correspondences, inliers of T_a_b.
  int hypothesis_inliers = 0;  ///< Inlier count of the best hypothesis.
  int iterations = 0;          ///< Pairs drawn (RANSAC) or enumerated (exhaustive).
  bool exhaustive = false;     ///< Whether every pair was tried.
};

/// Best rigid transform for the correspondences; found == false when there are fewer than two
/// of them or no pair passes the pre-checks. Deterministic for given options. Thread-safe.
RansacResult EstimateRigidRansac(const Correspondences& c, const RansacOptions& options);

}  // namespace gridslam::matching
