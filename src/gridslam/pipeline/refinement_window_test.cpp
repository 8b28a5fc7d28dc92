// RefinementWindow: the returns behind a key map, gathered from the robot's preceding key maps
// and placed in its frame by the front end's poses.
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/pipeline/key_map_aligner.hpp"

namespace gridslam::pipeline {
namespace {

/// One world point seen by each key map (in its own frame), key maps 1 m apart along a turning
/// path; a second robot's key maps interleaved (never part of robot 0's window).
struct Chain {
  KeyMapGraph graph{2, {}};
  std::vector<Pose2> odom;
  std::vector<Eigen::Vector2d> world;
  std::vector<int> ids;
};

Chain MakeChain(int count) {
  Chain chain;
  for (int v = 0; v < count; ++v) {
    const Pose2 T_odom_key(0.9 * v, 0.2 * v * v, 0.3 * v);
    const Eigen::Vector2d p(2.0 + v, -1.0 + 0.5 * v);  // in the odometry frame
    KeyMapNode node;
    node.robot = 0;
    node.travel = static_cast<double>(v);
    node.T_odom_key = T_odom_key;
    node.scan_points = {PointTransform(T_odom_key.Inverse())(p)};
    chain.odom.push_back(T_odom_key);
    chain.world.push_back(p);
    chain.ids.push_back(chain.graph.AddKeyMap(std::move(node)));
    KeyMapNode other;
    other.robot = 1;
    other.travel = static_cast<double>(v);
    other.scan_points = {Eigen::Vector2d(100.0, 100.0)};
    chain.graph.AddKeyMap(std::move(other));
  }
  return chain;
}

TEST(RefinementWindow, PlacesThePrecedingReturnsInTheKeyMapsFrameNewestFirst) {
  Chain chain = MakeChain(6);
  const int k = chain.ids[5];
  const std::vector<Eigen::Vector2d> window = RefinementWindow(chain.graph, k, 100.0, 1000);
  ASSERT_EQ(window.size(), 6U);  // its own and the five before, none of robot 1's
  const PointTransform to_k(chain.odom[5].Inverse());
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector2d expected = to_k(chain.world[static_cast<std::size_t>(5 - j)]);
    EXPECT_NEAR((window[static_cast<std::size_t>(j)] - expected).norm(), 0.0, 1e-12) << j;
  }
}

TEST(RefinementWindow, StopsAtTheTravelAndThePointBudget) {
  Chain chain = MakeChain(6);
  const int k = chain.ids[5];
  // Travel: key maps 1 m apart; 2.5 m reaches back two.
  EXPECT_EQ(RefinementWindow(chain.graph, k, 2.5, 1000).size(), 3U);
  EXPECT_EQ(RefinementWindow(chain.graph, k, 0.0, 1000).size(), 1U);
  // Budget: stops once it holds at least max_points.
  EXPECT_EQ(RefinementWindow(chain.graph, k, 100.0, 4).size(), 4U);
  EXPECT_EQ(RefinementWindow(chain.graph, k, 100.0, 1).size(), 1U);
  // The first key map has no predecessor.
  EXPECT_EQ(RefinementWindow(chain.graph, chain.ids[0], 100.0, 1000).size(), 1U);
}

}  // namespace
}  // namespace gridslam::pipeline
