// Choosing which key maps to align with a key map (docs/design.md §1.6). One rule for every kind of
// candidate: the nearest first (by predicted distance, then vertex id), at most max_candidates,
// and no two of the same robot closer than candidate_spacing along its path (a place is seen by
// many overlapping key maps; aligning several of them repeats one piece of evidence).
//   - Prior candidates of a new key map k: key maps of k's component, alignable, not within
//     min_travel_gap behind k on its own path, reachable in the uncertainty graph, whose
//     predicted centre lies within search_radius + search_radius_per_m * u (capped).
//   - Catch-up candidates of a key map b after a join: the alignable key maps of the other
//     robots within max_search_radius of b under the joined estimate.
// Contract: reads the graph only; deterministic.
#pragma once

#include <vector>

#include "gridslam/loop_closure/loop_closure_options.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"

namespace gridslam::pipeline {

struct Candidate {
  double distance = 0.0;  ///< Predicted distance between the key maps' centres [m].
  int node = 0;
};

class CandidateSelector {
 public:
  explicit CandidateSelector(const loop_closure::LoopClosureOptions& options) : options_(options) {}

  /// The spacing rule: of `candidates`, the nearest, spread along each robot's path.
  [[nodiscard]] std::vector<int> Choose(std::vector<Candidate> candidates,
                                        const KeyMapGraph& graph) const;
  /// Prior candidates of key map `k`; `distance`: uncertainty distances from k.
  [[nodiscard]] std::vector<int> Prior(const KeyMapGraph& graph, int k,
                                       const std::vector<double>& distance) const;
  /// Catch-up candidates of key map `b`: key maps of robots not in `moved` (by robot).
  [[nodiscard]] std::vector<int> CatchUp(const KeyMapGraph& graph, int b,
                                         const std::vector<bool>& moved) const;

 private:
  loop_closure::LoopClosureOptions options_;
};

}  // namespace gridslam::pipeline
