// The component joiner with a scripted aligner: two robots drive the same corridor, each
// mapping in its own frame; the joiner moves one into the other's frame and catches up.
#include "gridslam/pipeline/component_joiner.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "gridslam/pipeline/two_robot_corridor_testing.hpp"

namespace gridslam::pipeline {
namespace {

using loop_closure::Match;

using testing::ScriptedAligner;
using testing::Team;

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
