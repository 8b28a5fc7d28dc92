// The join verifier on two robots driving one corridor (two_robot_corridor_testing.hpp): a lone
// match is confirmed by the key maps around it when it is right, and refused when it is wrong,
// when only ridges agree, or when nothing independent of it does. The same inside one map: a
// loop met by one appearance match beyond the prior search's reach.
#include "gridslam/pipeline/join_verifier.hpp"

#include <cmath>
#include <utility>
#include <vector>

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

// One robot drives a corridor (y = 0, ids 0-14, key maps every 2 m), goes round a 100 m loop
// and drives it again beside its first pass (y = 1, ids 15-29), its estimate drifted by 6 m and
// 0.1 rad: farther than the prior search reaches, so only an appearance match meets the loop.
struct Loop {
  KeyMapGraph graph{1, {}};
  std::vector<Pose2> truth;
  explicit Loop(const Pose2& drift = Pose2(6.0, -2.0, 0.1)) {
    for (int pass = 0; pass < 2; ++pass) {
      for (int v = 0; v < 15; ++v) {
        truth.emplace_back(2.0 * v, pass, 0.0);
        KeyMapNode node;
        node.robot = 0;
        node.travel = 2.0 * v + 128.0 * pass;
        node.T_odom_key = pass == 0 ? truth.back() : drift * truth.back();
        node.alignable = true;
        testing::AppendKeyMap(&graph, std::move(node), pass == 1 && v == 0 ? 100.0 : 2.0);
      }
    }
  }
  [[nodiscard]] Match Closure(int i, int k) const {
    return {i, k, Between(truth[static_cast<std::size_t>(i)], truth[static_cast<std::size_t>(k)])};
  }
};

TEST(JoinVerifier, ConfirmsALoopInsideOneMapWithTheKeyMapsAroundIt) {
  const Loop loop;
  const loop_closure::LoopClosureOptions options;  // loop verification on by default
  ASSERT_GT(options.loop_verification_travel, 0.0);
  ScriptedAligner aligner(loop.truth, 3.0);
  const JoinVerifier verifier(options);
  const JoinVerifier::Result result =
      verifier.Verify(loop.Closure(10, 25), {}, loop.graph, aligner);
  ASSERT_FALSE(result.matches.empty());
  bool independent = false;
  for (const Match& m : result.matches) {
    // Second pass against first pass, never the path just driven.
    EXPECT_LT(m.i, 15);
    EXPECT_GE(m.k, 15);
    EXPECT_TRUE(IsApprox(m.T_i_k, loop.Closure(m.i, m.k).T_i_k, 1e-9, 1e-9));
    independent = independent || loop_closure::Independent(result.matches.front(), m, loop.graph,
                                                           options.independent_travel);
  }
  EXPECT_TRUE(independent);

  // Aliased 4 m along the corridor: the key maps around it do not agree.
  Match aliased = loop.Closure(10, 25);
  aliased.T_i_k = Pose2(aliased.T_i_k.x() - 4.0, aliased.T_i_k.y(), aliased.T_i_k.theta());
  EXPECT_TRUE(verifier.Verify(aliased, {}, loop.graph, aligner).matches.empty());

  // A waiting match of the same revisit that disagrees refuses it; one of another revisit (its
  // newer key map far along the path) is no evidence either way.
  Match same_revisit = loop.Closure(8, 23);
  same_revisit.T_i_k = Pose2(same_revisit.T_i_k.x() + 5.0, same_revisit.T_i_k.y(), 0.5);
  EXPECT_TRUE(
      verifier.Verify(loop.Closure(10, 25), {same_revisit}, loop.graph, aligner).matches.empty());
  Match other_revisit = loop.Closure(2, 3);
  other_revisit.T_i_k = Pose2(0.0, 7.0, 1.0);
  EXPECT_FALSE(
      verifier.Verify(loop.Closure(10, 25), {other_revisit}, loop.graph, aligner).matches.empty());

  // The revisit already has a closure, and the hypothesis moves the map against it: refused (a
  // look-alike); a closure that agrees with it does not stand in its way.
  Loop closed;
  closed.graph.AddLoopEdge(closed.Closure(7, 22), ClosureOutcome::kAccepted, false,
                           Information(0.05, 0.01), 1.0);
  EXPECT_FALSE(verifier.Verify(closed.Closure(10, 25), {}, closed.graph, aligner).matches.empty());
  Loop contradicted;
  Match shifted = contradicted.Closure(7, 22);
  shifted.T_i_k = Pose2(shifted.T_i_k.x() + 3.0, shifted.T_i_k.y(), shifted.T_i_k.theta());
  contradicted.graph.AddLoopEdge(shifted, ClosureOutcome::kAccepted, false, Information(0.05, 0.01),
                                 1.0);
  EXPECT_TRUE(verifier.Verify(contradicted.Closure(10, 25), {}, contradicted.graph, aligner)
                  .matches.empty());

  // Off: nothing is tried.
  loop_closure::LoopClosureOptions off = options;
  off.loop_verification_travel = 0.0;
  aligner.calls = 0;
  EXPECT_TRUE(
      JoinVerifier(off).Verify(loop.Closure(10, 25), {}, loop.graph, aligner).matches.empty());
  EXPECT_EQ(aligner.calls, 0);
}

