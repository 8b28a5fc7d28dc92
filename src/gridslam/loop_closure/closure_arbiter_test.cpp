// The closure arbiter on synthetic graphs (in the style of Cartographer's pose_graph_2d_test):
// key maps on a line or a square with known estimates; matches are scripted from a ground truth
// that differs from the estimate where the test wants the estimate to be wrong.
#include "gridslam/loop_closure/closure_arbiter.hpp"

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::loop_closure {
namespace {

/// A graph given by its estimates; travel = distance along the vertex order per robot.
class FakeGraph : public GraphView {
 public:
  int Add(int robot, const Pose2& estimate, double travel, int component = -1) {
    estimates_.push_back(estimate);
    robots_.push_back(robot);
    travel_.push_back(travel);
    components_.push_back(component < 0 ? robot : component);
    return static_cast<int>(estimates_.size()) - 1;
  }
  [[nodiscard]] Pose2 Estimate(int id) const override { return estimates_.at(Index(id)); }
  [[nodiscard]] double Travel(int id) const override { return travel_.at(Index(id)); }
  [[nodiscard]] int Robot(int id) const override { return robots_.at(Index(id)); }
  [[nodiscard]] int Component(int id) const override { return components_.at(Index(id)); }
  void SetComponent(int robot, int component) {
    for (std::size_t v = 0; v < robots_.size(); ++v) {
      if (robots_[v] == robot) {
        components_[v] = component;
      }
    }
  }

 private:
  static std::size_t Index(int id) { return static_cast<std::size_t>(id); }
  std::vector<Pose2> estimates_;
  std::vector<int> robots_;
  std::vector<double> travel_;
  std::vector<int> components_;
};

/// The measurement of k in i's frame if the true poses were `truth_i`, `truth_k`.
Match Measure(int i, int k, const Pose2& truth_i, const Pose2& truth_k) {
  return {i, k, Between(truth_i, truth_k)};
}

/// One robot driving along x, a key map per metre; estimates of key maps >= `drift_from` are
/// shifted by `drift` (the truth is the straight line).
struct Line {
  FakeGraph graph;
  std::vector<Pose2> truth;
  Line(int n, int drift_from, const Pose2& drift) {
    for (int v = 0; v < n; ++v) {
      truth.emplace_back(v * 1.0, 0.0, 0.0);
      graph.Add(0, v >= drift_from ? drift * truth.back() : truth.back(), v * 1.0);
    }
  }
  [[nodiscard]] Match Closure(int i, int k) const {
    return Measure(i, k, truth[static_cast<std::size_t>(i)], truth[static_cast<std::size_t>(k)]);
  }
};

TEST(ClosureOutcome, ToStringKeepsTheReportStrings) {
  EXPECT_EQ(ToString(ClosureOutcome::kAccepted), "accepted");
  EXPECT_EQ(ToString(ClosureOutcome::kGated), "gate");
  EXPECT_EQ(ToString(ClosureOutcome::kPending), "pending");
  EXPECT_EQ(ToString(ClosureOutcome::kJoined), "joined");
  EXPECT_EQ(ToString(ClosureOutcome::kPruned), "pruned");
}

TEST(ClosureArbiter, GateAcceptsAClosureThatAgreesWithTheEstimate) {
  const Line line(40, 1000, Pose2());
  ClosureArbiter arbiter{LoopClosureOptions{}};
  const Decision d = arbiter.OfferPrior(line.Closure(2, 30), /*u=*/5.0, false, line.graph);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_TRUE(d.in_gate);
  ASSERT_EQ(d.accepted.size(), 1U);
  EXPECT_EQ(d.accepted[0].i, 2);
  EXPECT_TRUE(arbiter.gated().empty());
}

TEST(ClosureArbiter, GateRejectsAClosureFarFromTheEstimateAndQueuesIt) {
  // The estimate says the newer key maps are 1 m off: the closure disagrees by 1 m.
  const Line line(40, 20, Pose2(0.0, 1.0, 0.0));
  ClosureArbiter arbiter{LoopClosureOptions{}};
  const Decision d = arbiter.OfferPrior(line.Closure(2, 30), 2.0, false, line.graph);
  EXPECT_EQ(d.verdict, Verdict::kWait);
  EXPECT_FALSE(d.in_gate);
  EXPECT_NEAR(d.error.translation().norm(), 1.0, 1e-9);
  ASSERT_EQ(arbiter.gated().size(), 1U);
  // The gate grows with the uncertainty distance: at u = 20 m the same error passes.
  ClosureArbiter wide{LoopClosureOptions{}};
  EXPECT_EQ(wide.OfferPrior(line.Closure(2, 30), 20.0, false, line.graph).verdict,
            Verdict::kAccept);
}

TEST(ClosureArbiter, AClosureFoundBySearchIsNeverTrustedAlone) {
  const Line line(40, 1000, Pose2());
  ClosureArbiter arbiter{LoopClosureOptions{}};
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(2, 30), 5.0, /*from_search=*/true, line.graph).verdict,
            Verdict::kWait);
}

