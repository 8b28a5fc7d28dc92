// Verifying a lone join hypothesis (docs/multi_robot.md, "A join from one meeting place"). Two
// robots that meet only briefly in a feature-poor building (a corridor crossed once) give the
// appearance search one run of neighbouring matches: never two independent ones, so
// ClosureArbiter::OfferJoin waits for ever and the robots never join. One verified appearance
// match is a hypothesis of the components' relative frame. Under it, the key maps of the newer
// robot within `join_verification_travel` along its path are aligned with the nearest key maps
// of the older component by the prediction (FeatureAligner::Align with a prior: features, then
// the prior search and refinement). The hypothesis stands when alignments that agree with it
// (PairConsistent) cover `min_consistent_gated` distinct key maps of the newer robot, the match's
// own included, and at least one of them is independent of the match (`independent_travel`
// along both paths): the rule a closure found by the prior search within one map must meet.
// Ridges (a position along a corridor left unmeasured) are not evidence for a join.
//
// Inside one map the same test verifies a loop (`loop_verification_travel`, on by default): a
// robot whose drift outgrew the prior search meets its old path in one run of neighbouring
// appearance matches, which ClosureArbiter::OfferWithinMap queues for ever for want of an
// independent one. The key maps within that travel of the match's newer one are aligned with the
// old pass's key maps the correction predicts them beside (never with key maps within
// min_travel_gap of them along the path: the path just driven); only waiting matches of the same
// revisit can contradict. The mapper retries a hypothesis as the next key maps arrive. A loop
// hypothesis must also beat the map as it stands: the same test run on the uncorrected estimate
// (the key maps aligned where the map now places them) must fail. In a corridor of identical bays
// both pass, and a correction the revisit cannot tell from no correction is refused.
// Contract: reads the graph, asks the aligner; writes nothing.
#pragma once

#include <vector>

#include "gridslam/loop_closure/closure_arbiter.hpp"
#include "gridslam/loop_closure/loop_closure_options.hpp"
#include "gridslam/pipeline/key_map_aligner.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"

namespace gridslam::pipeline {

class JoinVerifier {
 public:
  explicit JoinVerifier(const loop_closure::LoopClosureOptions& options) : options_(options) {}

  struct Result {
    /// The hypothesis first, then the alignments that confirm it (i in its component, k in the
    /// other); empty when it is not confirmed.
    std::vector<loop_closure::Match> matches;
    long alignments = 0;  ///< Alignments tried.
  };
  /// `hypothesis`: a verified match between two components (i: a key map of the component it
  /// would join, k: one of the newer robot's), or inside one (i: the old pass, k: the revisit).
  /// `pending`: the matches waiting (ClosureArbiter::joinable, or within_map inside one map); one
  /// that disagrees with the hypothesis refuses it (conflicting evidence: a symmetric building
  /// matched both ways).
  [[nodiscard]] Result Verify(const loop_closure::Match& hypothesis,
                              const std::vector<loop_closure::Match>& pending,
                              const KeyMapGraph& graph, Aligner& aligner) const;

 private:
  /// Alignments agreeing with a claim of where the newer key maps lie.
  struct Support {
    std::vector<loop_closure::Match> matches;
    int covered = 0;           ///< Distinct newer key maps they cover, the claim's own included.
    bool independent = false;  ///< One is independent of the claim (independent_travel).
  };
  /// The key maps within the verification travel of claim.k, aligned with the older component's
  /// key maps the claim predicts them beside; those that agree with the claim and, when `other`
  /// is a different claim, not with it too.
  Support Gather(const loop_closure::Match& claim, const loop_closure::Match& other,
                 const KeyMapGraph& graph, Aligner& aligner, long* alignments) const;
  [[nodiscard]] bool Confirms(const Support& support) const;

  loop_closure::LoopClosureOptions options_;
};

}  // namespace gridslam::pipeline
