// Loop closures of the Mapper (docs/design.md §1.6, §1.9): the prior-based candidates of a new key
// map (CandidateSelector::Prior) and the global appearance search, which looks a new key map up
// in every robot's appearance index, its own robot's included, with no prior: a robot whose
// drift outgrew the prior-based search still closes its loop, and robots with unknown relative
// starts find each other. Every verified alignment goes to the closure arbiter, whose decision
// is carried out here: loop edges, a join of two components (ComponentJoiner), or nothing.
#include <algorithm>
#include <cmath>
#include <limits>

#include "gridslam/common/logging.hpp"
#include "gridslam/pipeline/join_free_space.hpp"
#include "gridslam/pipeline/mapper_internal.hpp"

namespace gridslam::pipeline {

using loop_closure::Decision;
using loop_closure::Match;
using loop_closure::Verdict;

PriorSearch Mapper::Impl::SearchPriorCandidates(int k) {
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  // Uncertainty distances of the key maps that can be candidates: those within the largest
  // search radius (a little more: CandidateSelector measures the distance in k's frame), so the
  // search costs what the neighbourhood of k costs, not what the whole graph does.
  std::vector<int> near;
  const Eigen::Vector2d centre = graph.Estimate(k).translation();
  const double reach = lc.max_search_radius + 1e-3;
  for (int i = 0; i < graph.size(); ++i) {
    if (i != k && (graph.Estimate(i).translation() - centre).norm() < reach) {
      near.push_back(i);
    }
  }
  const std::vector<double> distance =
      near.empty() ? std::vector<double>(static_cast<std::size_t>(graph.size()),
                                         std::numeric_limits<double>::quiet_NaN())
                   : graph.DistancesFrom(k, near);
  PriorSearch search;
  search.tried = selector.Prior(graph, k, distance);
  for (const int i : search.tried) {
    ++stats.candidates;
    const double u = distance[static_cast<std::size_t>(i)];
    const Pose2 prior = Between(graph.Estimate(i), graph.Estimate(k));
    const std::optional<Alignment> measured = u < lc.prior_max_uncertainty
                                                  ? aligner.Align(i, k, &prior, u)
                                                  : aligner.Align(i, k, nullptr, 0.0);
    if (!measured.has_value()) {
      GRIDSLAM_LOG_DEBUG("closure {}-{} (t {:.1f}-{:.1f}) not aligned, uncertainty {:.1f} m", i, k,
                         ToSeconds(graph.node(i).time), ToSeconds(graph.node(k).time), u);
      continue;
    }
    const Match match = measured->ToMatch(i, k);
    const Decision decision = arbiter.OfferPrior(match, u, measured->from_search, graph);
    const Pose2& error = decision.error;
    GRIDSLAM_LOG_DEBUG("closure {}-{} (t {:.1f}-{:.1f}) aligned: error {:.3f} m {:.3f} rad", i, k,
                       ToSeconds(graph.node(i).time), ToSeconds(graph.node(k).time),
                       error.translation().norm(), error.theta());
    if (decision.verdict == Verdict::kReject) {
      ++stats.closures_beyond_drift;
      GRIDSLAM_LOG_DEBUG(
          "closure {}-{} refused: corrects {:.3f} m {:.3f} rad, beyond the drift of {:.1f} m of "
          "uncertainty",
          i, k, error.translation().norm(), error.theta(), u);
      continue;
    }
    if (decision.verdict == Verdict::kWait) {
      GRIDSLAM_LOG_DEBUG("closure {}-{} gated: error {:.3f} m {:.3f} rad, uncertainty {:.1f} m", i,
                         k, error.translation().norm(), error.theta(), u);
      graph.RecordClosure(match, ClosureOutcome::kGated, /*appearance=*/false);
      continue;
    }
    if (decision.verdict == Verdict::kAcceptGroup) {
      GRIDSLAM_LOG_DEBUG("closure {}-{} accepted with {} consistent gated closures", i, k,
                         decision.accepted.size() - 1);
    }
    for (std::size_t m = 0; m < decision.accepted.size(); ++m) {
      const Match& accepted = decision.accepted[m];
      const Eigen::Matrix3d information = LoopInformation(accepted, lc.sigma_xy, lc.sigma_theta);
      const double weight = LoopUncertaintyWeight(accepted, options.graph.loop_uncertainty);
      if (m == 0) {
        graph.AddLoopEdge(accepted, ClosureOutcome::kAccepted, /*appearance=*/false, information,
                          weight);
      } else {
        graph.AcceptGated(accepted, information, weight);
      }
    }
    // Only closures that disagree with the estimate make online optimization worth its cost.
    // A closure correcting the estimate by more than the gate's floor: a few SGD iterations
    // would leave most of it, and the next key maps' correct closures would be gated against
    // the stale estimate; the whole graph may be optimized instead (mapper.cpp).
    const bool in_gate = decision.in_gate;
    search.large_correction = search.large_correction || !in_gate ||
                              error.translation().norm() > lc.gate_xy ||
                              std::abs(error.theta()) > lc.gate_theta;
    search.changed = search.changed || !in_gate ||
                     error.translation().norm() > options.graph.online_trigger_xy ||
                     std::abs(error.theta()) > options.graph.online_trigger_theta;
  }
  return search;
}

bool Mapper::Impl::SearchAppearance(int k, const std::vector<int>& prior_tried) {
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  const KeyMapNode& current = graph.node(k);
  ++stats.appearance_queries;
  std::vector<double> distance;  // uncertainty distances from k, computed when first needed
  bool changed = false;
  // Every robot is searched in its own index: the query's nearest neighbours are that robot's
  // key maps, not near-duplicates from another one. In the query's own robot, the key maps just
  // behind it (min_travel_gap) and the prior-based candidates already tried are left out.
  for (std::size_t r = 0; r < robots.size(); ++r) {
    if (graph.NumKeyMaps(static_cast<int>(r)) == 0) {
      continue;
    }
    const auto allowed = [&, r](int id) {
      if (static_cast<int>(r) != current.robot) {
        return true;
      }
      return current.travel - graph.Travel(id) >= lc.min_travel_gap &&
             std::find(prior_tried.begin(), prior_tried.end(), id) == prior_tried.end();
    };
    const auto votes = robots[r].appearance->Query(
        current.features.descriptors, lc.appearance_candidates, /*min_votes=*/5, allowed);
    for (const loop_closure::AppearanceVote& vote : votes) {
      ++stats.appearance_candidates;
      const std::optional<Alignment> measured = aligner.Align(vote.node, k, nullptr, 0.0);
      if (!measured.has_value()) {
        continue;
      }
      const Match match{vote.node, k, measured->T_i_k};
      if (graph.RobotComponent(static_cast<int>(r)) == graph.Component(k)) {
        if (distance.empty()) {
          distance = graph.DistancesFrom(k);
        }
        changed = OfferWithinMap(match, distance[static_cast<std::size_t>(vote.node)]) || changed;
        continue;
      }
      graph.RecordClosure(match, ClosureOutcome::kPending, /*appearance=*/true);
      const Decision decision = arbiter.OfferJoin(match, graph);
      std::vector<Match> group = decision.accepted;
      if (decision.verdict != Verdict::kAcceptGroup) {
        // A lone match: verified by aligning the key maps around it under the frame it implies.
        const JoinVerifier::Result verified =
            join_verifier.Verify(match, arbiter.joinable(), graph, aligner);
        stats.verification_alignments += verified.alignments;
        group = verified.matches;
      }
      if (!group.empty() && !FreeSpaceAllowsJoin(group)) {
        group.clear();
      }
      if (!group.empty()) {
        const ComponentJoiner::Result joined = joiner.Join(group, now, graph, arbiter, aligner);
        joins.push_back(joined.join);
        stats.verification_alignments += joined.alignments;
        return true;
      }
    }
  }
  return changed;
}

bool Mapper::Impl::FreeSpaceAllowsJoin(const std::vector<Match>& group) {
  const loop_closure::FreeSpaceVerdict verdict =
      CheckJoinFreeSpace(group, graph, options.loop_closure.free_space_check);
  GRIDSLAM_LOG_DEBUG(
      "join {}-{} ({} matches): its alignments contradict free space at {:.4f} (median), the "
      "robots themselves at {:.4f}{}",
      group.front().i, group.front().k, group.size(), verdict.alignments, verdict.baseline,
      verdict.refused ? ": refused" : "");
  if (verdict.refused) {
    ++stats.joins_refused_free_space;
  }
  return !verdict.refused;
}

bool Mapper::Impl::OfferWithinMap(const Match& match, double uncertainty_distance) {
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  const Decision decision = arbiter.OfferWithinMap(match, uncertainty_distance, graph);
  const Pose2& error = decision.error;
  const Eigen::Matrix3d information = Information(lc.sigma_xy, lc.sigma_theta);
  switch (decision.verdict) {
    case Verdict::kAccept:
      graph.AddLoopEdge(match, ClosureOutcome::kAccepted, /*appearance=*/true, information,
                        options.graph.loop_uncertainty);
      return error.translation().norm() > options.graph.online_trigger_xy ||
             std::abs(error.theta()) > options.graph.online_trigger_theta;
    case Verdict::kReject:
      GRIDSLAM_LOG_DEBUG(
          "appearance match {}-{} rejected: moves the map {:.2f} m {:.3f} rad (uncertainty "
          "distance {:.1f} m)",
          match.i, match.k, error.translation().norm(), error.theta(), uncertainty_distance);
      return false;
    case Verdict::kWait: {
      GRIDSLAM_LOG_DEBUG("appearance match {}-{} off by {:.2f} m {:.3f} rad: waits", match.i,
                         match.k, error.translation().norm(), error.theta());
      // A loop whose drift outgrew the prior search meets itself in one run of neighbouring
      // matches, none independent of another: a hypothesis verified by the key maps around it
      // (once per key map: the first waiting match of k is the best-voted), and, if they do
      // not confirm it yet, by the next key maps (RetryLoopHypothesis).
      // A lone hypothesis must also be a drift the path could have gathered: the 10 m floor of
      // max_correction is for matches with independent support (a look-alike room of a short
      // loop would otherwise pass).
      const bool plausible =
          error.translation().norm() <=
          loop_closure::DriftBound(uncertainty_distance, error.theta(), options.loop_closure);
      if (plausible && loop_verified_k != match.k) {
        loop_verified_k = match.k;
        loop_hypothesis = match;
        VerifyLoopHypothesis();
      }
      return false;
    }
    case Verdict::kAcceptGroup:
      GRIDSLAM_LOG_DEBUG(
          "{} consistent matches between robots {} and {} correct the map by "
          "{:.2f} m",
          decision.accepted.size(), graph.Robot(match.i), graph.Robot(match.k),
          error.translation().norm());
      for (const Match& m : decision.accepted) {
        graph.AddLoopEdge(m, ClosureOutcome::kAccepted, /*appearance=*/true, information,
                          options.graph.loop_uncertainty);
      }
      OptimizeNow();  // a correction of metres: more than a few SGD iterations can absorb
      return false;
  }
  return false;
}

bool Mapper::Impl::VerifyLoopHypothesis() {
  if (!loop_hypothesis.has_value()) {
    return false;
  }
  const Match hypothesis = *loop_hypothesis;
  const JoinVerifier::Result verified =
      join_verifier.Verify(hypothesis, arbiter.within_map(), graph, aligner);
  stats.verification_alignments += verified.alignments;
  if (verified.matches.empty()) {
    return false;
  }
  loop_hypothesis.reset();
  const Pose2 error = loop_closure::ClosureError(hypothesis, graph);
  GRIDSLAM_LOG_DEBUG(
      "loop hypothesis {}-{} confirmed by {} alignments: corrects the map by "
      "{:.2f} m {:.3f} rad",
      hypothesis.i, hypothesis.k, verified.matches.size() - 1, error.translation().norm(),
      error.theta());
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  const Eigen::Matrix3d information = Information(lc.sigma_xy, lc.sigma_theta);
  for (const Match& m : verified.matches) {
    graph.AddLoopEdge(m, ClosureOutcome::kAccepted, /*appearance=*/true, information,
                      options.graph.loop_uncertainty);
  }
  ++stats.verified_loops;
  OptimizeNow();  // a correction of metres, as for a group
  return true;
}

void Mapper::Impl::RetryLoopHypothesis(int k) {
  if (!loop_hypothesis.has_value() || k == loop_hypothesis->k ||
      graph.Robot(k) != graph.Robot(loop_hypothesis->k)) {
    return;
  }
  // The key maps after the hypothesis's are predictions it did not see: while they stay within
  // the verification's reach, each new one may confirm it.
  if (graph.Travel(k) - graph.Travel(loop_hypothesis->k) >
      options.loop_closure.loop_verification_travel) {
    loop_hypothesis.reset();
    return;
  }
  VerifyLoopHypothesis();
}

}  // namespace gridslam::pipeline
