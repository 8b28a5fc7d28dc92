#include "gridslam/pipeline/key_map_aligner.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "gridslam/common/logging.hpp"
#include "gridslam/loop_closure/grid_refinement.hpp"

namespace gridslam::pipeline {

FeatureAligner::FeatureAligner(const KeyMapGraph& graph, const matching::AlignOptions& matching,
                               const loop_closure::LoopClosureOptions& loop_closure)
    : graph_(graph), matching_(matching), options_(loop_closure) {}

std::span<const Eigen::Vector2d> FeatureAligner::RefinementPoints(const KeyMapNode& b) const {
  const auto min_points = static_cast<std::size_t>(options_.refinement.min_points);
  return b.scan_points.size() >= 2 * min_points
             ? std::span<const Eigen::Vector2d>(b.scan_points)
             : std::span<const Eigen::Vector2d>(b.description.obstacle_points);
}

std::optional<Alignment> FeatureAligner::Align(int i, int k, const Pose2* prior,
                                               double uncertainty_distance) {
  const KeyMapNode& a = graph_.node(i);
  const KeyMapNode& b = graph_.node(k);
  const matching::VerificationInput verification =
      description::KeyMapDescription::Verification(a.description, b.description);
  const matching::AlignResult result =
      matching::Align(a.description.features, b.description.features, matching_, &verification);
  if (!result.accepted) {
    return prior != nullptr && options_.prior_refinement
               ? RefineFromPrior(i, k, *prior, verification, uncertainty_distance)
               : std::nullopt;
  }
  ++counters_.verified;
  Pose2 T_a_b = result.T_a_b;
  if (options_.refinement.enabled) {
    const loop_closure::RefinementResult refined = loop_closure::RefineOnDistanceField(
        RefinementPoints(b), a.description.distance, T_a_b, options_.refinement);
    if (refined.ok) {
      T_a_b = refined.T_a_b;
    }
  }
  return Alignment{T_a_b, false};
}

std::optional<Alignment> FeatureAligner::RefineFromPrior(
    int i, int k, const Pose2& T_i_k, const matching::VerificationInput& verification,
    double uncertainty_distance) {
  const KeyMapNode& a = graph_.node(i);
  const KeyMapNode& b = graph_.node(k);
  loop_closure::RefinementOptions refinement = options_.refinement;
  refinement.max_distance = std::max(refinement.max_distance, 0.5);
  // After a long loop the prediction may be off by more than the refinement converges from.
  const loop_closure::PriorSearchOptions& search = options_.prior_search;
  const double window = std::min(search.max_window_xy, search.window_per_m * uncertainty_distance);
  Pose2 start = T_i_k;
  bool searched = false;
  if (search.enabled && window > search.min_window_xy) {
    ++counters_.prior_searches;
    const loop_closure::PriorSearchResult found = loop_closure::SearchAroundPrior(
        b.description.obstacle_points, a.description.distance, T_i_k, window, search);
    GRIDSLAM_LOG_DEBUG("prior search {}-{}: window {:.2f} m, score {:.3f}, rival {:.3f}, {}", i, k,
                       window, found.score, found.rival, found.ok ? "ok" : "refused");
    if (!found.ok) {
      return std::nullopt;
    }
    start = found.T_a_b;
    searched = true;
  }
  const loop_closure::RefinementResult refined = loop_closure::RefineOnDistanceField(
      RefinementPoints(b), a.description.distance, start, refinement);
  if (!refined.ok || refined.inlier_fraction < options_.prior_min_inliers) {
    GRIDSLAM_LOG_DEBUG("prior refinement {}-{}: refused, ok {}, inliers {:.2f}", i, k, refined.ok,
                       refined.inlier_fraction);
    return std::nullopt;
  }
  // Degenerate geometry (a featureless corridor) constrains some direction poorly: refuse it.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(refined.hessian.topLeftCorner<2, 2>());
  if (eig.eigenvalues()(0) < options_.prior_min_constraint * eig.eigenvalues()(1)) {
    GRIDSLAM_LOG_DEBUG("prior refinement {}-{}: refused, poorly constrained", i, k);
    return std::nullopt;
  }
  const matching::VerificationResult verified =
      matching::VerifyAlignment(refined.T_a_b, verification, matching_.verification);
  if (!verified.accepted) {
    GRIDSLAM_LOG_DEBUG(
        "prior refinement {}-{}: not verified, overlap {} ({}), agreement {:.2f}, contradiction "
        "{:.2f}",
        i, k, verified.overlap, verified.enough_overlap, verified.agreement,
        verified.contradiction);
    return std::nullopt;
  }
  ++counters_.prior_refined;
  return Alignment{refined.T_a_b, searched};
}

}  // namespace gridslam::pipeline