TEST(ClosureArbiter, AcceptsAConsistentGroupOfGatedClosures) {
  const Line line(40, 20, Pose2(0.0, 1.0, 0.0));
  LoopClosureOptions options;
  ClosureArbiter arbiter(options);
  ASSERT_EQ(options.min_consistent_gated, 3);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(2, 30), 2.0, false, line.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(5, 31), 2.0, false, line.graph).verdict,
            Verdict::kWait);
  const Decision d = arbiter.OfferPrior(line.Closure(8, 32), 2.0, false, line.graph);
  EXPECT_EQ(d.verdict, Verdict::kAcceptGroup);
  ASSERT_EQ(d.accepted.size(), 3U);
  EXPECT_EQ(d.accepted[0].k, 32);  // the new one first
  EXPECT_EQ(d.accepted[1].k, 30);
  EXPECT_EQ(d.accepted[2].k, 31);
  EXPECT_TRUE(arbiter.gated().empty());
}

// A corridor met from its other end can match itself turned by pi, at every key map along it:
// a consistent group. Over a short path the estimate cannot be off by that much, so each match
// is refused and none waits to outvote the estimate; after a long path the same turn is heading
// drift the path can gather, and the group is accepted as before.
TEST(ClosureArbiter, PriorClosuresBeyondTheDriftOfTheirPathAreRefused) {
  const Line turned(40, 20, Pose2(0.0, 0.0, std::numbers::pi));
  LoopClosureOptions options;
  ClosureArbiter short_path(options);
  for (const auto& [i, k] : {std::pair{2, 30}, std::pair{5, 31}, std::pair{8, 32}}) {
    const Decision d = short_path.OfferPrior(turned.Closure(i, k), 10.0, false, turned.graph);
    EXPECT_EQ(d.verdict, Verdict::kReject);
    EXPECT_TRUE(d.accepted.empty());
    EXPECT_NEAR(std::abs(d.error.theta()), std::numbers::pi, 1e-9);
  }
  EXPECT_TRUE(short_path.gated().empty());
  ClosureArbiter long_path(options);
  ASSERT_GT(HeadingDriftBound(900.0, options), std::numbers::pi);
  EXPECT_EQ(long_path.OfferPrior(turned.Closure(2, 30), 900.0, false, turned.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(long_path.OfferPrior(turned.Closure(5, 31), 900.0, false, turned.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(long_path.OfferPrior(turned.Closure(8, 32), 900.0, false, turned.graph).verdict,
            Verdict::kAcceptGroup);
}

TEST(ClosureArbiter, BeyondDriftIsTheWithinMapBound) {
  LoopClosureOptions options;
  // Translation: max(max_correction, max_drift * u + |theta| * u / 2); rotation: the heading bound.
  EXPECT_FALSE(BeyondDrift(Pose2(9.9, 0.0, 0.0), 10.0, options));
  EXPECT_TRUE(BeyondDrift(Pose2(10.1, 0.0, 0.0), 10.0, options));
  EXPECT_FALSE(BeyondDrift(Pose2(14.9, 0.0, 0.0), 300.0, options));
  EXPECT_TRUE(BeyondDrift(Pose2(15.1, 0.0, 0.0), 300.0, options));
  EXPECT_FALSE(BeyondDrift(Pose2(0.0, 0.0, 0.49), 10.0, options));
  EXPECT_TRUE(BeyondDrift(Pose2(0.0, 0.0, 0.51), 10.0, options));
  EXPECT_FALSE(BeyondDrift(Pose2(0.0, 0.0, 1.5), 400.0, options));
}

// Two matches of one key map (its scans against two older key maps) repeat one piece of
// evidence: a look-alike seen from one key map is found from it twice. With a third key map's
// match they are not yet three.
TEST(ClosureArbiter, MatchesOfOneKeyMapCountOnceInAGatedGroup) {
  const Line line(40, 20, Pose2(0.0, 1.0, 0.0));
  LoopClosureOptions options;
  ClosureArbiter arbiter(options);
  ASSERT_EQ(options.min_consistent_gated, 3);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(2, 30), 2.0, false, line.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(5, 30), 2.0, false, line.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(8, 32), 2.0, false, line.graph).verdict,
            Verdict::kWait);
  const Decision d = arbiter.OfferPrior(line.Closure(9, 33), 2.0, false, line.graph);
  EXPECT_EQ(d.verdict, Verdict::kAcceptGroup);
  EXPECT_EQ(d.accepted.size(), 4U);  // all consistent matches, both of key map 30 included
  EXPECT_TRUE(arbiter.gated().empty());
}

// The prior search's wide window may hold a look-alike, and neighbouring key maps see it alike:
// three consistent wide-search matches of key maps a metre apart are one piece of evidence. A
// fourth match, far from the first along both paths, makes the group.
TEST(ClosureArbiter, AWideSearchGroupNeedsTwoIndependentMatches) {
  const Line line(40, 20, Pose2(0.0, 1.0, 0.0));
  LoopClosureOptions options;
  ASSERT_EQ(options.min_consistent_gated, 3);
  ASSERT_DOUBLE_EQ(options.independent_travel, 5.0);
  const auto wide = [&](int i, int k) {
    Match m = line.Closure(i, k);
    m.wide_search = true;
    return m;
  };
  ClosureArbiter arbiter(options);
  EXPECT_EQ(arbiter.OfferPrior(wide(2, 30), 2.0, true, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(wide(3, 31), 2.0, true, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(wide(4, 32), 2.0, true, line.graph).verdict, Verdict::kWait);
  const Decision d = arbiter.OfferPrior(wide(9, 36), 2.0, true, line.graph);
  EXPECT_EQ(d.verdict, Verdict::kAcceptGroup);
  EXPECT_EQ(d.accepted.size(), 4U);
  // The same three matches from the first window: accepted as before.
  ClosureArbiter narrow(options);
  EXPECT_EQ(narrow.OfferPrior(line.Closure(2, 30), 2.0, true, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(narrow.OfferPrior(line.Closure(3, 31), 2.0, true, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(narrow.OfferPrior(line.Closure(4, 32), 2.0, true, line.graph).verdict,
            Verdict::kAcceptGroup);
}

TEST(ClosureArbiter, InconsistentGatedClosuresStayQueued) {
  const Line line(40, 20, Pose2(0.0, 1.0, 0.0));
  ClosureArbiter arbiter{LoopClosureOptions{}};
  // Each wrong in its own way: the loops they form with the graph do not close.
  Match a = line.Closure(2, 30);
  Match b = line.Closure(5, 31);
  Match c = line.Closure(8, 32);
  b.T_i_k = b.T_i_k * Pose2(0.0, 2.0, 0.0);
  c.T_i_k = c.T_i_k * Pose2(0.0, -3.0, 0.0);
  EXPECT_EQ(arbiter.OfferPrior(a, 2.0, false, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(b, 2.0, false, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(c, 2.0, false, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(arbiter.gated().size(), 3U);
}

TEST(ClosureArbiter, GatedClosuresOutsideTheWindowDoNotSupport) {
  const Line line(80, 20, Pose2(0.0, 1.0, 0.0));
  LoopClosureOptions options;
  options.gated_window = 5;
  ClosureArbiter arbiter(options);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(2, 30), 2.0, false, line.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(5, 40), 2.0, false, line.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(8, 50), 2.0, false, line.graph).verdict,
            Verdict::kWait);
}

/// Two robots in one component: robot 1's estimate is `offset` away from the truth.
struct TwoRobots {
  FakeGraph graph;
  std::vector<Pose2> truth;
  explicit TwoRobots(const Pose2& offset, bool one_component) {
    for (int r = 0; r < 2; ++r) {
      for (int v = 0; v < 30; ++v) {
        truth.emplace_back(v * 1.0, r * 0.5, 0.0);
        graph.Add(r, r == 1 ? offset * truth.back() : truth.back(), v * 1.0, one_component ? 0 : r);
      }
    }
  }
  [[nodiscard]] Match Closure(int i, int k) const {
    return Measure(i, k, truth[static_cast<std::size_t>(i)], truth[static_cast<std::size_t>(k)]);
  }
};

// A ridge match: the truth's measurement with its translation moved `along` metres along the
// free axis `axis` (i's frame), where the search could not tell the position.
Match Ridge(const Match& truth, const Eigen::Vector2d& axis, double along) {
  Match ridge = truth;
  const Eigen::Vector2d t = truth.T_i_k.translation() + along * axis;
  ridge.T_i_k = Pose2(t.x(), t.y(), truth.T_i_k.theta());
  ridge.free_axis = axis;
  return ridge;
}

TEST(ClosureArbiter, ARidgeIsJudgedWithoutItsFreeAxis) {
  // The newer key maps' estimate is 1 m off across the line and 0.02 rad in heading.
  const Line line(40, 20, Pose2(0.0, 1.0, 0.02));
  const Eigen::Vector2d along_x(1.0, 0.0);
  const Match a = Ridge(line.Closure(2, 30), along_x, 1.7);
  const Match b = Ridge(line.Closure(5, 31), along_x, -2.4);
  // Error against the estimate: the 1.7 m along the line is not part of it.
  const Pose2 full = Between(Between(line.graph.Estimate(2), line.graph.Estimate(30)), a.T_i_k);
  const Pose2 error = ClosureError(a, line.graph);
  EXPECT_GT(full.translation().norm(), 2.0);
  EXPECT_NEAR(error.theta(), full.theta(), 1e-12);
  // Across the line the estimate is off by 1 m plus the heading error's 0.02 rad over 28 m.
  EXPECT_NEAR(error.translation().norm(), 1.0 + 30.0 * std::sin(0.02), 1e-9);
  // The two ridges agree with each other where they measure, although 4.1 m apart along it ...
  const Pose2 loop = LoopError(a, b, line.graph);
  EXPECT_LT(loop.translation().norm(), 1e-9);
  EXPECT_LT(std::abs(loop.theta()), 1e-9);
  Match a_full = a;
  Match b_full = b;
  a_full.free_axis.reset();
  b_full.free_axis.reset();
  EXPECT_NEAR(LoopError(a_full, b_full, line.graph).translation().norm(), 4.1, 1e-9);
  // ... but not when one of them is off across the line.
  Match across = b;
  across.T_i_k = Pose2(b.T_i_k.x(), b.T_i_k.y() + 0.5, b.T_i_k.theta());
  EXPECT_NEAR(LoopError(a, across, line.graph).translation().norm(), 0.5, 1e-6);
  // Free axes that cross leave only the rotation to check.
  Match crossing = Ridge(line.Closure(5, 31), Eigen::Vector2d(0.0, 1.0), 0.8);
  EXPECT_LT(LoopError(a, crossing, line.graph).translation().norm(), 1e-12);
}

// A ridge agrees with closures anywhere along its line; two of them 4 m apart along it do not
// agree with each other: evidence for two places, the ridge's group waits.
TEST(ClosureArbiter, AGatedGroupIsMutuallyConsistentNotOnlyWithTheNewMatch) {
  const Line line(40, 20, Pose2(0.0, 1.0, 0.0));
  LoopClosureOptions options;
  options.min_consistent_gated = 3;
  const Eigen::Vector2d along_x(1.0, 0.0);
  ClosureArbiter arbiter(options);
  Match shifted = line.Closure(5, 31);  // a look-alike 4 m along the line
  shifted.T_i_k = Pose2(4.0, 0.0, 0.0) * shifted.T_i_k;
  EXPECT_EQ(arbiter.OfferPrior(line.Closure(2, 30), 2.0, true, line.graph).verdict, Verdict::kWait);
  EXPECT_EQ(arbiter.OfferPrior(shifted, 2.0, true, line.graph).verdict, Verdict::kWait);
  // The ridge agrees with both, but they disagree: no group of three mutually consistent ones.
  EXPECT_EQ(
      arbiter.OfferPrior(Ridge(line.Closure(8, 32), along_x, 1.0), 2.0, true, line.graph).verdict,
      Verdict::kWait);
  // A right one that measures the position along the line leaves the look-alike out.
  const Decision d = arbiter.OfferPrior(line.Closure(9, 33), 2.0, true, line.graph);
  ASSERT_EQ(d.verdict, Verdict::kAcceptGroup);
  EXPECT_EQ(d.accepted.size(), 3U);
  for (const Match& m : d.accepted) {
    EXPECT_NE(m.k, 31);
  }
}

TEST(ClosureArbiter, ReversingARidgeRotatesItsAxis) {
  const Match match{3, 7, Pose2(2.0, 1.0, M_PI / 2.0), Eigen::Vector2d(1.0, 0.0)};
  const Match reversed = Reversed(match);
  EXPECT_EQ(reversed.i, 7);
  EXPECT_EQ(reversed.k, 3);
  ASSERT_TRUE(reversed.free_axis.has_value());
  // i's x axis, seen from k (turned by 90 degrees), is k's -y axis.
  EXPECT_TRUE(reversed.free_axis->isApprox(Eigen::Vector2d(0.0, -1.0), 1e-12));
  EXPECT_FALSE(Reversed(Match{3, 7, Pose2(2.0, 1.0, 0.3)}).free_axis.has_value());
}

TEST(ClosureArbiter, ReversingAWeakMatchRotatesItsWeakAxis) {
  Match match{3, 7, Pose2(2.0, 1.0, M_PI / 2.0)};
  match.weak_axis = Eigen::Vector2d(1.0, 0.0);
  match.weak_sigma = 0.1;
  const Match reversed = Reversed(match);
  ASSERT_TRUE(reversed.weak_axis.has_value());
  EXPECT_TRUE(reversed.weak_axis->isApprox(Eigen::Vector2d(0.0, -1.0), 1e-12));
  EXPECT_EQ(reversed.weak_sigma, 0.1);
  EXPECT_FALSE(reversed.free_axis.has_value());
}

// Where a match was found does not depend on the side it is seen from: a wide-search match
// oriented for a join keeps its burden of proof (two independent matches in its group).
TEST(ClosureArbiter, ReversingKeepsTheWideSearchFlag) {
  Match match{3, 7, Pose2(2.0, 1.0, 0.3)};
  match.wide_search = true;
  EXPECT_TRUE(Reversed(match).wide_search);
  match.wide_search = false;
  EXPECT_FALSE(Reversed(match).wide_search);
}

// A weak axis is measured: unlike a ridge's free axis, an offset along it counts in the checks.
TEST(ClosureArbiter, AnOffsetAlongAWeakAxisCountsInTheChecks) {
  Match weak{3, 7, Pose2(2.0, 1.0, 0.0)};
  weak.weak_axis = Eigen::Vector2d(1.0, 0.0);
  weak.weak_sigma = 0.1;
  Match ridge{3, 7, Pose2(2.0, 1.0, 0.0), Eigen::Vector2d(1.0, 0.0), 0.1};
  const Line line(10, 1000, Pose2());
  const Pose2 shift(1.5, 0.0, 0.0);  // along the axis
  weak.T_i_k = Between(line.graph.Estimate(3), line.graph.Estimate(7)) * shift;
  ridge.T_i_k = weak.T_i_k;
  EXPECT_NEAR(ClosureError(weak, line.graph).translation().norm(), 1.5, 1e-9);
  EXPECT_NEAR(ClosureError(ridge, line.graph).translation().norm(), 0.0, 1e-9);
}

// Ridges found by the search along one straight stretch, each at another position along it,
// correct the heading and the offset across it as a group.
TEST(ClosureArbiter, AcceptsAConsistentGroupOfRidges) {
  const Line line(40, 20, Pose2(0.0, 1.0, 0.02));
  const LoopClosureOptions options;
  ClosureArbiter arbiter(options);
  const Eigen::Vector2d along_x(1.0, 0.0);
  EXPECT_EQ(
      arbiter.OfferPrior(Ridge(line.Closure(2, 30), along_x, 1.2), 20.0, true, line.graph).verdict,
      Verdict::kWait);
  EXPECT_EQ(
      arbiter.OfferPrior(Ridge(line.Closure(5, 31), along_x, -0.8), 20.0, true, line.graph).verdict,
      Verdict::kWait);
  const Decision d =
      arbiter.OfferPrior(Ridge(line.Closure(8, 32), along_x, 2.6), 20.0, true, line.graph);
  EXPECT_EQ(d.verdict, Verdict::kAcceptGroup);
  ASSERT_EQ(d.accepted.size(), 3U);
  for (const Match& m : d.accepted) {
    EXPECT_TRUE(m.free_axis.has_value());
  }
  // The same ridges, one of them 0.6 m off across the line: no group.
  ClosureArbiter strict(options);
  strict.OfferPrior(Ridge(line.Closure(2, 30), along_x, 1.2), 20.0, true, line.graph);
  Match off = Ridge(line.Closure(5, 31), along_x, -0.8);
  off.T_i_k = Pose2(off.T_i_k.x(), off.T_i_k.y() + 0.6, off.T_i_k.theta());
  strict.OfferPrior(off, 20.0, true, line.graph);
  Match third = Ridge(line.Closure(8, 32), along_x, 2.6);
  third.T_i_k = Pose2(third.T_i_k.x(), third.T_i_k.y() - 0.6, third.T_i_k.theta());
  EXPECT_EQ(strict.OfferPrior(third, 20.0, true, line.graph).verdict, Verdict::kWait);
}

TEST(ClosureArbiter, WithinMapRejectsAMatchThatWouldMoveTheMapTooFar) {
  const TwoRobots robots(Pose2(20.0, 0.0, 0.0), true);
  ClosureArbiter arbiter{LoopClosureOptions{}};
  EXPECT_EQ(arbiter.OfferWithinMap(robots.Closure(3, 33), 10.0, robots.graph).verdict,
            Verdict::kReject);
  EXPECT_TRUE(arbiter.within_map().empty());
}

TEST(ClosureArbiter, DriftBoundAddsTheDisplacementOfTheRotationCorrection) {
  LoopClosureOptions options;
  options.max_drift = 0.05;
  EXPECT_DOUBLE_EQ(DriftBound(100.0, 0.0, options), 5.0);
  EXPECT_DOUBLE_EQ(DriftBound(100.0, 0.2, options), 5.0 + 10.0);
  EXPECT_DOUBLE_EQ(DriftBound(100.0, -0.2, options), 5.0 + 10.0);
}

TEST(ClosureArbiter, WithinMapWaitsOnADisplacementItsHeadingErrorExplains) {
  // 60 m out along a line whose estimate turned by 0.3 rad at its start: the revisit of key map
  // 60 by key map 0's neighbourhood is displaced by about 18 m, more than max_drift * u (5 m) and
  // the 10 m floor, but what a heading error of 0.3 rad does to a path 100 m long.
  const Line turned(61, 1, Pose2(0.0, 0.0, 0.3));
  ClosureArbiter arbiter{LoopClosureOptions{}};
  const Decision d = arbiter.OfferWithinMap(turned.Closure(0, 60), 100.0, turned.graph);
  ASSERT_GT(d.error.translation().norm(), 15.0);
  EXPECT_EQ(d.verdict, Verdict::kWait);
  // The same displacement with no heading error is not drift: refused as a look-alike.
  const Line shifted(61, 1, Pose2(0.0, d.error.translation().norm(), 0.0));
  ClosureArbiter other{LoopClosureOptions{}};
  EXPECT_EQ(other.OfferWithinMap(shifted.Closure(0, 60), 100.0, shifted.graph).verdict,
            Verdict::kReject);
}

TEST(ClosureArbiter, HeadingDriftBoundGrowsWithThePathAboveItsFloor) {
  LoopClosureOptions options;
  options.max_correction_theta = 0.5;
  options.max_drift_theta = 0.004;
  EXPECT_DOUBLE_EQ(HeadingDriftBound(0.0, options), 0.5);
  EXPECT_DOUBLE_EQ(HeadingDriftBound(100.0, options), 0.5);
  EXPECT_DOUBLE_EQ(HeadingDriftBound(800.0, options), 3.2);
}

TEST(ClosureArbiter, WithinMapTakesALargeTurnOnlyAfterALongPath) {
  // The estimate turned by 0.6 rad early on a line: more than the 0.5 rad floor. Over a short
  // path that is a look-alike turned against the map, refused; after 400 m of path it is the
  // heading error such a path can gather (0.004 rad/m: 1.6 rad), and the match waits for
  // support like any other correction within the drift bound.
  const Line turned(61, 1, Pose2(0.0, 0.0, 0.6));
  ClosureArbiter short_path{LoopClosureOptions{}};
  const Decision refused = short_path.OfferWithinMap(turned.Closure(0, 60), 100.0, turned.graph);
  ASSERT_NEAR(std::abs(refused.error.theta()), 0.6, 1e-9);
  EXPECT_EQ(refused.verdict, Verdict::kReject);
  ClosureArbiter long_path{LoopClosureOptions{}};
  EXPECT_EQ(long_path.OfferWithinMap(turned.Closure(0, 60), 400.0, turned.graph).verdict,
            Verdict::kWait);
  ASSERT_EQ(long_path.within_map().size(), 1U);
}

TEST(ClosureArbiter, WithinMapAcceptsIndependentConsistentMatchesTogether) {
  const TwoRobots robots(Pose2(2.0, 0.0, 0.0), true);
  LoopClosureOptions options;
  ClosureArbiter arbiter(options);
  const int needed = std::max(options.min_join_matches + 1, options.min_consistent_gated);
  ASSERT_EQ(needed, 3);
  // Key maps 10 m apart on both robots: independent evidence.
  EXPECT_EQ(arbiter.OfferWithinMap(robots.Closure(0, 30), 1.0, robots.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferWithinMap(robots.Closure(10, 40), 1.0, robots.graph).verdict,
            Verdict::kWait);
  const Decision d = arbiter.OfferWithinMap(robots.Closure(20, 50), 1.0, robots.graph);
  EXPECT_EQ(d.verdict, Verdict::kAcceptGroup);
  EXPECT_EQ(d.accepted.size(), 3U);
  EXPECT_TRUE(arbiter.within_map().empty());
}

TEST(ClosureArbiter, NeighbouringMatchesAreNotIndependentEvidence) {
  const TwoRobots robots(Pose2(2.0, 0.0, 0.0), true);
  ClosureArbiter arbiter{LoopClosureOptions{}};
  EXPECT_EQ(arbiter.OfferWithinMap(robots.Closure(0, 30), 1.0, robots.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferWithinMap(robots.Closure(1, 31), 1.0, robots.graph).verdict,
            Verdict::kWait);
  EXPECT_EQ(arbiter.OfferWithinMap(robots.Closure(2, 32), 1.0, robots.graph).verdict,
            Verdict::kWait);
}

TEST(ClosureArbiter, JoinNeedsIndependentConsistentMatchesBetweenComponents) {
  // Each robot in its own frame: robot 1's estimate is its truth seen from far away.
  TwoRobots robots(Pose2(100.0, -40.0, 2.0), false);
  LoopClosureOptions options;
  ClosureArbiter arbiter(options);
  ASSERT_EQ(options.min_join_matches, 2);
  EXPECT_EQ(arbiter.OfferJoin(robots.Closure(0, 30), robots.graph).verdict, Verdict::kWait);
  // A match found from the other side counts reversed.
  const Decision d = arbiter.OfferJoin(robots.Closure(40, 10), robots.graph);
  EXPECT_EQ(d.verdict, Verdict::kAcceptGroup);
  ASSERT_EQ(d.accepted.size(), 2U);
  EXPECT_EQ(d.accepted[1].i, 30);  // oriented from the new match's i side
  EXPECT_EQ(arbiter.joinable().size(), 2U);
  robots.graph.SetComponent(1, 0);
  arbiter.ForgetWithinComponents(robots.graph);
  EXPECT_TRUE(arbiter.joinable().empty());
}

TEST(ClosureArbiter, InconsistentMatchesDoNotJoin) {
  TwoRobots robots(Pose2(100.0, -40.0, 2.0), false);
  ClosureArbiter arbiter{LoopClosureOptions{}};
  Match wrong = robots.Closure(10, 40);
  wrong.T_i_k = wrong.T_i_k * Pose2(3.0, 0.0, 0.5);
  EXPECT_EQ(arbiter.OfferJoin(robots.Closure(0, 30), robots.graph).verdict, Verdict::kWait);
  EXPECT_EQ(arbiter.OfferJoin(wrong, robots.graph).verdict, Verdict::kWait);
}

}  // namespace
}  // namespace gridslam::loop_closure
