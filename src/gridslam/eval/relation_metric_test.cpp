#include "gridslam/eval/relation_metric.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace gridslam::eval {
namespace {

Time S(double seconds) { return FromSeconds(seconds); }

TEST(RelationMetric, PerfectTrajectoryHasZeroError) {
  const std::vector<StampedPose> traj = {{S(1.0), Pose2(5, 5, 1.0)}, {S(2.0), Pose2(6, 7, -2.0)}};
  const Relation r{S(1.0), S(2.0), Between(traj[0].pose, traj[1].pose)};
  const auto m = EvaluateRelations({r}, traj, {});
  EXPECT_EQ(m.used, 1);
  EXPECT_EQ(m.missing, 0);
  EXPECT_NEAR(m.translation.mean, 0.0, 1e-12);
  EXPECT_NEAR(m.rotation_deg.mean, 0.0, 1e-9);
}

TEST(RelationMetric, TranslationErrorIsMeasuredInTheFrameAtT1) {
  // X1 faces +y; the estimate moves 1 m forward, the truth 1 m forward and 0.2 m left.
  const std::vector<StampedPose> traj = {{S(1.0), Pose2(5, 5, std::numbers::pi / 2)},
                                         {S(2.0), Pose2(5, 6, std::numbers::pi / 2)}};
  const auto m = EvaluateRelations({{S(1.0), S(2.0), Pose2(1.0, 0.2, 0.0)}}, traj, {});
  ASSERT_EQ(m.used, 1);
  EXPECT_NEAR(m.translation.mean, 0.2, 1e-12);
  EXPECT_NEAR(m.rotation_deg.mean, 0.0, 1e-12);
  EXPECT_NEAR(m.translation_sq.mean, 0.04, 1e-12);
}

TEST(RelationMetric, RotationErrorInDegreesWrapped) {
  const std::vector<StampedPose> traj = {{S(1.0), Pose2(0, 0, 3.1)}, {S(2.0), Pose2(0, 0, -3.1)}};
  // Estimate turns +0.0832 rad across pi; the truth says it did not turn.
  const auto m = EvaluateRelations({{S(1.0), S(2.0), Pose2(0, 0, 0)}}, traj, {});
  ASSERT_EQ(m.used, 1);
  EXPECT_NEAR(m.rotation_deg.mean, RadToDeg(2 * std::numbers::pi - 6.2), 1e-9);
  EXPECT_NEAR(m.rotation_sq_deg2.mean, std::pow(RadToDeg(2 * std::numbers::pi - 6.2), 2), 1e-6);
}

TEST(RelationMetric, DefinitionDoesNotDependOnWhichSideIsTheEstimate) {
  // A pure rotation error: positions agree, so the translational error is 0 either way (with
  // Cartographer's delta * truth^-1 it would be |(1 - cos 0.5, -sin 0.5)| = 0.49).
  const Pose2 estimate(1.0, 0.0, 0.5);
  const Pose2 truth(1.0, 0.0, 0.0);
  EXPECT_NEAR(RelationErrorPose(estimate, truth).translation().norm(), 0.0, 1e-12);
  EXPECT_NEAR(RelationErrorPose(truth, estimate).translation().norm(), 0.0, 1e-12);
  const Pose2 other(0.3, -0.7, 2.0);
  EXPECT_NEAR(RelationErrorPose(other, truth).translation().norm(),
              RelationErrorPose(truth, other).translation().norm(), 1e-12);
  EXPECT_NEAR((other.translation() - truth.translation()).norm(),
              RelationErrorPose(other, truth).translation().norm(), 1e-12);
}

TEST(RelationMetric, SampleStandardDeviation) {
  const std::vector<StampedPose> traj = {
      {S(0.0), Pose2(0, 0, 0)}, {S(1.0), Pose2(1, 0, 0)}, {S(2.0), Pose2(2, 0, 0)}};
  const std::vector<Relation> rel = {{S(0.0), S(1.0), Pose2(1.1, 0, 0)},
                                     {S(1.0), S(2.0), Pose2(1.3, 0, 0)}};
  const auto m = EvaluateRelations(rel, traj, {});
  ASSERT_EQ(m.used, 2);
  EXPECT_NEAR(m.translation.mean, 0.2, 1e-12);
  EXPECT_NEAR(m.translation.std, std::sqrt(0.02), 1e-12);
  EXPECT_NEAR(m.translation_sq.mean, 0.05, 1e-12);
  EXPECT_NEAR(m.translation_sq.std, std::sqrt(2 * 0.04 * 0.04), 1e-12);
  EXPECT_EQ(ComputeMeanStd({4.0}).std, 0.0);
  EXPECT_EQ(ComputeMeanStd({}).mean, 0.0);
}

TEST(RelationMetric, NearestTimestampWithinToleranceElseMissing) {
  const std::vector<StampedPose> traj = {{S(2.0), Pose2(1, 0, 0)},  // unsorted on purpose
                                         {S(1.0), Pose2(0, 0, 0)},
                                         {S(1.0004), Pose2(9, 9, 0)}};
  EvalOptions options;  // tolerance 1 ms
  const std::vector<Relation> rel = {
      {S(0.9996), S(2.0009), Pose2(1, 0, 0)},  // matches 1.0 (nearest), 2.0
      {S(1.0), S(2.002), Pose2(1, 0, 0)},      // 2.002 is 2 ms away: missing
      {S(5.0), S(6.0), Pose2(1, 0, 0)}};       // outside the trajectory: missing
  const auto m = EvaluateRelations(rel, traj, options);
  EXPECT_EQ(m.total, 3);
  EXPECT_EQ(m.used, 1);
  EXPECT_EQ(m.missing, 2);
  EXPECT_NEAR(m.translation.mean, 0.0, 1e-12);
  options.tolerance = 0.01;
  EXPECT_EQ(EvaluateRelations(rel, traj, options).used, 2);
}

TEST(RelationMetric, FiltersByDuration) {
  const std::vector<StampedPose> traj = {
      {S(0.0), Pose2(0, 0, 0)}, {S(4.0), Pose2(1, 0, 0)}, {S(20.0), Pose2(2, 0, 0)}};
  const std::vector<Relation> rel = {{S(0.0), S(4.0), Pose2(1, 0, 0)},
                                     {S(0.0), S(20.0), Pose2(2.5, 0, 0)}};
  EvalOptions options;
  options.max_dt = 10.0;
  auto m = EvaluateRelations(rel, traj, options);
  EXPECT_EQ(m.used, 1);
  EXPECT_EQ(m.filtered, 1);
  EXPECT_NEAR(m.translation.mean, 0.0, 1e-12);
  options.max_dt = 0.0;
  options.min_dt = 10.0;
  m = EvaluateRelations(rel, traj, options);
  EXPECT_EQ(m.used, 1);
  EXPECT_NEAR(m.translation.mean, 0.5, 1e-12);
  EXPECT_TRUE(options.Validate().ok());
  options.max_dt = 5.0;
  EXPECT_FALSE(options.Validate().ok());
  options = {};
  options.trajectory_frame = "map";
  EXPECT_FALSE(options.Validate().ok());
}

TEST(RelationMetric, InterpolatesBetweenTwoPoses) {
  // The robot drives 1 m/s along x and turns 0.1 rad/s; poses only every second.
  std::vector<StampedPose> traj;
  for (int k = 0; k <= 10; ++k) {
    traj.push_back({S(100.0 + k), Pose2(1.0 * k, 0.0, 0.1 * k)});
  }
  // Truth between t = 101.25 and 104.5 from the same motion model.
  const Pose2 at1(1.25, 0.0, 0.125);
  const Pose2 at2(4.5, 0.0, 0.45);
  const Relation r{S(101.25), S(104.5), Between(at1, at2)};
  const Relation exact{S(101.0), S(103.0), Between(traj[1].pose, traj[3].pose)};
  auto m = EvaluateRelations({r, exact}, traj, {});
  EXPECT_EQ(m.used, 2);
  EXPECT_EQ(m.missing, 0);
  EXPECT_EQ(m.interpolated, 1);
  EXPECT_NEAR(m.errors[0].translation, 0.0, 1e-9);
  EXPECT_NEAR(m.errors[0].rotation, 0.0, 1e-9);

  EvalOptions no;
  no.interpolate = false;
  m = EvaluateRelations({r, exact}, traj, no);
  EXPECT_EQ(m.used, 1);
  EXPECT_EQ(m.missing, 1);
  EXPECT_EQ(m.interpolated, 0);
}

TEST(RelationMetric, InterpolationTakesTheShortArcAndRespectsTheGap) {
  const std::vector<StampedPose> traj = {
      {S(1.0), Pose2(0, 0, 3.0)}, {S(2.0), Pose2(2, 0, -3.0)}, {S(10.0), Pose2(10, 0, -3.0)}};
  // Half way across pi: theta = pi (not 0), x = 1.
  const Relation r{S(1.0), S(1.5), Between(traj[0].pose, Pose2(1.0, 0.0, std::numbers::pi))};
  auto m = EvaluateRelations({r}, traj, {});
  ASSERT_EQ(m.used, 1);
  EXPECT_NEAR(m.errors[0].translation, 0.0, 1e-9);
  EXPECT_NEAR(m.errors[0].rotation, 0.0, 1e-9);
  // Between 2 s and 10 s (8 s apart): beyond the default 1 s gap, so missing; 0 = any gap.
  const Relation far{S(1.0), S(6.0), Pose2(6.0, 0.0, 0.0)};
  m = EvaluateRelations({far}, traj, {});
  EXPECT_EQ(m.missing, 1);
  EvalOptions any;
  any.max_interpolation_gap = 0.0;
  m = EvaluateRelations({far}, traj, any);
  EXPECT_EQ(m.used, 1);
  EXPECT_EQ(m.interpolated, 1);
  // Outside the trajectory's time span nothing is extrapolated.
  m = EvaluateRelations({{S(0.5), S(1.0), Pose2()}, {S(2.0), S(11.0), Pose2()}}, traj, any);
  EXPECT_EQ(m.missing, 2);
}

TEST(RelationMetric, ExactMatchWithinToleranceIsNotInterpolated) {
  const std::vector<StampedPose> traj = {{S(1.0), Pose2(0, 0, 0)}, {S(2.0), Pose2(1, 0, 0)}};
  const auto m = EvaluateRelations({{S(1.0004), S(1.9996), Pose2(1, 0, 0)}}, traj, {});
  EXPECT_EQ(m.used, 1);
  EXPECT_EQ(m.interpolated, 0);
  EXPECT_NEAR(m.errors[0].translation, 0.0, 1e-12);
}

}  // namespace
}  // namespace gridslam::eval
