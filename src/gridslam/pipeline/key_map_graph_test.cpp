// The key-map graph on synthetic graphs: chained estimates, the optimizer seeing exactly the
// active edges (also after a join), pruning of a wrong closure with the final optimum, events.
#include "gridslam/pipeline/key_map_graph.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "gridslam/pose_graph/edge_error.hpp"

namespace gridslam::pipeline {
namespace {

using loop_closure::Match;

const Eigen::Matrix3d kSequential = Information(0.05, 0.01);
const Eigen::Matrix3d kLoop = Information(0.03, 0.005);

/// Key maps of `robot` at the front-end poses `odom` (travel = their index in metres).
std::vector<int> AddRobot(KeyMapGraph& graph, int robot, const std::vector<Pose2>& odom) {
  std::vector<int> ids;
  for (std::size_t v = 0; v < odom.size(); ++v) {
    KeyMapNode node;
    node.robot = robot;
    node.travel = static_cast<double>(v);
    node.T_odom_key = odom[v];
    node.alignable = true;
    const int previous = graph.LastKeyMap(robot);
    ids.push_back(graph.AddKeyMap(std::move(node)));
    if (previous >= 0) {
      EdgeRecord edge;
      edge.from = previous;
      edge.to = ids.back();
      edge.T_from_to = Between(odom[v - 1], odom[v]);
      edge.information = kSequential;
      graph.AddEdge(edge, 1.0);
    }
  }
  return ids;
}

/// A 4 m square walked once and a bit (key maps every metre), with a drifting heading.
std::vector<Pose2> Square(double drift_per_key_map) {
  std::vector<Pose2> truth;
  for (int side = 0; side < 4; ++side) {
    for (int step = 0; step < 4; ++step) {
      const double a = side * std::numbers::pi / 2;
      const Pose2 corner = side == 0   ? Pose2(0, 0, a)
                           : side == 1 ? Pose2(4, 0, a)
                           : side == 2 ? Pose2(4, 4, a)
                                       : Pose2(0, 4, a);
      truth.push_back(corner * Pose2(step, 0, 0));
    }
  }
  std::vector<Pose2> odom = {truth[0]};
  for (std::size_t v = 1; v < truth.size(); ++v) {
    odom.push_back(odom.back() * Between(truth[v - 1], truth[v]) * Pose2(0, 0, drift_per_key_map));
  }
  return odom;
}

// χ² of a loop edge measuring T_i_k with `information`, when k sits at T_i_k moved by
// `offset_in_i` (in i's frame) from i at X_i.
double LoopChi2(const Eigen::Matrix3d& information, const Pose2& X_i, const Pose2& T_i_k,
                const Eigen::Vector2d& offset_in_i) {
  const Eigen::Vector3d z(T_i_k.x(), T_i_k.y(), T_i_k.theta());
  const Pose2 X_k =
      X_i * Pose2(T_i_k.x() + offset_in_i.x(), T_i_k.y() + offset_in_i.y(), T_i_k.theta());
  const Eigen::Vector3d e = pose_graph::EdgeError(Eigen::Vector3d(X_i.x(), X_i.y(), X_i.theta()),
                                                  Eigen::Vector3d(X_k.x(), X_k.y(), X_k.theta()), z,
                                                  std::cos(z.z()), std::sin(z.z()));
  return e.dot(information * e);
}

// A ridge's loop edge has only the search window's information along its free axis: moving k
// along it (in i's frame) costs what a 5 m standard deviation says, moving it across what a full
// closure costs.
TEST(LoopInformation, ARidgeEdgeCostsNothingAlongItsFreeAxis) {
  const Eigen::Vector2d axis = Eigen::Vector2d(1.0, 2.0).normalized();  // in i's frame
  const Pose2 T_i_k(4.0, -1.0, 0.7);
  const Match ridge{0, 1, T_i_k, axis, /*free_sigma=*/5.0};
  const Eigen::Matrix3d information = LoopInformation(ridge, 0.03, 0.005);
  EXPECT_TRUE(LoopInformation(Match{0, 1, T_i_k}, 0.03, 0.005).isApprox(kLoop));
  const Pose2 X_i(1.0, 2.0, -0.4);
  const auto chi2 = [&](const Eigen::Vector2d& offset_in_i) {
    return LoopChi2(information, X_i, T_i_k, offset_in_i);
  };
  EXPECT_NEAR(chi2(Eigen::Vector2d::Zero()), 0.0, 1e-12);
  EXPECT_NEAR(chi2(2.5 * axis), 2.5 * 2.5 / (5.0 * 5.0), 1e-9);
  EXPECT_GT(information.determinant(), 0.0);
  const Eigen::Vector2d across(-axis.y(), axis.x());
  EXPECT_NEAR(chi2(0.1 * across), 0.1 * 0.1 / (0.03 * 0.03), 1e-6);
  EXPECT_TRUE(std::isinf(LoopUncertaintyWeight(ridge, 0.5)));
  EXPECT_EQ(LoopUncertaintyWeight(Match{0, 1, T_i_k}, 0.5), 0.5);
}

// A weak axis (a corridor placed by the search's peak) lowers the information along it to its
// sigma (never more information than a full closure's) and keeps it across.
TEST(LoopInformation, AWeakAxisHasTheSearchsPrecisionAlongIt) {
  const Eigen::Vector2d axis = Eigen::Vector2d(2.0, -1.0).normalized();  // in i's frame
  const Pose2 T_i_k(3.0, 1.0, -0.6);
  Match weak{0, 1, T_i_k};
  weak.weak_axis = axis;
  weak.weak_sigma = 0.12;
  const Eigen::Matrix3d information = LoopInformation(weak, 0.03, 0.005);
  const Pose2 X_i(-1.0, 0.5, 0.9);
  EXPECT_NEAR(LoopChi2(information, X_i, T_i_k, 0.2 * axis), 0.2 * 0.2 / (0.12 * 0.12), 1e-9);
  const Eigen::Vector2d across(-axis.y(), axis.x());
  EXPECT_NEAR(LoopChi2(information, X_i, T_i_k, 0.1 * across), 0.1 * 0.1 / (0.03 * 0.03), 1e-6);
  EXPECT_TRUE(std::isfinite(LoopUncertaintyWeight(weak, 0.5)));
  weak.weak_sigma = 0.01;  // finer than a full closure: a full closure's information
  EXPECT_TRUE(LoopInformation(weak, 0.03, 0.005).isApprox(kLoop));
}

TEST(KeyMapGraph, ChainsEstimatesFromTheFrontEndAndAnchorsEachRobot) {
  KeyMapGraph graph(2, {});
  const std::vector<int> a = AddRobot(graph, 0, {Pose2(1, 2, 0.1), Pose2(2, 2, 0.1)});
  const std::vector<int> b = AddRobot(graph, 1, {Pose2(5, 5, 1.0), Pose2(5, 6, 1.0)});
  EXPECT_TRUE(IsApprox(graph.Estimate(a[1]), Pose2(2, 2, 0.1), 1e-12, 1e-12));
  EXPECT_EQ(graph.node(b[1]).previous, b[0]);
  EXPECT_EQ(graph.node(b[0]).previous, -1);
  EXPECT_NE(graph.Component(a[0]), graph.Component(b[0]));
  const pose_graph::PoseGraph& active = graph.ActiveGraph();
  EXPECT_EQ(active.num_edges(), 2U);
  EXPECT_TRUE(active.vertex(active.IndexOf(a[0])).fixed);
  EXPECT_TRUE(active.vertex(active.IndexOf(b[0])).fixed);
}

TEST(KeyMapGraph, MergeMovesTheComponentAndTheOptimizerSeesTheJoinEdges) {
  KeyMapGraph graph(2, {});
  const std::vector<Pose2> line = {Pose2(0, 0, 0), Pose2(1, 0, 0), Pose2(2, 0, 0)};
  const std::vector<int> a = AddRobot(graph, 0, line);
  const std::vector<int> b = AddRobot(graph, 1, line);  // truth: robot 1 at y = 1
  const Pose2 T_a_b(0, 1, 0);
  graph.MergeComponents(0, 1, T_a_b, Time{});
  EXPECT_EQ(graph.Component(a[0]), graph.Component(b[0]));
  EXPECT_TRUE(IsApprox(graph.Estimate(b[2]), Pose2(2, 1, 0), 1e-12, 1e-12));
  graph.AddLoopEdge({a[1], b[1], Pose2(0, 1, 0)}, ClosureOutcome::kJoined, true, kLoop, 0.5);
  graph.AddLoopEdge({a[2], b[2], Pose2(0, 1, 0)}, ClosureOutcome::kJoined, true, kLoop, 0.5);
  const pose_graph::PoseGraph& active = graph.ActiveGraph();
  EXPECT_EQ(active.num_edges(), graph.edges().size());
  int fixed = 0;
  for (const pose_graph::Vertex& v : active.vertices()) {
    fixed += v.fixed ? 1 : 0;
  }
  EXPECT_EQ(fixed, 1);  // one anchor for the merged component
  EXPECT_NEAR(pose_graph::Chi2(active), 0.0, 1e-12);
  EXPECT_EQ(graph.NumClosures(ClosureOutcome::kJoined), 2);
  // The uncertainty distance runs through the join edges.
  EXPECT_NEAR(graph.DistancesFrom(a[2])[static_cast<std::size_t>(b[2])], 0.5, 1e-12);
}

TEST(KeyMapGraph, FinalOptimizationRemovesAWrongClosureAndEndsAtTheOptimum) {
  KeyMapGraph graph(1, {});
  const std::vector<Pose2> odom = Square(0.01);
  const std::vector<int> ids = AddRobot(graph, 0, odom);
  // Correct closure: key map 15 is 1 m before the start along -y (truth (0, 1, -pi/2)).
  const Pose2 truth_15 = Pose2(0, 4, 3 * std::numbers::pi / 2) * Pose2(3, 0, 0);
  graph.AddLoopEdge({ids[0], ids[15], Between(Pose2(0, 0, 0), truth_15)}, ClosureOutcome::kAccepted,
                    false, kLoop, 0.5);
  // A wrong one: claims key map 12 sits on key map 2.
  const int wrong = graph.AddLoopEdge({ids[2], ids[12], Pose2(0.2, 0, 0)},
                                      ClosureOutcome::kAccepted, false, kLoop, 0.5);
  graph.DrainEvents();
  const KeyMapGraph::FinalResult result =
      graph.OptimizeAndPrune({}, "gn", /*prune_rounds=*/1, /*prune_chi2=*/25.0);
  EXPECT_EQ(result.pruned, 1);
  EXPECT_EQ(graph.closures()[static_cast<std::size_t>(wrong)].outcome, ClosureOutcome::kPruned);
  EXPECT_EQ(graph.closures()[0].outcome, ClosureOutcome::kAccepted);
  const pose_graph::PoseGraph& final_graph = graph.ActiveGraph();
  EXPECT_EQ(final_graph.num_edges(), graph.edges().size() - 1);
  // chi2 reported = chi2 of the graph that remains, and that graph is at its optimum.
  EXPECT_NEAR(result.chi2, pose_graph::Chi2(final_graph), 1e-9 * (1.0 + result.chi2));
  pose_graph::PoseGraph again = final_graph;
  pose_graph::OptimizerOptions gn;
  gn.method = "gn";
  pose_graph::Optimize(again, gn);
  EXPECT_GE(pose_graph::Chi2(again), result.chi2 - 1e-6 * (1.0 + result.chi2));
  // The correct closure pulled the drift out: key map 15 near its true pose.
  EXPECT_TRUE(IsApprox(graph.Estimate(ids[15]), truth_15, 0.05, 0.02));
  const std::vector<MapperEvent> events = graph.DrainEvents();
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].kind, MapperEvent::Kind::kClosureRemoved);
  EXPECT_EQ(events[0].closure, wrong);
}

