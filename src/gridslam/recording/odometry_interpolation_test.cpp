#include "gridslam/recording/odometry_interpolation.hpp"

#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::recording {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(InterpolateOdometry, LinearInPositionShortestArcInHeading) {
  const std::vector<OdometrySample> samples = {{1000, Pose2(0.0, 0.0, kPi - 0.1)},
                                               {2000, Pose2(1.0, 2.0, -kPi + 0.1)}};
  bool clamped = true;
  const Pose2 p = InterpolateOdometry(samples, 1250, &clamped);
  EXPECT_FALSE(clamped);
  EXPECT_NEAR(p.x(), 0.25, 1e-12);
  EXPECT_NEAR(p.y(), 0.5, 1e-12);
  // Through +-pi, not through 0: a quarter of the 0.2 rad arc past pi - 0.1.
  EXPECT_NEAR(p.theta(), kPi - 0.05, 1e-12);
}

TEST(InterpolateOdometry, ExactSampleAndClampingOutsideTheSpan) {
  const std::vector<OdometrySample> samples = {
      {1000, Pose2(1.0, 0.0, 0.0)}, {2000, Pose2(2.0, 0.0, 0.5)}, {3000, Pose2(3.0, 0.0, 1.0)}};
  bool clamped = true;
  EXPECT_NEAR(InterpolateOdometry(samples, 2000, &clamped).theta(), 0.5, 1e-12);
  EXPECT_FALSE(clamped);
  EXPECT_NEAR(InterpolateOdometry(samples, 1000, &clamped).x(), 1.0, 1e-12);
  EXPECT_FALSE(clamped);
  EXPECT_NEAR(InterpolateOdometry(samples, 999, &clamped).x(), 1.0, 1e-12);
  EXPECT_TRUE(clamped);
  EXPECT_NEAR(InterpolateOdometry(samples, 3001, &clamped).x(), 3.0, 1e-12);
  EXPECT_TRUE(clamped);
  EXPECT_NEAR(InterpolateOdometry(samples, 2500).x(), 2.5, 1e-12);  // clamped is optional
}

// Two samples at one stamp: the stamp itself gives the first, later stamps interpolate from the
// last of them (no division by a zero span).
TEST(InterpolateOdometry, RepeatedStamps) {
  const std::vector<OdometrySample> samples = {
      {1000, Pose2(1.0, 0.0, 0.0)}, {1000, Pose2(2.0, 0.0, 0.0)}, {2000, Pose2(3.0, 0.0, 0.0)}};
  EXPECT_NEAR(InterpolateOdometry(samples, 1000).x(), 1.0, 1e-12);
  EXPECT_NEAR(InterpolateOdometry(samples, 1500).x(), 2.5, 1e-12);
}

}  // namespace
}  // namespace gridslam::recording
