// Descriptor association between the features of two key maps (docs/design.md §1.5; docs/method.md
// §1.5.2 and §2.6). Brute force over the full distance matrix (one GEMM for float descriptors,
// popcount for binary ones), gated by the sign of the Laplacian (Bay et al. 2008 §4.1: only blobs
// of the same contrast can match) and optionally by keypoint scale, then a cross-check (strict
// mutual nearest neighbours by default; k > 1 reproduces the authors' relaxed 3-NN cross-check)
// and an optional Lowe ratio test applied in both directions, so that swapping a and b swaps the
// matches. Deterministic; single-threaded.
#pragma once

#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/matching/feature_set.hpp"

namespace gridslam::matching {

struct DescriptorMatchOptions {
  /// Cross-check: 1 = mutual nearest neighbours; k > 1 = accept the first of a's k nearest in
  /// b that has a among its own k nearest (the authors' code uses k = 3); 0 = no cross-check
  /// (every a feature keeps its nearest neighbour in b).
  int cross_check_k = 1;
  /// Lowe's ratio test: keep a match only if its distance is below max_ratio times the second
  /// smallest distance of its row (and of its column when cross-checking); >= 1 disables it.
  double max_ratio = 0.9;
  /// Compare only features with the same sign of the Laplacian (when both sets carry it).
  bool use_laplacian_sign = true;
  /// Compare only features whose scales differ by at most this factor (both key maps have the
  /// same resolution, so true matches have similar scales); 0 disables the gate.
  double max_scale_ratio = 0.0;
  /// Reject matches whose descriptor distance exceeds this; 0 disables it.
  double max_descriptor_distance = 0.0;

  template <class V>
  void Visit(V& v) {
    v("cross_check_k", cross_check_k,
      "Cross-check: 1 = mutual nearest neighbours, k > 1 = authors' k-NN cross-check, 0 = none");
    v("max_ratio", max_ratio, "Lowe ratio test threshold d1/d2 (>= 1 disables) [-]");
    v("use_laplacian_sign", use_laplacian_sign,
      "Match only features with the same sign of the Laplacian");
    v("max_scale_ratio", max_scale_ratio,
      "Match only features whose scales differ by at most this factor (0 disables) [-]");
    v("max_descriptor_distance", max_descriptor_distance,
      "Reject matches with a larger descriptor distance (0 disables) [descriptor units]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(cross_check_k >= 0 && cross_check_k <= 16,
                                     "matching.descriptors.cross_check_k in [0, 16]"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_ratio > 0.0, "matching.descriptors.max_ratio > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_scale_ratio == 0.0 || max_scale_ratio >= 1.0,
                                     "matching.descriptors.max_scale_ratio is 0 or >= 1"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_descriptor_distance >= 0.0,
                                     "matching.descriptors.max_descriptor_distance >= 0"));
    return Status::Ok();
  }
};

/// Putative matches between `a` and `b`, sorted by index_a, at most one per feature of a (and,
/// with cross_check_k == 1, at most one per feature of b).
/// Contract: both sets consistent (FeatureSetError empty) with the same descriptor type and
/// length unless one of them is empty (checked, fatal). Empty sets give no matches.
std::vector<Match> MatchDescriptors(const FeatureSet& a, const FeatureSet& b,
                                    const DescriptorMatchOptions& options);

}  // namespace gridslam::matching
