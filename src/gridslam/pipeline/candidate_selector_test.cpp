// The candidate selector: one spacing rule for prior and catch-up candidates.
#include "gridslam/pipeline/candidate_selector.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace gridslam::pipeline {
namespace {

/// One robot whose key maps (1 m apart along x, travel = x) come back along y = 0.5.
KeyMapGraph OutAndBack(int robots = 1) {
  KeyMapGraph graph(robots, {});
  for (int r = 0; r < robots; ++r) {
    for (int v = 0; v < 40; ++v) {
      KeyMapNode node;
      node.robot = r;
      node.travel = v;
      node.T_odom_key = v < 20 ? Pose2(v, 0, 0) : Pose2(39 - v, 0.5, 3.14159);
      node.alignable = true;
      graph.AddKeyMap(std::move(node));
    }
  }
  return graph;
}

TEST(CandidateSelector, ChoosesTheNearestSpreadAlongThePath) {
  const KeyMapGraph graph = OutAndBack();
  loop_closure::LoopClosureOptions options;
  options.max_candidates = 3;
  options.candidate_spacing = 3.0;
  const CandidateSelector selector(options);
  const std::vector<int> chosen =
      selector.Choose({{0.1, 10}, {0.2, 11}, {0.3, 12}, {0.4, 13}, {0.5, 14}, {0.6, 20}}, graph);
  EXPECT_EQ(chosen, (std::vector<int>{10, 13, 20}));
}

TEST(CandidateSelector, TiesAreBrokenByVertexId) {
  const KeyMapGraph graph = OutAndBack();
  const CandidateSelector selector{loop_closure::LoopClosureOptions{}};
  EXPECT_EQ(selector.Choose({{1.0, 30}, {1.0, 5}}, graph), (std::vector<int>{5, 30}));
}

TEST(CandidateSelector, PriorCandidatesLieWithinTheRadiusAndBehindTheTravelGap) {
  const KeyMapGraph graph = OutAndBack();
  loop_closure::LoopClosureOptions options;
  options.search_radius = 2.0;
  options.search_radius_per_m = 0.0;
  options.min_travel_gap = 10.0;
  options.max_candidates = 10;
  options.candidate_spacing = 0.0;
  const CandidateSelector selector(options);
  // Key map 30 sits at x = 9 on the way back: the way out's x = 8, 9, 10 (and 7, 11 at
  // 2.06 m... outside) are within 2 m; 29, 31 are too recent.
  const std::vector<double> distance(40, 0.0);
  const std::vector<int> chosen = selector.Prior(graph, 30, distance);
  EXPECT_EQ(chosen, (std::vector<int>{9, 8, 10}));
}

TEST(CandidateSelector, PriorCandidatesStayInTheComponentAndNeedAPath) {
  const KeyMapGraph graph = OutAndBack(2);
  loop_closure::LoopClosureOptions options;
  options.min_travel_gap = 10.0;
  const CandidateSelector selector(options);
  std::vector<double> distance(80, 0.0);
  distance[9] = loop_closure::UncertaintyGraph::kUnreachable;
  for (const int id : selector.Prior(graph, 30, distance)) {
    EXPECT_LT(id, 40);  // robot 1 is another component
    EXPECT_NE(id, 9);   // unreachable
  }
}

TEST(CandidateSelector, CatchUpCandidatesAreTheOtherRobotsNearestKeyMaps) {
  const KeyMapGraph graph = OutAndBack(2);
  loop_closure::LoopClosureOptions options;
  options.max_candidates = 2;
  options.candidate_spacing = 3.0;
  const CandidateSelector selector(options);
  const std::vector<bool> moved = {false, true};
  const std::vector<int> chosen = selector.CatchUp(graph, 45, moved);  // robot 1 at x = 5
  ASSERT_EQ(chosen.size(), 2U);
  EXPECT_EQ(chosen[0], 5);  // robot 0 at x = 5
  for (const int id : chosen) {
    EXPECT_EQ(graph.Robot(id), 0);
  }
  EXPECT_GE(std::abs(graph.Travel(chosen[0]) - graph.Travel(chosen[1])), 3.0);
}

}  // namespace
}  // namespace gridslam::pipeline
