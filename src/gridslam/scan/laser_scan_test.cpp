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

}  // namespace
}  // namespace gridslam
