#include "gridslam/matching/align.hpp"

#include <utility>

#include "gridslam/common/check.hpp"

namespace gridslam::matching {

const char* ToString(RejectReason reason) {
  switch (reason) {
    case RejectReason::kNone:
      return "accepted";
    case RejectReason::kTooFewMatches:
      return "too few matches";
    case RejectReason::kNoHypothesis:
      return "no valid 2-point hypothesis";
    case RejectReason::kTooFewInliers:
      return "too few inliers";
    case RejectReason::kDegenerateInliers:
      return "degenerate (collinear or coincident) inliers";
    case RejectReason::kTooLittleOverlap:
      return "too little grid overlap";
    case RejectReason::kGridDisagreement:
      return "grids disagree";
  }
  return "unknown";
}

AlignResult Align(const FeatureSet& a, const FeatureSet& b, const AlignOptions& options,
                  const VerificationInput* verify) {
  return AlignMatches(a, b, MatchDescriptors(a, b, options.descriptors), options, verify);
}

AlignResult AlignMatches(const FeatureSet& a, const FeatureSet& b, std::vector<Match> matches,
                         const AlignOptions& options, const VerificationInput* verify) {
  const Status valid = options.Validate();
  GRIDSLAM_CHECK(valid.ok()) << valid.error().ToString();
  AlignResult result;
  result.matches = std::move(matches);
  const int m = static_cast<int>(result.matches.size());
  if (m < 2 || m < options.min_inliers) {
    result.reason = RejectReason::kTooFewMatches;
    return result;
  }

  Correspondences c;
  c.a.reserve(static_cast<std::size_t>(m));
  c.b.reserve(static_cast<std::size_t>(m));
  const bool with_angles = !a.angles.empty() && !b.angles.empty();
  for (const Match& match : result.matches) {
    GRIDSLAM_CHECK(match.index_a >= 0 && match.index_a < a.size() && match.index_b >= 0 &&
                   match.index_b < b.size())
        << "match index out of range";
    const auto ia = static_cast<std::size_t>(match.index_a);
    const auto ib = static_cast<std::size_t>(match.index_b);
    c.a.push_back(a.points[ia]);
    c.b.push_back(b.points[ib]);
    if (with_angles) {
      c.rotation.push_back(a.angles[ia] - b.angles[ib]);
    }
  }

  const RansacResult ransac = EstimateRigidRansac(c, options.ransac);
  result.hypotheses = ransac.iterations;
  if (!ransac.found) {
    result.reason = RejectReason::kNoHypothesis;
    return result;
  }
  result.T_a_b = ransac.T_a_b;
  result.inliers = ransac.inliers;
  result.rms_residual = RmsResidual(c, result.inliers, result.T_a_b);
  result.information = FitInformation(c, result.inliers, result.T_a_b, options.information);
  if (static_cast<int>(result.inliers.size()) < options.min_inliers) {
    result.reason = RejectReason::kTooFewInliers;
    return result;
  }
  if (PrincipalSpread(c, result.inliers).x() < options.min_inlier_spread) {
    result.reason = RejectReason::kDegenerateInliers;
    return result;
  }

  if (verify != nullptr && options.verification.enabled) {
    result.verification = VerifyAlignment(result.T_a_b, *verify, options.verification);
    result.verified = true;
    result.agreement = result.verification.agreement;
    result.overlap = result.verification.overlap;
    result.contradiction = result.verification.contradiction;
    if (!result.verification.enough_overlap) {
      result.reason = RejectReason::kTooLittleOverlap;
      return result;
    }
    if (!result.verification.accepted) {
      result.reason = RejectReason::kGridDisagreement;
      return result;
    }
  }
  result.accepted = true;
  result.reason = RejectReason::kNone;
  return result;
}

}  // namespace gridslam::matching
