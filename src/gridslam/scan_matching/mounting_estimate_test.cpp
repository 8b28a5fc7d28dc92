#include "gridslam/scan_matching/mounting_estimate.hpp"

#include <random>

#include <gtest/gtest.h>

namespace gridslam::scan_matching {
namespace {

// Increments of a robot that drives and turns; what a front end that assumes the laser at the
// centre matches when the laser really sits `offset` beyond it: D^-1 increment D, D = (offset, 0),
// plus noise, and a share of `outliers` matches 0.5 m off.
MountingEstimate Feed(const Eigen::Vector2d& offset, int n, double noise, double outliers,
                      bool turns = true, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::bernoulli_distribution outlier(outliers);
  const Pose2 D(offset.x(), offset.y(), 0.0);
  MountingEstimate estimate;
  for (int k = 0; k < n; ++k) {
    const Pose2 odometry(0.2 * (1.0 + uniform(rng)), 0.01 * uniform(rng),
                         turns ? 0.3 * uniform(rng) : 0.0);
    Pose2 matched = D.Inverse() * odometry * D;
    Eigen::Vector2d error(noise * normal(rng), noise * normal(rng));
    if (outlier(rng)) {
      error += Eigen::Vector2d(0.5 * uniform(rng), 0.5 * uniform(rng));
    }
    matched = Pose2(matched.x() + error.x(), matched.y() + error.y(), matched.theta());
    estimate.Add(odometry, matched);
  }
  return estimate;
}

TEST(MountingEstimate, FindsALaserAheadOfTheCentreDespiteOutliers) {
  const Eigen::Vector2d truth(0.22, -0.03);
  const MountingResult result = Feed(truth, 2000, 0.005, 0.1).Estimate();
  ASSERT_TRUE(result.ok);
  EXPECT_EQ(result.increments, 2000);
  EXPECT_NEAR(result.offset.x(), truth.x(), 0.01);
  EXPECT_NEAR(result.offset.y(), truth.y(), 0.01);
  // The standard deviations describe the error: small, and not far below it.
  EXPECT_LT(result.sigma, 0.01);
  EXPECT_LT((result.offset - truth).cwiseAbs().maxCoeff(), 5.0 * result.sigma);
}

TEST(MountingEstimate, ALaserAtTheCentreGivesNoOffset) {
  const MountingResult result =
      Feed(Eigen::Vector2d::Zero(), 1000, 0.005, 0.05, true, 2).Estimate();
  ASSERT_TRUE(result.ok);
  EXPECT_LT(result.offset.norm(), 0.01);
}

TEST(MountingEstimate, NeedsTurnsAndEnoughIncrements) {
  // Straight driving says nothing about where the laser sits.
  EXPECT_FALSE(Feed(Eigen::Vector2d(0.2, 0.0), 500, 0.005, 0.0, /*turns=*/false).Estimate().ok);
  const MountingEstimate few = Feed(Eigen::Vector2d(0.2, 0.0), 20, 0.005, 0.0);
  EXPECT_FALSE(few.Estimate().ok);
  EXPECT_EQ(few.Estimate().increments, 20);
  EXPECT_TRUE(few.Estimate(/*min_increments=*/10).ok);
  EXPECT_FALSE(MountingEstimate().Estimate().ok);
}

}  // namespace
}  // namespace gridslam::scan_matching
