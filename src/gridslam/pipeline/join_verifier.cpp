#include "gridslam/pipeline/join_verifier.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "gridslam/common/logging.hpp"

namespace gridslam::pipeline {

using loop_closure::Match;

namespace {

// Key maps of the component `component`, alignable, whose estimates lie within `radius` of
// `centre`, nearest first, at most `count`; with `behind` >= 0, only those at least `behind`
// along the path from key map `of` (inside one map: the old pass, not the path just driven).
std::vector<int> Nearest(const KeyMapGraph& graph, int component, const Eigen::Vector2d& centre,
                         double radius, std::size_t count, int of, double behind) {
  std::vector<std::pair<double, int>> near;
  for (const KeyMapNode& node : graph.nodes()) {
    const double d = (graph.Estimate(node.id).translation() - centre).norm();
    const bool old_pass = behind < 0.0 || graph.Robot(node.id) != graph.Robot(of) ||
                          std::abs(graph.Travel(of) - node.travel) >= behind;
    if (node.alignable && graph.Component(node.id) == component && d < radius && old_pass) {
      near.emplace_back(d, node.id);
    }
  }
  std::sort(near.begin(), near.end());
  std::vector<int> ids;
  for (std::size_t n = 0; n < std::min(count, near.size()); ++n) {
    ids.push_back(near[n].second);
  }
  return ids;
}

}  // namespace

JoinVerifier::Result JoinVerifier::Verify(const Match& hypothesis,
                                          const std::vector<Match>& pending,
                                          const KeyMapGraph& graph, Aligner& aligner) const {
  Result result;
  const int older = graph.Component(hypothesis.i);
  const int newer = graph.Component(hypothesis.k);
  const bool loop = older == newer;
  const char* kind = loop ? "loop" : "join";
  const double travel =
      loop ? options_.loop_verification_travel : options_.join_verification_travel;
  if (travel <= 0.0) {
    return result;
  }
  const auto component_of = [&](int id) { return graph.Component(id); };
  for (const Match& p : pending) {
    const std::optional<Match> oriented = loop_closure::Oriented(p, older, newer, component_of);
    // Inside one map the waiting matches are of every loop of the building; only those of the
    // same revisit (their newer key map near the hypothesis's along the path) can contradict it.
    const bool same_revisit =
        !loop || std::abs(graph.Travel(p.k) - graph.Travel(hypothesis.k)) <= travel;
    if (oriented.has_value() && same_revisit &&
        !loop_closure::PairConsistent(hypothesis, *oriented, graph, options_)) {
      GRIDSLAM_LOG_DEBUG("{} hypothesis {}-{}: refused, match {}-{} disagrees", kind, hypothesis.i,
                         hypothesis.k, p.i, p.k);
      return result;
    }
  }
  // Inside one map the revisit may already have closures: the estimate there is then measured,
  // and a hypothesis that moves the map against one of them is a look-alike (a symmetric
  // building's twin corridor), not a loop the prior search missed.
  if (loop) {
    for (const ClosureRecord& record : graph.closures()) {
      const Match accepted{record.from, record.to, record.T_from_to};
      if (record.outcome == loop_closure::ClosureOutcome::kAccepted &&
          graph.Robot(record.to) == graph.Robot(hypothesis.k) &&
          std::abs(graph.Travel(record.to) - graph.Travel(hypothesis.k)) <= travel &&
          !loop_closure::PairConsistent(hypothesis, accepted, graph, options_)) {
        GRIDSLAM_LOG_DEBUG("loop hypothesis {}-{}: refused, closure {}-{} disagrees", hypothesis.i,
                           hypothesis.k, record.from, record.to);
        return result;
      }
    }
  }
  Support support = Gather(hypothesis, hypothesis, graph, aligner, &result.alignments);
  GRIDSLAM_LOG_DEBUG("{} hypothesis {}-{}: {} alignments, {} agree ({} key maps{})", kind,
                     hypothesis.i, hypothesis.k, result.alignments, support.matches.size(),
                     support.covered, support.independent ? ", one independent" : "");
  if (!Confirms(support)) {
    return result;
  }
  // Inside one map the hypothesis competes with the map as it stands: the same key maps aligned
  // where the current estimate places them. In a corridor of identical bays both agree with
  // their alignments (the features and the refinement find whichever copy the prior is nearest);
  // a real drift leaves the current estimate without support. When the uncorrected map passes
  // the same test, the revisit does not tell the two apart, and the correction is refused.
  if (loop) {
    const Match as_is{hypothesis.i, hypothesis.k,
                      Between(graph.Estimate(hypothesis.i), graph.Estimate(hypothesis.k))};
    const long before = result.alignments;
    const Support rival = Gather(as_is, hypothesis, graph, aligner, &result.alignments);
    GRIDSLAM_LOG_DEBUG(
        "loop hypothesis {}-{} against the map as it stands: {} alignments, {} agree "
        "({} key maps{})",
        hypothesis.i, hypothesis.k, result.alignments - before, rival.matches.size(), rival.covered,
        rival.independent ? ", one independent" : "");
    if (Confirms(rival)) {
      GRIDSLAM_LOG_DEBUG(
          "loop hypothesis {}-{}: refused, the map as it stands explains the revisit as well ({} "
          "key maps agree with it)",
          hypothesis.i, hypothesis.k, rival.covered);
      return result;
    }
  }
  result.matches.push_back(hypothesis);
  result.matches.insert(result.matches.end(), support.matches.begin(), support.matches.end());
  return result;
}

bool JoinVerifier::Confirms(const Support& support) const {
  return support.covered >= options_.min_consistent_gated && support.independent;
}

JoinVerifier::Support JoinVerifier::Gather(const Match& claim, const Match& other,
                                           const KeyMapGraph& graph, Aligner& aligner,
                                           long* alignments) const {
  const int older = graph.Component(claim.i);
  const bool loop = older == graph.Component(claim.k);
  const double travel =
      loop ? options_.loop_verification_travel : options_.join_verification_travel;
  const int robot = graph.Robot(claim.k);
  // The newer component's frame in the older one's, as the claim says.
  const Pose2 T_a_b = graph.Estimate(claim.i) * claim.T_i_k * graph.Estimate(claim.k).Inverse();
  const bool distinct = !loop_closure::PairConsistent(claim, other, graph, options_);
  Support support;
  std::vector<int> covered = {claim.k};
  for (const KeyMapNode& b : graph.nodes()) {
    const double along = std::abs(b.travel - graph.Travel(claim.k));
    if (b.robot != robot || b.id == claim.k || !b.alignable || along > travel) {
      continue;
    }
    const Pose2 predicted = T_a_b * graph.Estimate(b.id);  // b in the older component's frame
    const double behind = loop ? options_.min_travel_gap : -1.0;
    for (const int a : Nearest(graph, older, predicted.translation(), options_.search_radius,
                               /*count=*/2, b.id, behind)) {
      const Pose2 prior = Between(graph.Estimate(a), predicted);
      // The prediction is as uncertain as the two paths from the matched key maps (another
      // robot of the older component: as far as the search reaches).
      const double uncertainty = along + (graph.Robot(a) == graph.Robot(claim.i)
                                              ? std::abs(graph.Travel(a) - graph.Travel(claim.i))
                                              : options_.max_search_radius);
      ++*alignments;
      const std::optional<Alignment> measured = aligner.Align(a, b.id, &prior, uncertainty);
      if (!measured.has_value() || measured->free_axis.has_value()) {
        continue;
      }
      const Match found{a, b.id, measured->T_i_k};
      // An alignment that agrees with both claims supports neither against the other.
      if (!loop_closure::PairConsistent(claim, found, graph, options_) ||
          (distinct && loop_closure::PairConsistent(other, found, graph, options_))) {
        continue;
      }
      support.matches.push_back(found);
      if (std::find(covered.begin(), covered.end(), b.id) == covered.end()) {
        covered.push_back(b.id);
      }
      support.independent =
          support.independent ||
          loop_closure::Independent(claim, found, graph, options_.independent_travel);
    }
  }
  support.covered = static_cast<int>(covered.size());
  return support;
}

}  // namespace gridslam::pipeline
