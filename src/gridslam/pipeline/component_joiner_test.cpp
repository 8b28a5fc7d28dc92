// The component joiner with a scripted aligner: two robots drive the same corridor, each
// mapping in its own frame; the joiner moves one into the other's frame and catches up.
#include "gridslam/pipeline/component_joiner.hpp"

#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::pipeline {
namespace {

using loop_closure::Match;

/// Answers with the true relative pose of key maps within `range` of each other (in truth),
/// or a scripted wrong answer.
class ScriptedAligner : public Aligner {
 public:
  ScriptedAligner(std::vector<Pose2> truth, double range)
      : truth_(std::move(truth)), range_(range) {}
  std::optional<Alignment> Align(int i, int k, const Pose2*, double) override {
    ++calls;
    if (const auto it = wrong.find({i, k}); it != wrong.end()) {
      return Alignment{it->second, false};
    }
    const Pose2& a = truth_[static_cast<std::size_t>(i)];
    const Pose2& b = truth_[static_cast<std::size_t>(k)];
    if ((a.translation() - b.translation()).norm() > range_) {
      return std::nullopt;
    }
    return Alignment{Between(a, b), false};
  }
  std::map<std::pair<int, int>, Pose2> wrong;
  int calls = 0;

 private:
  std::vector<Pose2> truth_;
  double range_;
};

struct Team {
  KeyMapGraph graph{2, {}};
  std::vector<Pose2> truth;
  /// Robot 0 along y = 0, robot 1 along y = 1 (key maps every 2 m), robot 1's odometry frame
  /// rotated and moved by `T_1_world`.
  explicit Team(const Pose2& T_1_world) {
    for (int r = 0; r < 2; ++r) {
      for (int v = 0; v < 15; ++v) {
        truth.emplace_back(2.0 * v, r, 0.0);
        KeyMapNode node;
        node.robot = r;
        node.travel = 2.0 * v;
        node.T_odom_key = r == 0 ? truth.back() : T_1_world * truth.back();
        node.alignable = true;
        const int previous = graph.LastKeyMap(r);
        const int id = graph.AddKeyMap(std::move(node));
        if (previous >= 0) {
          EdgeRecord edge;
          edge.from = previous;
          edge.to = id;
          edge.T_from_to = Between(graph.node(previous).T_odom_key, graph.node(id).T_odom_key);
          edge.information = Information(0.02, 0.005);
          graph.AddEdge(edge, 2.0);
        }
      }
    }
  }
  [[nodiscard]] Match Closure(int i, int k) const {
    return {i, k, Between(truth[static_cast<std::size_t>(i)], truth[static_cast<std::size_t>(k)])};
  }
};

TEST(ComponentJoiner, JoinsIntoTheOlderFrameAndCatchesUp) {
  Team team(Pose2(50.0, -20.0, 1.0));
  loop_closure::LoopClosureOptions options;
  loop_closure::ClosureArbiter arbiter(options);
  ScriptedAligner aligner(team.truth, 1.5);
  const ComponentJoiner joiner(options, 0.5, {});
  const std::vector<Match> matches = {team.Closure(3, 18), team.Closure(10, 25)};
  const ComponentJoiner::Result result = joiner.Join(matches, Time{}, team.graph, arbiter, aligner);
  EXPECT_EQ(result.join.robot_a, 0);
  EXPECT_EQ(result.join.robot_b, 1);
  EXPECT_EQ(result.join.matches, 2);
  EXPECT_EQ(team.graph.Component(0), team.graph.Component(15));
  // Robot 1 in robot 0's frame: at its true poses.
  for (int id = 15; id < 30; ++id) {
    EXPECT_TRUE(
        IsApprox(team.graph.Estimate(id), team.truth[static_cast<std::size_t>(id)], 1e-3, 1e-4))
        << id;
  }
  EXPECT_GT(result.caught_up, 5);
  EXPECT_EQ(result.alignments, aligner.calls);
  EXPECT_EQ(team.graph.NumClosures(ClosureOutcome::kJoined), 2);
  EXPECT_EQ(team.graph.NumClosures(ClosureOutcome::kAccepted), result.caught_up);
  // The optimizer holds every edge.
  EXPECT_EQ(team.graph.ActiveGraph().num_edges(), team.graph.edges().size());
}

TEST(ComponentJoiner, CatchUpRefusesAnAlignmentNothingSupports) {
  Team team(Pose2(50.0, -20.0, 1.0));
  loop_closure::LoopClosureOptions options;
  loop_closure::ClosureArbiter arbiter(options);
  ScriptedAligner aligner(team.truth, 1.5);
  // Robot 1's key map 20 (x = 10) aligned with robot 0's key map 5 (x = 10): 2 m off.
  aligner.wrong[{5, 20}] = Pose2(2.0, 1.0, 0.0);
  const ComponentJoiner joiner(options, 0.5, {});
  joiner.Join({team.Closure(3, 18), team.Closure(10, 25)}, Time{}, team.graph, arbiter, aligner);
  for (const ClosureRecord& c : team.graph.closures()) {
    EXPECT_FALSE(c.from == 5 && c.to == 20) << "the wrong alignment became a loop edge";
  }
  EXPECT_TRUE(IsApprox(team.graph.Estimate(20), team.truth[20], 1e-3, 1e-4));
}

TEST(ComponentJoiner, ForgetsTheJoinMatchesNowInsideOneComponent) {
  Team team(Pose2(50.0, -20.0, 1.0));
  loop_closure::LoopClosureOptions options;
  loop_closure::ClosureArbiter arbiter(options);
  ASSERT_EQ(arbiter.OfferJoin(team.Closure(3, 18), team.graph).verdict,
            loop_closure::Verdict::kWait);
  const loop_closure::Decision d = arbiter.OfferJoin(team.Closure(10, 25), team.graph);
  ASSERT_EQ(d.verdict, loop_closure::Verdict::kAcceptGroup);
  ScriptedAligner aligner(team.truth, 1.5);
  const ComponentJoiner joiner(options, 0.5, {});
  joiner.Join(d.accepted, Time{}, team.graph, arbiter, aligner);
  EXPECT_TRUE(arbiter.joinable().empty());
}

}  // namespace
}  // namespace gridslam::pipeline
