#include "gridslam/scan_matching/odometry_noise.hpp"

#include <random>

#include <gtest/gtest.h>

namespace gridslam::scan_matching {
namespace {

constexpr double kSigmaTheta = 0.05;

/// Feeds n yaw corrections drawn with the given true standard deviation (a fraction `outliers`
/// of them 20 times larger).
void Feed(OdometryNoiseEstimate& estimate, int n, double sigma_theta, double outliers = 0.0,
          unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  for (int i = 0; i < n; ++i) {
    const double k = uniform(rng) < outliers ? 20.0 : 1.0;
    estimate.Add(k * sigma_theta * normal(rng), kSigmaTheta);
  }
}

TEST(OdometryNoiseEstimate, StaysAtTheDefaultsUntilTheWindowIsFull) {
  OdometryNoiseEstimate estimate(100, 0.1);
  Feed(estimate, 99, 0.0);
  EXPECT_EQ(estimate.RotationScale(), 1.0);
  Feed(estimate, 1, 0.0);
  EXPECT_EQ(estimate.RotationScale(), 0.1);  // exact odometry: clamped at the floor
}

TEST(OdometryNoiseEstimate, RecoversTheTrueScaleDespiteOutliers) {
  OdometryNoiseEstimate estimate(400, 0.05);
  Feed(estimate, 400, 0.5 * kSigmaTheta, /*outliers=*/0.1);
  EXPECT_NEAR(estimate.RotationScale(), 0.5, 0.08);
}

TEST(OdometryNoiseEstimate, NeverLooserThanTheDefaultsAndFollowsChanges) {
  OdometryNoiseEstimate estimate(200, 0.1);
  Feed(estimate, 200, 3.0 * kSigmaTheta);
  EXPECT_EQ(estimate.RotationScale(), 1.0);
  Feed(estimate, 200, 0.2 * kSigmaTheta, 0.0, 2);  // the window forgets
  EXPECT_NEAR(estimate.RotationScale(), 0.2, 0.05);
}

}  // namespace
}  // namespace gridslam::scan_matching
