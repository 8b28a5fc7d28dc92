#include "gridslam/grid/scan_points.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

TEST(ExtractScanPoints, AppliesTheMountingAndEstimatesNormals) {
  LaserScan scan;
  scan.angle_min = -0.5;
  scan.angle_increment = 0.01;
  scan.range_min = 0.05;
  scan.range_max = 20.0;
  for (int k = 0; k <= 100; ++k) {  // a wall at x = 2 in the laser frame
    scan.ranges.push_back(
        static_cast<float>(2.0 / std::cos(scan.Angle(static_cast<std::size_t>(k)))));
  }
  scan.ranges[50] = 20.0F;  // no return
  scan.ranges[51] = std::nanf("");
  const Pose2 T_base_laser(0.22, 0.0, std::numbers::pi / 2);
  const ScanPoints points = ExtractScanPoints(scan, T_base_laser, 30.0);
  EXPECT_EQ(points.size(), 99U);
  ASSERT_EQ(points.no_return_directions.size(), 1U);
  EXPECT_TRUE(points.origin.isApprox(Eigen::Vector2d(0.22, 0.0)));
  for (std::size_t k = 0; k < points.size(); ++k) {
    // Laser x = 2 is base y = 2 after the 90 degree mounting.
    EXPECT_NEAR(points.points[k].y(), 2.0, 1e-5);
    EXPECT_NEAR(std::abs(points.normals[k].y()), 1.0, 1e-6);
    EXPECT_GT(points.normal_quality[k], 0.49F);
  }
  EXPECT_TRUE(points.no_return_directions[0].isApprox(Eigen::Vector2d(0.0, 1.0), 1e-9));
  const ScanPoints near = ExtractScanPoints(scan, T_base_laser, 2.01);
  EXPECT_LT(near.size(), points.size());
}

}  // namespace
}  // namespace gridslam
