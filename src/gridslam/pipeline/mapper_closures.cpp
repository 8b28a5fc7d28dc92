// Loop closures of the Mapper (DESIGN.md §1.6): prior-based candidates gated by the current
// estimate (the appearance search across robots and their joins are in mapper_join.cpp).
#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "gridslam/common/logging.hpp"
#include "gridslam/loop_closure/grid_refinement.hpp"
#include "gridslam/matching/align.hpp"
#include "gridslam/pipeline/mapper_internal.hpp"

namespace gridslam::pipeline {

std::optional<Pose2> Mapper::Impl::TryAlign(int i, int k, const Pose2* prior,
                                            double uncertainty_distance) {
  const Node& a = nodes[static_cast<std::size_t>(i)];
  const Node& b = nodes[static_cast<std::size_t>(k)];
  const matching::VerificationInput verification =
      description::KeyMapDescription::Verification(a.description, b.description);
  const matching::AlignResult result = matching::Align(
      a.description.features, b.description.features, options.matching, &verification);
  if (!result.accepted) {
    return prior != nullptr && options.loop_closure.prior_refinement
               ? RefineFromPrior(i, k, *prior, verification, uncertainty_distance)
               : std::nullopt;
  }
  ++stats.verified;
  Pose2 T_a_b = result.T_a_b;
  if (options.loop_closure.refinement.enabled) {
    const loop_closure::RefinementResult refined = loop_closure::RefineOnDistanceField(
        RefinementPoints(b), a.description.distance, T_a_b, options.loop_closure.refinement);
    if (refined.ok) {
      T_a_b = refined.T_a_b;
    }
  }
  return T_a_b;
}

namespace {

// The loop i -> k (measured), k -> k2 (estimate in k's component), k2 -> i2 (measured),
// i2 -> i (estimate in i's component) closes within the tolerances.
bool Consistent(const PendingJoin& a, const PendingJoin& b, const std::vector<Node>& nodes,
                double tolerance_xy, double tolerance_theta) {
  const auto& n = [&](int id) -> const Node& { return nodes[static_cast<std::size_t>(id)]; };
  const Pose2 loop = a.T_i_k * Between(n(a.k).estimate, n(b.k).estimate) * b.T_i_k.Inverse() *
                     Between(n(b.i).estimate, n(a.i).estimate);
  return loop.translation().norm() < tolerance_xy && std::abs(loop.theta()) < tolerance_theta;
}

}  // namespace

std::optional<Pose2> Mapper::Impl::RefineFromPrior(int i, int k, const Pose2& T_i_k,
                                                   const matching::VerificationInput& verification,
                                                   double uncertainty_distance) {
  const Node& a = nodes[static_cast<std::size_t>(i)];
  const Node& b = nodes[static_cast<std::size_t>(k)];
  loop_closure::RefinementOptions refinement = options.loop_closure.refinement;
  refinement.max_distance = std::max(refinement.max_distance, 0.5);
  // After a long loop the prediction may be off by more than the refinement converges from.
  const loop_closure::PriorSearchOptions& search = options.loop_closure.prior_search;
  const double window = std::min(search.max_window_xy, search.window_per_m * uncertainty_distance);
  Pose2 start = T_i_k;
  if (search.enabled && window > search.min_window_xy) {
    ++stats.prior_searches;
    const loop_closure::PriorSearchResult found = loop_closure::SearchAroundPrior(
        b.description.obstacle_points, a.description.distance, T_i_k, window, search);
    GRIDSLAM_LOG_DEBUG("prior search {}-{}: window {:.2f} m, score {:.3f}, rival {:.3f}, {}", i, k,
                       window, found.score, found.rival, found.ok ? "ok" : "refused");
    if (!found.ok) {
      return std::nullopt;
    }
    start = found.T_a_b;
    searched_ = true;
  }
  const loop_closure::RefinementResult refined = loop_closure::RefineOnDistanceField(
      RefinementPoints(b), a.description.distance, start, refinement);
  if (!refined.ok || refined.inlier_fraction < options.loop_closure.prior_min_inliers) {
    GRIDSLAM_LOG_DEBUG("prior refinement {}-{}: refused, ok {}, inliers {:.2f}", i, k, refined.ok,
                       refined.inlier_fraction);
    return std::nullopt;
  }
  // Degenerate geometry (a featureless corridor) constrains some direction poorly: refuse it.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(refined.hessian.topLeftCorner<2, 2>());
  if (eig.eigenvalues()(0) < options.loop_closure.prior_min_constraint * eig.eigenvalues()(1)) {
    GRIDSLAM_LOG_DEBUG("prior refinement {}-{}: refused, poorly constrained", i, k);
    return std::nullopt;
  }
  const matching::VerificationResult verified =
      matching::VerifyAlignment(refined.T_a_b, verification, options.matching.verification);
  if (!verified.accepted) {
    GRIDSLAM_LOG_DEBUG(
        "prior refinement {}-{}: not verified, overlap {} ({}), agreement {:.2f}, contradiction "
        "{:.2f}",
        i, k, verified.overlap, verified.enough_overlap, verified.agreement,
        verified.contradiction);
    return std::nullopt;
  }
  ++stats.prior_refined;
  return refined.T_a_b;
}

bool Mapper::Impl::SearchPriorCandidates(int k) {
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  const Node& current = nodes[static_cast<std::size_t>(k)];
  const int component = FindComponent(current.robot);
  const std::vector<double> distance = uncertainty.DistancesFrom(k);
  struct Candidate {
    double predicted_distance;
    int node;
  };
  std::vector<Candidate> candidates;
  for (const Node& node : nodes) {
    if (node.id == k || !node.alignable || FindComponent(node.robot) != component) {
      continue;
    }
    if (node.robot == current.robot && current.travel - node.travel < lc.min_travel_gap) {
      continue;
    }
    const double u = distance[static_cast<std::size_t>(node.id)];
    if (!std::isfinite(u)) {
      continue;
    }
    const double d = Between(node.estimate, current.estimate).translation().norm();
    const double radius =
        std::min(lc.max_search_radius, lc.search_radius + lc.search_radius_per_m * u);
    if (d < radius) {
      candidates.push_back({d, node.id});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.predicted_distance < b.predicted_distance;
  });
  std::vector<int> chosen;
  for (const Candidate& c : candidates) {
    if (static_cast<int>(chosen.size()) >= lc.max_candidates) {
      break;
    }
    const Node& node = nodes[static_cast<std::size_t>(c.node)];
    const bool too_close = std::any_of(chosen.begin(), chosen.end(), [&](int other) {
      const Node& o = nodes[static_cast<std::size_t>(other)];
      return o.robot == node.robot && std::abs(o.travel - node.travel) < lc.candidate_spacing;
    });
    if (!too_close) {
      chosen.push_back(c.node);
    }
  }
  prior_tried = chosen;
  bool accepted_any = false;
  for (const int i : chosen) {
    ++stats.candidates;
    searched_ = false;
    const Pose2 prior = Between(nodes[static_cast<std::size_t>(i)].estimate, current.estimate);
    const std::optional<Pose2> measured =
        distance[static_cast<std::size_t>(i)] < lc.prior_max_uncertainty
            ? TryAlign(i, k, &prior, distance[static_cast<std::size_t>(i)])
            : TryAlign(i, k, nullptr);
    if (!measured.has_value()) {
      GRIDSLAM_LOG_DEBUG("closure {}-{} (t {:.1f}-{:.1f}) not aligned, uncertainty {:.1f} m", i, k,
                         ToSeconds(nodes[static_cast<std::size_t>(i)].time),
                         ToSeconds(current.time), distance[static_cast<std::size_t>(i)]);
      continue;
    }
    const Node& old = nodes[static_cast<std::size_t>(i)];
    const Pose2 predicted = Between(old.estimate, current.estimate);
    const Pose2 error = Between(predicted, *measured);
    const double u = distance[static_cast<std::size_t>(i)];
    ClosureRecord record{i, k, *measured, "accepted", false};
    GRIDSLAM_LOG_DEBUG("closure {}-{} (t {:.1f}-{:.1f}) aligned: error {:.3f} m {:.3f} rad", i, k,
                       ToSeconds(old.time), ToSeconds(current.time), error.translation().norm(),
                       error.theta());
    // A closure found by the prior search is never trusted alone: in a wide window a look-alike
    // place (a row of identical bays) may score best; it needs the support of other closures.
    const bool in_gate = !searched_ &&
                         error.translation().norm() <= lc.gate_xy + lc.gate_xy_per_m * u &&
                         std::abs(error.theta()) <= lc.gate_theta + lc.gate_theta_per_m * u;
    std::vector<PendingJoin> group = {{i, k, *measured}};
    if (!in_gate) {
      // A closure outside the gate is kept; once enough recent gated closures agree with each
      // other (the loops they form with the graph close), the estimate is what was wrong, and
      // they are accepted together (DESIGN.md 1.6: pairwise consistency of several closures).
      for (const PendingJoin& g : gated) {
        if (g.k != k && k - g.k <= lc.gated_window &&
            Consistent(group.front(), g, nodes, lc.pairwise_xy, lc.pairwise_theta)) {
          group.push_back(g);
        }
      }
      if (static_cast<int>(group.size()) < lc.min_consistent_gated) {
        record.outcome = "gate";
        ++stats.rejected_gate;
        GRIDSLAM_LOG_DEBUG("closure {}-{} gated: error {:.3f} m {:.3f} rad, uncertainty {:.1f} m",
                           i, k, error.translation().norm(), error.theta(), u);
        closures.push_back(record);
        gated.push_back(group.front());
        continue;
      }
      GRIDSLAM_LOG_DEBUG("closure {}-{} accepted with {} consistent gated closures", i, k,
                         group.size() - 1);
      gated.erase(std::remove_if(gated.begin(), gated.end(),
                                 [&](const PendingJoin& g) {
                                   return std::any_of(group.begin(), group.end(),
                                                      [&](const PendingJoin& m) {
                                                        return m.i == g.i && m.k == g.k;
                                                      });
                                 }),
                  gated.end());
    }
    for (std::size_t m = 0; m < group.size(); ++m) {
      EdgeRecord edge;
      edge.from = group[m].i;
      edge.to = group[m].k;
      edge.T_from_to = group[m].T_i_k;
      edge.information = Information(lc.sigma_xy, lc.sigma_theta);
      edge.loop = true;
      if (m == 0) {
        edge.closure = static_cast<int>(closures.size());
        closures.push_back(record);
      } else {
        for (ClosureRecord& c : closures) {
          if (c.from == edge.from && c.to == edge.to && c.outcome == "gate") {
            c.outcome = "accepted";
            --stats.rejected_gate;
            edge.closure = static_cast<int>(&c - closures.data());
          }
        }
      }
      AddEdge(edge, options.graph.loop_uncertainty);
      ++stats.accepted;
    }
    // Only closures that disagree with the estimate make online optimization worth its cost.
    // A closure correcting the estimate by more than the gate's floor: a few SGD iterations
    // would leave most of it, and the next key maps' correct closures would be gated against
    // the stale estimate; the whole graph is optimized instead (mapper.cpp).
    large_correction_ = large_correction_ || !in_gate || error.translation().norm() > lc.gate_xy ||
                        std::abs(error.theta()) > lc.gate_theta;
    accepted_any = accepted_any || !in_gate ||
                   error.translation().norm() > options.graph.online_trigger_xy ||
                   std::abs(error.theta()) > options.graph.online_trigger_theta;
  }
  return accepted_any;
}

}  // namespace gridslam::pipeline
