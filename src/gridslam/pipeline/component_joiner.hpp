// Joining two robots' map components (docs/design.md §1.9): once the closure arbiter has enough
// mutually consistent matches between two components (ClosureArbiter::OfferJoin), the joiner
// moves the newer component into the older one's frame so that the first match holds, adds the
// matches as loop edges (outcome kJoined), and runs the catch-up search: every key map of the
// moved robots is aligned with its nearest key maps of the others (CandidateSelector::CatchUp)
// and the alignments that min_join_matches others (found or trusted) support become loop edges,
// for catch_up_rounds rounds with a full optimization after each. Before a join each graph is
// anchored on its own (Howard et al. 2006's manifold: shared places simply exist twice).
// Contract: writes the graph only through KeyMapGraph; the aligner is asked, never bypassed.
#pragma once

#include <vector>

#include "gridslam/loop_closure/closure_arbiter.hpp"
#include "gridslam/pipeline/candidate_selector.hpp"
#include "gridslam/pipeline/key_map_aligner.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"
#include "gridslam/pose_graph/optimizer.hpp"

namespace gridslam::pipeline {

class ComponentJoiner {
 public:
  /// `loop_uncertainty`: weight of a loop edge in the uncertainty distance [m].
  ComponentJoiner(const loop_closure::LoopClosureOptions& options, double loop_uncertainty,
                  const pose_graph::OptimizerOptions& optimizer);

  struct Result {
    JoinRecord join;
    long alignments = 0;  ///< Catch-up alignments tried.
    int caught_up = 0;    ///< Catch-up loop edges added.
  };
  /// Joins the components of matches.front() (i: the older component, k: the newer) with the
  /// consistent `matches`, then catches up. `now`: the time of the frame that completed it.
  Result Join(const std::vector<loop_closure::Match>& matches, Time now, KeyMapGraph& graph,
              loop_closure::ClosureArbiter& arbiter, Aligner& aligner) const;

 private:
  void CatchUp(const std::vector<bool>& moved, std::vector<loop_closure::Match> trusted,
               KeyMapGraph& graph, Aligner& aligner, Result& result) const;

  loop_closure::LoopClosureOptions options_;
  double loop_uncertainty_;
  pose_graph::OptimizerOptions optimizer_;
  CandidateSelector selector_;
};

}  // namespace gridslam::pipeline
