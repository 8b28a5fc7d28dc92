#include "gridslam/pipeline/component_joiner.hpp"

#include "gridslam/common/logging.hpp"

namespace gridslam::pipeline {

using loop_closure::Match;

ComponentJoiner::ComponentJoiner(const loop_closure::LoopClosureOptions& options,
                                 double loop_uncertainty,
                                 const pose_graph::OptimizerOptions& optimizer)
    : options_(options),
      loop_uncertainty_(loop_uncertainty),
      optimizer_(optimizer),
      selector_(options) {}

ComponentJoiner::Result ComponentJoiner::Join(const std::vector<Match>& matches, Time now,
                                              KeyMapGraph& graph,
                                              loop_closure::ClosureArbiter& arbiter,
                                              Aligner& aligner) const {
  GRIDSLAM_CHECK(!matches.empty());
  const Match& anchor = matches.front();
  const int robot_a = graph.Robot(anchor.i);
  const int robot_b = graph.Robot(anchor.k);
  const int component_b = graph.RobotComponent(robot_b);
  std::vector<bool> moved(static_cast<std::size_t>(graph.num_robots()), false);
  for (int r = 0; r < graph.num_robots(); ++r) {
    moved[static_cast<std::size_t>(r)] = graph.RobotComponent(r) == component_b;
  }
  // Move component b into a's frame so that anchor.k lands at X_i * T_i_k.
  const Pose2 T_a_b = graph.Estimate(anchor.i) * anchor.T_i_k * graph.Estimate(anchor.k).Inverse();
  graph.MergeComponents(robot_a, robot_b, T_a_b, now);
  const Eigen::Matrix3d information = Information(options_.sigma_xy, options_.sigma_theta);
  for (const Match& m : matches) {
    GRIDSLAM_LOG_DEBUG(
        "join match {} (robot {}, t {:.1f}, travel {:.1f} m) - {} (robot {}, t {:.1f}, "
        "travel {:.1f} m)",
        m.i, graph.Robot(m.i), ToSeconds(graph.node(m.i).time), graph.Travel(m.i), m.k,
        graph.Robot(m.k), ToSeconds(graph.node(m.k).time), graph.Travel(m.k));
    graph.AddLoopEdge(m, ClosureOutcome::kJoined, /*appearance=*/true, information,
                      loop_uncertainty_);
  }
  arbiter.ForgetWithinComponents(graph);
  Result result;
  result.join = {robot_a, robot_b, now, anchor.i, anchor.k, static_cast<int>(matches.size())};
  CatchUp(moved, matches, graph, aligner, result);
  return result;
}

void ComponentJoiner::CatchUp(const std::vector<bool>& moved, std::vector<Match> trusted,
                              KeyMapGraph& graph, Aligner& aligner, Result& result) const {
  graph.Optimize(optimizer_);
  std::vector<bool> linked(static_cast<std::size_t>(graph.size()), false);
  for (const Match& t : trusted) {
    linked[static_cast<std::size_t>(t.k)] = true;
  }
  const Eigen::Matrix3d information = Information(options_.sigma_xy, options_.sigma_theta);
  for (int round = 0; round < options_.catch_up_rounds; ++round) {
    // Every key map of b not yet linked: the nearest key maps of a under the joined estimate.
    std::vector<Match> found;
    for (const KeyMapNode& b : graph.nodes()) {
      if (!moved[static_cast<std::size_t>(b.robot)] || !b.alignable ||
          linked[static_cast<std::size_t>(b.id)]) {
        continue;
      }
      for (const int i : selector_.CatchUp(graph, b.id, moved)) {
        ++result.alignments;
        if (const std::optional<Alignment> measured = aligner.Align(i, b.id, nullptr, 0.0)) {
          found.push_back({i, b.id, measured->T_i_k});
        }
      }
    }
    // Kept: the matches that min_join_matches others (found or trusted) agree with.
    std::vector<Match> pool = trusted;
    pool.insert(pool.end(), found.begin(), found.end());
    std::vector<Match> accepted;
    for (const Match& f : found) {
      if (loop_closure::Support(f, pool, graph, options_) < options_.min_join_matches) {
        continue;
      }
      graph.AddLoopEdge(f, ClosureOutcome::kAccepted, /*appearance=*/false, information,
                        loop_uncertainty_);
      linked[static_cast<std::size_t>(f.k)] = true;
      accepted.push_back(f);
    }
    result.caught_up += static_cast<int>(accepted.size());
    trusted.insert(trusted.end(), accepted.begin(), accepted.end());
    if (accepted.empty()) {
      break;
    }
    graph.Optimize(optimizer_);
  }
  GRIDSLAM_LOG_DEBUG("join catch-up: {} alignments, {} loop edges", result.alignments,
                     result.caught_up);
}

}  // namespace gridslam::pipeline
