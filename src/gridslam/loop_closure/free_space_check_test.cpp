#include "gridslam/loop_closure/free_space_check.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::loop_closure {
namespace {

// A 10 m corridor 2 m wide seen from inside: walls at y = +-1 observed as obstacles, the space
// between them observed free, nothing beyond.
description::KeyMapCells Corridor() {
  const MapLimits limits(0.05, Eigen::Vector2d(-5.0, -5.0), 200, 200);
  Grid2D<float> log_odds(limits, 0.0F);
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 200; ++j) {
      const double y = limits.CellCenter({i, j}).y();
      if (std::abs(std::abs(y) - 1.0) < 0.03) {
        log_odds(i, j) = 2.0F;
      } else if (std::abs(y) < 1.0) {
        log_odds(i, j) = -2.0F;
      }
    }
  }
  return description::KeyMapCells(log_odds, 0.4F, 0.1F);
}

std::vector<Eigen::Vector2d> WallReturns() {
  std::vector<Eigen::Vector2d> points;
  for (double x = -4.0; x <= 4.0; x += 0.1) {
    points.emplace_back(x, 1.0);
    points.emplace_back(x, -1.0);
  }
  return points;
}

TEST(FreeSpaceCheck, ReturnsOnTheWallsAgreeInsideTheCorridorContradictBeyondTellNothing) {
  const description::KeyMapCells cells = Corridor();
  const std::vector<Eigen::Vector2d> points = WallReturns();
  const FreeSpaceCounts right = ReplayReturns(points, Pose2(), cells, 0.15);
  EXPECT_EQ(right.returns, static_cast<long>(points.size()));
  EXPECT_EQ(right.agreeing, right.observed);
  EXPECT_EQ(right.contradicting, 0);
  EXPECT_DOUBLE_EQ(right.Contradiction(), 0.0);
  // Shifted 0.5 m across: one wall runs down the free middle, the other beyond what was seen.
  const FreeSpaceCounts wrong = ReplayReturns(points, Pose2(0.0, 0.5, 0.0), cells, 0.15);
  EXPECT_EQ(wrong.observed, static_cast<long>(points.size()) / 2);
  EXPECT_EQ(wrong.contradicting, wrong.observed);
  EXPECT_DOUBLE_EQ(wrong.Contradiction(), 1.0);
  // Turned by 90 degrees: the walls cross the corridor; only returns near y = +-1 agree.
  const FreeSpaceCounts turned = ReplayReturns(points, Pose2(0.0, 0.0, 1.5708), cells, 0.15);
  EXPECT_GT(turned.Contradiction(), 0.5);
}

TEST(FreeSpaceCheck, APairIsReplayedBothWays) {
  const description::KeyMapCells cells = Corridor();
  const std::vector<Eigen::Vector2d> points = WallReturns();
  const FreeSpaceCounts pair = ReplayPair(points, cells, points, cells, Pose2(0.0, 0.5, 0.0), 0.15);
  EXPECT_EQ(pair.returns, 2 * static_cast<long>(points.size()));
  EXPECT_EQ(pair.contradicting, pair.observed);
  EXPECT_GT(pair.observed, 0);
}

TEST(FreeSpaceCheck, AJoinIsRefusedOnlyBeyondTheRobotsOwnContradiction) {
  const FreeSpaceCheckOptions options;  // max_ratio 4, min_excess 0.01
  // A noise-free building: the robots contradict themselves at 0.1 %, a look-alike at 4 %.
  EXPECT_TRUE(JudgeContradictions({0.04, 0.03, 0.29}, {0.001, 0.001, 0.002}, options).refused);
  EXPECT_FALSE(JudgeContradictions({0.002, 0.003, 0.001}, {0.001, 0.002, 0.002}, options).refused);
  // A laser whose long returns carve free space: 5 % from a right join is the robots' own level.
  const FreeSpaceVerdict noisy = JudgeContradictions({0.05, 0.04, 0.29}, {0.02, 0.015}, options);
  EXPECT_FALSE(noisy.refused);
  EXPECT_DOUBLE_EQ(noisy.alignments, 0.05);
  EXPECT_DOUBLE_EQ(noisy.baseline, 0.02);
  // Off: never refused.
  FreeSpaceCheckOptions off = options;
  off.enabled = false;
  EXPECT_FALSE(JudgeContradictions({0.5}, {0.0}, off).refused);
  EXPECT_TRUE(JudgeContradictions({0.5}, {}, options).refused);
}

TEST(FreeSpaceCheck, OptionsAreValidated) {
  FreeSpaceCheckOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.baseline_travel.clear();
  EXPECT_FALSE(options.Validate().ok());
  options = FreeSpaceCheckOptions();
  options.max_ratio = 0.5;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace gridslam::loop_closure
