#include "gridslam/pipeline/join_free_space.hpp"

#include <algorithm>

namespace gridslam::pipeline {

namespace {

loop_closure::FreeSpaceCounts Replay(const KeyMapGraph& graph, int a, int b, const Pose2& T_a_b,
                                     double agreement_distance) {
  const KeyMapNode& node_a = graph.node(a);
  const KeyMapNode& node_b = graph.node(b);
  return loop_closure::ReplayPair(node_a.scan_points, node_a.cells, node_b.scan_points,
                                  node_b.cells, T_a_b, agreement_distance);
}

// The robot's key map at least `travel` behind `id` along its path; -1 if its path is shorter.
int Behind(const KeyMapGraph& graph, int id, double travel) {
  int behind = id;
  while (graph.Travel(id) - graph.Travel(behind) < travel) {
    behind = graph.node(behind).previous;
    if (behind < 0) {
      return -1;
    }
  }
  return behind;
}

}  // namespace

loop_closure::FreeSpaceVerdict CheckJoinFreeSpace(
    const std::vector<loop_closure::Match>& group, const KeyMapGraph& graph,
    const loop_closure::FreeSpaceCheckOptions& options) {
  std::vector<double> alignments;
  std::vector<int> joined;
  for (const loop_closure::Match& match : group) {
    alignments.push_back(
        Replay(graph, match.i, match.k, match.T_i_k, options.agreement_distance).Contradiction());
    joined.push_back(match.i);
    joined.push_back(match.k);
  }
  std::sort(joined.begin(), joined.end());
  joined.erase(std::unique(joined.begin(), joined.end()), joined.end());
  std::vector<double> baselines;
  for (const int id : joined) {
    for (const double travel : options.baseline_travel) {
      const int behind = Behind(graph, id, travel);
      if (behind >= 0) {
        baselines.push_back(Replay(graph, behind, id,
                                   Between(graph.Estimate(behind), graph.Estimate(id)),
                                   options.agreement_distance)
                                .Contradiction());
      }
    }
  }
  return loop_closure::JudgeContradictions(std::move(alignments), std::move(baselines), options);
}

}  // namespace gridslam::pipeline
