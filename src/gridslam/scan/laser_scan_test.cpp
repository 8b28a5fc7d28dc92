#include "gridslam/scan/laser_scan.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

TEST(LaserScan, HitsExcludeNoReturnsAndNaN) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 2;
  scan.range_min = 0.0;
  scan.range_max = 80.0;
  scan.ranges = {1.0F, 81.83F, std::numeric_limits<float>::quiet_NaN(), 0.0F};
  EXPECT_TRUE(scan.IsHit(0));
  EXPECT_FALSE(scan.IsHit(1));
  EXPECT_FALSE(scan.IsHit(2));
  EXPECT_FALSE(scan.IsHit(3));
  ASSERT_EQ(scan.CountHits(), 1U);
  const auto points = scan.HitPoints();
  ASSERT_EQ(points.size(), 1U);
  EXPECT_NEAR(points[0].x(), 0.0, 1e-9);
  EXPECT_NEAR(points[0].y(), -1.0, 1e-9);
}

// A limit that a float cannot hold exactly (5.6 m, a Hokuyo URG-04LX): the reading written at the
// limit is a no-return, not a hit on a circle of radius range_max around the robot.
TEST(LaserScan, AReadingAtTheLimitIsANoReturnInFloatPrecision) {
  LaserScan scan;
  scan.angle_increment = 0.01;
  scan.range_min = 0.1;
  scan.range_max = 5.6;
  scan.ranges = {5.6F, 5.59F, std::nextafter(5.6F, 0.0F), 0.1F, 6.0F};
  ASSERT_LT(static_cast<double>(scan.ranges[0]), scan.range_max);  // why it needs a rule
  EXPECT_FALSE(scan.IsHit(0));
  EXPECT_TRUE(scan.IsNoReturn(0));
  EXPECT_TRUE(scan.IsHit(1));
  EXPECT_FALSE(scan.IsNoReturn(1));
  EXPECT_TRUE(scan.IsHit(2));
  EXPECT_FALSE(scan.IsHit(3));  // at range_min
  EXPECT_FALSE(scan.IsNoReturn(3));
  EXPECT_TRUE(scan.IsNoReturn(4));
  EXPECT_EQ(scan.CountHits(), 2U);
}

TEST(LaserScan, UnboundedLimitsNeverOverflowTheFloatComparison) {
  LaserScan scan;
  scan.range_min = -1e300;
  scan.range_max = 1e300;
  scan.ranges = {0.0F, 1e30F, std::numeric_limits<float>::infinity()};
  EXPECT_TRUE(scan.IsHit(0));
  EXPECT_TRUE(scan.IsHit(1));
  EXPECT_FALSE(scan.IsHit(2));
  EXPECT_FALSE(scan.IsNoReturn(2));
}

}  // namespace
}  // namespace gridslam
