#include "gridslam/scan_matching/motion_check.hpp"

#include <random>

#include <gtest/gtest.h>

#include "gridslam/common/angles.hpp"

namespace gridslam::scan_matching {
namespace {

Time At(double seconds) { return FromSeconds(1000.0 + seconds); }

// A robot driving a gentle arc at 0.5 m/s, scanned at 5 Hz, odometry = truth plus noise.
class MotionCheckTest : public ::testing::Test {
 protected:
  MotionCheckTest() : check_(MotionCheckOptions{}) {}

  void Drive(int frames) {
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 0.003);
    for (int k = 0; k < frames; ++k) {
      truth_ = truth_ * Pose2(0.1, 0.0, 0.02);
      odometry_ = odometry_ * Pose2(0.1 + noise(rng), noise(rng), 0.02 + noise(rng));
      t_ += 0.2;
      const MotionPrediction p = check_.Predict(At(t_), odometry_);
      EXPECT_EQ(p.check, OdometryCheck::kConsistent) << "frame " << k;
      check_.Update(At(t_), odometry_, truth_, p);
    }
  }

  MotionCheck check_;
  Pose2 truth_;
  Pose2 odometry_;
  double t_ = 0.0;
};

TEST_F(MotionCheckTest, SmoothMotionIsConsistent) {
  check_.Reset(At(0.0), odometry_, truth_);
  Drive(200);
  // The thresholds are at their floors: the innovations are millimetres.
  EXPECT_DOUBLE_EQ(check_.ThresholdXy(), MotionCheckOptions{}.floor_xy);
  EXPECT_DOUBLE_EQ(check_.ThresholdTheta(), MotionCheckOptions{}.floor_theta);
}

TEST_F(MotionCheckTest, AYawOrTranslationJumpIsDoubtfulAndTheConstantVelocityHoldsTheTruth) {
  check_.Reset(At(0.0), odometry_, truth_);
  Drive(50);
  for (const Pose2& jump :
       {Pose2(0.0, 0.0, DegToRad(30.0)), Pose2(0.5, 0.0, 0.0), Pose2(0.0, 0.0, DegToRad(-85.0))}) {
    truth_ = truth_ * Pose2(0.1, 0.0, 0.02);
    odometry_ = odometry_ * Pose2(0.1, 0.0, 0.02) * jump;
    t_ += 0.2;
    const MotionPrediction p = check_.Predict(At(t_), odometry_);
    EXPECT_EQ(p.check, OdometryCheck::kDoubtful);
    // The velocity comes from the (noisy) odometry of the last second.
    EXPECT_TRUE(IsApprox(p.constant_velocity, truth_, 0.02, 0.01));
    EXPECT_FALSE(p.after_overrule);
    check_.Update(At(t_), odometry_, truth_, p, /*odometry_overruled=*/true);
    // The odometry carries on from the jumped pose. Its next increment is doubtful only for
    // having been overruled; once a match confirms it, the following ones are fine again.
    truth_ = truth_ * Pose2(0.1, 0.0, 0.02);
    odometry_ = odometry_ * Pose2(0.1, 0.0, 0.02);
    t_ += 0.2;
    const MotionPrediction next = check_.Predict(At(t_), odometry_);
    EXPECT_EQ(next.check, OdometryCheck::kDoubtful);
    EXPECT_TRUE(next.after_overrule);
    EXPECT_LT(next.innovation_xy, check_.ThresholdXy());
    check_.Update(At(t_), odometry_, truth_, next, /*odometry_overruled=*/false);
    Drive(5);
  }
}

TEST_F(MotionCheckTest, AJumpBeyondTractionIsImpossibleAManoeuvreOnlyDoubtful) {
  check_.Reset(At(0.0), odometry_, truth_);
  Drive(50);
  // Scans 0.2 s apart: 1 g over the interval moves the robot 9.81 * 0.2^2 / 2 = 0.196 m.
  struct Case {
    Pose2 jump;
    bool impossible;
  };
  for (const Case& c :
       {Case{Pose2(0.5, 0.0, 0.0), true}, Case{Pose2(0.0, -0.6, 0.0), true},
        Case{Pose2(0.15, 0.0, 0.0), false}, Case{Pose2(0.0, 0.0, DegToRad(40.0)), false}}) {
    truth_ = truth_ * Pose2(0.1, 0.0, 0.02);
    odometry_ = odometry_ * Pose2(0.1, 0.0, 0.02) * c.jump;
    t_ += 0.2;
    const MotionPrediction p = check_.Predict(At(t_), odometry_);
    EXPECT_EQ(p.check, OdometryCheck::kDoubtful);
    EXPECT_EQ(p.impossible, c.impossible) << "jump " << c.jump.x() << " " << c.jump.y();
    check_.Update(At(t_), odometry_, truth_, p, /*odometry_overruled=*/true);
    truth_ = truth_ * Pose2(0.1, 0.0, 0.02);  // the match confirms the next increment
    odometry_ = odometry_ * Pose2(0.1, 0.0, 0.02);
    t_ += 0.2;
    const MotionPrediction next = check_.Predict(At(t_), odometry_);
    EXPECT_FALSE(next.impossible);
    check_.Update(At(t_), odometry_, truth_, next, /*odometry_overruled=*/false);
    Drive(10);
  }
  // The same 0.5 m beyond the recent velocity over a 1 s gap between scans: doubtful, but a
  // robot can change its speed that much in a second.
  truth_ = truth_ * Pose2(0.5, 0.0, 0.1);
  odometry_ = odometry_ * Pose2(0.5, 0.0, 0.1) * Pose2(0.5, 0.0, 0.0);
  t_ += 1.0;
  const MotionPrediction late = check_.Predict(At(t_), odometry_);
  EXPECT_EQ(late.check, OdometryCheck::kDoubtful);
  EXPECT_FALSE(late.impossible);
}

TEST_F(MotionCheckTest, MissingOdometryPredictsTheConstantVelocity) {
  check_.Reset(At(0.0), odometry_, truth_);
  Drive(10);
  const Pose2 expected = truth_ * Pose2(0.1, 0.0, 0.02);
  const MotionPrediction p = check_.Predict(At(t_ + 0.2), std::nullopt);
  EXPECT_EQ(p.check, OdometryCheck::kMissing);
  EXPECT_TRUE(IsApprox(p.constant_velocity, expected, 0.02, 0.01));
}

TEST_F(MotionCheckTest, NonFiniteOdometryIsDoubtful) {
  check_.Reset(At(0.0), odometry_, truth_);
  Drive(10);
  const MotionPrediction p =
      check_.Predict(At(t_ + 0.2), Pose2(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0));
  EXPECT_EQ(p.check, OdometryCheck::kDoubtful);
  EXPECT_TRUE(p.constant_velocity.ToVector().allFinite());
}

TEST(MotionCheck, TheThresholdGrowsWithTheRobotsDynamics) {
  // A jerky robot (speed changing by up to 0.3 m/s between 5 Hz scans) raises the spread.
  MotionCheck check(MotionCheckOptions{});
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> speed(0.0, 1.5);
  Pose2 pose;
  check.Reset(At(0.0), pose, pose);
  double t = 0.0;
  for (int k = 0; k < 200; ++k) {
    pose = pose * Pose2(0.2 * speed(rng), 0.0, 0.0);
    t += 0.2;
    const MotionPrediction p = check.Predict(At(t), pose);
    check.Update(At(t), pose, pose, p);
  }
  EXPECT_GT(check.ThresholdXy(), MotionCheckOptions{}.floor_xy);
}

}  // namespace
}  // namespace gridslam::scan_matching