// A corridor of identical bays `period` apart along x: the features and the refinement find the
// copy of the true pose nearest the prior (any copy when there is none), if it overlaps.
class BaysAligner : public Aligner {
 public:
  BaysAligner(std::vector<Pose2> truth, double range, double period)
      : truth_(std::move(truth)), range_(range), period_(period) {}
  std::optional<Alignment> Align(int i, int k, const Pose2* prior, double) override {
    const Pose2 T =
        Between(truth_[static_cast<std::size_t>(i)], truth_[static_cast<std::size_t>(k)]);
    const double shift =
        prior == nullptr ? 0.0 : period_ * std::round((prior->x() - T.x()) / period_);
    const Pose2 copy(T.x() + shift, T.y(), T.theta());
    if (copy.translation().norm() > range_) {
      return std::nullopt;
    }
    return Alignment{copy, false};
  }

 private:
  std::vector<Pose2> truth_;
  double range_;
  double period_;
};

TEST(JoinVerifier, RefusesALoopTheUncorrectedMapExplainsAsWell) {
  const loop_closure::LoopClosureOptions options;
  const JoinVerifier verifier(options);
  // The second pass's estimate is right; the appearance match is the next bay, 4 m along.
  const Loop right_map(Pose2(0.0, 0.0, 0.0));
  BaysAligner bays(right_map.truth, 5.0, 4.0);
  Match next_bay = right_map.Closure(10, 25);
  next_bay.T_i_k = Pose2(next_bay.T_i_k.x() - 4.0, next_bay.T_i_k.y(), next_bay.T_i_k.theta());
  // Aligned where the hypothesis places them, the key maps around it agree with it (the bays
  // look alike) ...
  const JoinVerifier::Result refused = verifier.Verify(next_bay, {}, right_map.graph, bays);
  EXPECT_TRUE(refused.matches.empty());
  // ... and as the map places them, they agree with it too: refused. The aligner was asked
  // about both (more alignments than the hypothesis's own).
  long hypothesis_only = 0;
  {
    loop_closure::LoopClosureOptions without_rival = options;
    without_rival.min_consistent_gated = 1000;  // fails on its own support: no rival tried
    BaysAligner counting(right_map.truth, 5.0, 4.0);
    hypothesis_only =
        JoinVerifier(without_rival).Verify(next_bay, {}, right_map.graph, counting).alignments;
  }
  EXPECT_GT(refused.alignments, hypothesis_only);

  // A real drift (6 m, 0.1 rad): the uncorrected map's alignments find a bay, but not where the
  // map places the key maps (off across the corridor and in heading): the loop is confirmed.
  const Loop drifted;
  BaysAligner drifted_bays(drifted.truth, 5.0, 4.0);
  const JoinVerifier::Result confirmed =
      verifier.Verify(drifted.Closure(10, 25), {}, drifted.graph, drifted_bays);
  ASSERT_FALSE(confirmed.matches.empty());
  for (const Match& m : confirmed.matches) {
    EXPECT_TRUE(IsApprox(m.T_i_k, drifted.Closure(m.i, m.k).T_i_k, 1e-9, 1e-9));
  }
}

}  // namespace
}  // namespace gridslam::pipeline