TEST(KeyMapGraph, NothingIsPrunedWhenEveryClosureFits) {
  KeyMapGraph graph(1, {});
  const std::vector<int> ids = AddRobot(graph, 0, Square(0.0));
  const Pose2 truth_15 = Pose2(0, 4, 3 * std::numbers::pi / 2) * Pose2(3, 0, 0);
  graph.AddLoopEdge({ids[0], ids[15], Between(Pose2(0, 0, 0), truth_15)}, ClosureOutcome::kAccepted,
                    false, kLoop, 0.5);
  const KeyMapGraph::FinalResult result = graph.OptimizeAndPrune({}, "gn", 3, 25.0);
  EXPECT_EQ(result.pruned, 0);
  EXPECT_NEAR(result.chi2, 0.0, 1e-9);
}

TEST(KeyMapGraph, GatedClosureAcceptedLaterBecomesOneEdge) {
  KeyMapGraph graph(1, {});
  const std::vector<int> ids = AddRobot(graph, 0, Square(0.0));
  const Match m{ids[0], ids[15], Pose2(0, 1, -std::numbers::pi / 2)};
  graph.RecordClosure(m, ClosureOutcome::kGated, false);
  EXPECT_EQ(graph.NumClosures(ClosureOutcome::kGated), 1);
  const std::size_t edges = graph.edges().size();
  graph.AcceptGated(m, kLoop, 0.5);
  EXPECT_EQ(graph.NumClosures(ClosureOutcome::kGated), 0);
  EXPECT_EQ(graph.NumClosures(ClosureOutcome::kAccepted), 1);
  ASSERT_EQ(graph.edges().size(), edges + 1);
  EXPECT_EQ(graph.edges().back().closure, 0);
  EXPECT_EQ(graph.ActiveGraph().num_edges(), edges + 1);
  EXPECT_EQ(graph.loop_edges_added(), 1);
}

TEST(KeyMapGraph, QueuesEventsInOrder) {
  KeyMapGraph graph(2, {});
  const std::vector<int> a = AddRobot(graph, 0, {Pose2(), Pose2(1, 0, 0)});
  const std::vector<int> b = AddRobot(graph, 1, {Pose2()});
  graph.MergeComponents(0, 1, Pose2(0, 1, 0), Time{});
  graph.AddLoopEdge({a[0], b[0], Pose2(0, 1, 0)}, ClosureOutcome::kJoined, true, kLoop, 0.5);
  const std::vector<MapperEvent> events = graph.DrainEvents();
  ASSERT_EQ(events.size(), 5U);
  EXPECT_EQ(events[0].kind, MapperEvent::Kind::kKeyMapAdded);
  EXPECT_EQ(events[2].kind, MapperEvent::Kind::kKeyMapAdded);
  EXPECT_EQ(events[2].robot, 1);
  EXPECT_EQ(events[3].kind, MapperEvent::Kind::kRobotsJoined);
  EXPECT_EQ(events[4].kind, MapperEvent::Kind::kClosureAccepted);
  EXPECT_TRUE(graph.DrainEvents().empty());
}

}  // namespace
}  // namespace gridslam::pipeline
