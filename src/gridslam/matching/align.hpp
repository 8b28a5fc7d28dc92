// Alignment of two key maps with no initial guess (docs/design.md §1.5; docs/method.md
// §1.5.2–1.5.3, done as its recommendations say rather than as the authors' code): descriptor
// matching, 2-point RANSAC, least-squares refinement (the refined transform is the measurement), an
// information matrix from the fit, then verification by grid agreement, which guards against
// perceptual aliasing. The result T_a_b is the pose of key map b's frame in key map a's frame,
// p_a = T_a_b * p_b: the g2o EDGE_SE2 measurement of an edge from a to b.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/matching/descriptor_matcher.hpp"
#include "gridslam/matching/feature_set.hpp"
#include "gridslam/matching/grid_verification.hpp"
#include "gridslam/matching/rigid_fit.hpp"
#include "gridslam/matching/rigid_ransac.hpp"

namespace gridslam::matching {

struct AlignOptions {
  DescriptorMatchOptions descriptors;
  RansacOptions ransac;
  InformationOptions information;
  VerificationOptions verification;
  /// Minimum inliers of the refined transform (the authors use 5 for consecutive key maps and
  /// 6 for loop closures) [-].
  int min_inliers = 6;
  /// Minimum standard deviation of the inliers (in b) along their minor principal axis [m]:
  /// rejects coincident or collinear inlier sets, typical of corridor aliasing.
  double min_inlier_spread = 0.05;

  template <class V>
  void Visit(V& v) {
    v("min_inliers", min_inliers, "Minimum inliers of the refined transform [-]");
    v("min_inlier_spread", min_inlier_spread,
      "Minimum spread of the inliers across their principal axis [m]");
    v.Section("descriptors", descriptors, "Descriptor matching (mutual NN, ratio, Laplacian)");
    v.Section("ransac", ransac, "2-point RANSAC and least-squares refinement");
    v.Section("information", information, "Information matrix of the alignment");
    v.Section("verification", verification, "Verification by grid agreement");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(min_inliers >= 2, "matching.min_inliers >= 2"));
    GRIDSLAM_RETURN_IF_ERROR(Require(min_inlier_spread >= 0.0, "matching.min_inlier_spread >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(descriptors.Validate());
    GRIDSLAM_RETURN_IF_ERROR(ransac.Validate());
    GRIDSLAM_RETURN_IF_ERROR(information.Validate());
    GRIDSLAM_RETURN_IF_ERROR(verification.Validate());
    return Status::Ok();
  }
};

/// Why an alignment was rejected, in the order the stages run.
enum class RejectReason {
  kNone,               ///< Accepted.
  kTooFewMatches,      ///< Fewer than 2 (or than min_inliers) descriptor matches.
  kNoHypothesis,       ///< No pair of matches passed the 2-point pre-checks.
  kTooFewInliers,      ///< The refined transform has fewer than min_inliers inliers.
  kDegenerateInliers,  ///< Inliers coincident or collinear (min_inlier_spread).
  kTooLittleOverlap,   ///< Verification: too few obstacle points in the overlap.
  kGridDisagreement,   ///< Verification: too little agreement or too much contradiction.
};
const char* ToString(RejectReason reason);

struct AlignResult {
  bool accepted = false;
  RejectReason reason = RejectReason::kTooFewMatches;
  /// Pose of b's frame in a's frame, p_a = T_a_b * p_b. Meaningful from the estimation stage on
  /// (reason kNone, kTooFewInliers or later), even if rejected.
  Pose2 T_a_b;
  /// Information of T_a_b in (x, y, theta) order, right-perturbation (EDGE_SE2) convention, see
  /// FitInformation; zero unless at least 2 inliers.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  std::vector<Match> matches;       ///< Putative descriptor matches.
  std::vector<int> inliers;         ///< Indices into `matches`: inliers of T_a_b.
  double rms_residual = 0.0;        ///< RMS inlier residual of T_a_b [m].
  int hypotheses = 0;               ///< 2-point hypotheses drawn or enumerated.
  bool verified = false;            ///< The grid verification ran.
  double agreement = 0.0;           ///< Verification: smallest agreeing fraction [-].
  double contradiction = 1.0;       ///< Verification: largest contradicting fraction [-].
  int overlap = 0;                  ///< Verification: smallest overlap [points].
  VerificationResult verification;  ///< Details of both directions.
};

/// Aligns key map b to key map a. `verify` (may be null) adds the grid verification
/// (options.verification.enabled). Contract: options valid, feature sets consistent and of the
/// same descriptor type (checked, fatal). Deterministic; thread-safe.
AlignResult Align(const FeatureSet& a, const FeatureSet& b, const AlignOptions& options,
                  const VerificationInput* verify);

/// Align from given matches (e.g. from a global appearance search): the stages after matching.
AlignResult AlignMatches(const FeatureSet& a, const FeatureSet& b, std::vector<Match> matches,
                         const AlignOptions& options, const VerificationInput* verify);

}  // namespace gridslam::matching
