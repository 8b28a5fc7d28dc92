// The join verifier on two robots driving one corridor (two_robot_corridor_testing.hpp): a lone
// match is confirmed by the key maps around it when it is right, and refused when it is wrong,
// when only ridges agree, or when nothing independent of it does.
#include "gridslam/pipeline/join_verifier.hpp"

#include <gtest/gtest.h>

#include "gridslam/pipeline/two_robot_corridor_testing.hpp"

namespace gridslam::pipeline {
namespace {

using loop_closure::Match;
using testing::ScriptedAligner;
using testing::Team;

// Robot 1's odometry frame far from robot 0's: before a join the components share nothing.
const Pose2 kRobot1Frame(50.0, -20.0, 1.0);

// The verifier as a user switches it on (off by default).
loop_closure::LoopClosureOptions Options() {
  loop_closure::LoopClosureOptions options;
  options.join_verification_travel = 20.0;
  return options;
}

TEST(JoinVerifier, ConfirmsARightMatchWithTheKeyMapsAroundIt) {
  const Team team(kRobot1Frame);
  const loop_closure::LoopClosureOptions options = Options();
  ScriptedAligner aligner(team.truth, 3.0);
  const JoinVerifier verifier(options);
  // Robot 1's key map 25 (x = 20) met robot 0's key map 10 (x = 20).
  const JoinVerifier::Result result =
      verifier.Verify(team.Closure(10, 25), {}, team.graph, aligner);
  ASSERT_FALSE(result.matches.empty());
  EXPECT_EQ(result.matches.front().i, 10);
  EXPECT_EQ(result.matches.front().k, 25);
  EXPECT_EQ(result.alignments, aligner.calls);
  bool independent = false;
  for (const Match& m : result.matches) {
    EXPECT_EQ(team.graph.Robot(m.i), 0);
    EXPECT_EQ(team.graph.Robot(m.k), 1);
    EXPECT_TRUE(IsApprox(m.T_i_k, team.Closure(m.i, m.k).T_i_k, 1e-9, 1e-9));
    independent = independent || loop_closure::Independent(result.matches.front(), m, team.graph,
                                                           options.independent_travel);
  }
  EXPECT_TRUE(independent);
  // Robot 1's other key maps within join_verification_travel (20 m) of key map 25, 14 of them,
  // each with at most its two nearest key maps of robot 0.
  EXPECT_LE(result.alignments, 2 * 14);
  // From key map 29 (x = 28) only the ten within 20 m of its path: robot 1's first four are not.
  aligner.calls = 0;
  EXPECT_LE(verifier.Verify(team.Closure(14, 29), {}, team.graph, aligner).alignments, 2 * 10);
}

TEST(JoinVerifier, RefusesAMatchTheKeyMapsAroundItContradict) {
  const Team team(kRobot1Frame);
  const loop_closure::LoopClosureOptions options = Options();
  ScriptedAligner aligner(team.truth, 3.0);
  // An aliased match: robot 1's key map 25 placed 4 m further along robot 0's corridor.
  Match aliased = team.Closure(10, 25);
  aliased.T_i_k = Pose2(aliased.T_i_k.x() - 4.0, aliased.T_i_k.y(), aliased.T_i_k.theta());
  const JoinVerifier verifier(options);
  EXPECT_TRUE(verifier.Verify(aliased, {}, team.graph, aligner).matches.empty());
}

TEST(JoinVerifier, RefusesAMatchAWaitingMatchContradicts) {
  const Team team(kRobot1Frame);
  const loop_closure::LoopClosureOptions options = Options();
  ScriptedAligner aligner(team.truth, 3.0);
  const JoinVerifier verifier(options);
  // A waiting match found from robot 1's side (i in robot 1) that agrees: still confirmed.
  const std::vector<Match> agreeing = {team.Closure(20, 5)};
  EXPECT_FALSE(
      verifier.Verify(team.Closure(10, 25), agreeing, team.graph, aligner).matches.empty());
  // One that places robot 1 elsewhere: the evidence conflicts, nothing is tried.
  Match elsewhere = team.Closure(3, 18);
  elsewhere.T_i_k = Pose2(elsewhere.T_i_k.x() + 6.0, elsewhere.T_i_k.y(), 3.0);
  aligner.calls = 0;
  EXPECT_TRUE(
      verifier.Verify(team.Closure(10, 25), {elsewhere}, team.graph, aligner).matches.empty());
  EXPECT_EQ(aligner.calls, 0);
}

TEST(JoinVerifier, RidgesAreNoEvidence) {
  const Team team(kRobot1Frame);
  const loop_closure::LoopClosureOptions options = Options();
  ScriptedAligner aligner(team.truth, 3.0);
  aligner.free_axis = Eigen::Vector2d::UnitX();  // every alignment: along the corridor unknown
  const JoinVerifier verifier(options);
  EXPECT_TRUE(verifier.Verify(team.Closure(10, 25), {}, team.graph, aligner).matches.empty());
}

TEST(JoinVerifier, NeedsAnAgreeingKeyMapIndependentOfTheMatch) {
  const Team team(kRobot1Frame);
  loop_closure::LoopClosureOptions options = Options();
  ScriptedAligner aligner(team.truth, 3.0);
  // Key maps 2 m apart: within 3 m of path only key maps 2 m from the match are tried, and none
  // is independent of it (independent_travel 5 m).
  options.join_verification_travel = 3.0;
  EXPECT_TRUE(
      JoinVerifier(options).Verify(team.Closure(10, 25), {}, team.graph, aligner).matches.empty());
  // Off: nothing is tried.
  options.join_verification_travel = 0.0;
  aligner.calls = 0;
  const JoinVerifier::Result off =
      JoinVerifier(options).Verify(team.Closure(10, 25), {}, team.graph, aligner);
  EXPECT_TRUE(off.matches.empty());
  EXPECT_EQ(aligner.calls, 0);
}

}  // namespace
}  // namespace gridslam::pipeline
