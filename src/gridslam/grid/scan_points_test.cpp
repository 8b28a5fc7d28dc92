#include "gridslam/grid/scan_points.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

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

// The beam directions of the last geometry are reused: scans of other geometries in between, and
// one of the same geometry again, give exactly the points computed afresh (Angle, cos, sin).
TEST(ExtractScanPoints, ScansOfChangingGeometryGetTheirOwnBeamDirections) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> range(0.5F, 6.0F);
  auto make = [&](double angle_min, double increment, int beams) {
    LaserScan scan;
    scan.angle_min = angle_min;
    scan.angle_increment = increment;
    scan.range_min = 0.05;
    scan.range_max = 20.0;
    for (int k = 0; k < beams; ++k) {
      scan.ranges.push_back(range(rng));
    }
    return scan;
  };
  const std::vector<LaserScan> scans = {make(-1.5, 0.01, 181),  make(-1.5, 0.01, 181),
                                        make(-1.49, 0.01, 181), make(-1.5, 0.01, 180),
                                        make(-1.5, 0.02, 181),  make(-1.5, 0.01, 181)};
  for (const LaserScan& scan : scans) {
    const ScanPoints points = ExtractScanPoints(scan, Pose2(), 30.0);
    ASSERT_EQ(points.size(), scan.size());
    for (std::size_t k = 0; k < scan.size(); ++k) {
      const double a = scan.Angle(k);
      const double r = scan.ranges[k];
      EXPECT_EQ(points.points[k], Eigen::Vector2d(r * std::cos(a), r * std::sin(a)));
    }
  }
}

// A wall y = 1 seen at 3..8 degrees: consecutive returns lie metres apart, beyond the normal
// neighbourhood, so they have no normal unless grazing_normals recognizes the line; a pole in
// front of a background wall never passes for a wall.
TEST(ExtractScanPoints, GrazingWallsGetTheirNormalIsolatedObjectsDoNot) {
  LaserScan scan;
  scan.angle_min = 3.0 * std::numbers::pi / 180.0;
  scan.angle_increment = std::numbers::pi / 180.0;
  scan.range_min = 0.05;
  scan.range_max = 80.0;
  for (int k = 0; k <= 5; ++k) {
    scan.ranges.push_back(
        static_cast<float>(1.0 / std::sin(scan.Angle(static_cast<std::size_t>(k)))));
  }
  const ScanPoints plain = ExtractScanPoints(scan, Pose2(), 30.0);
  const ScanPoints grazing = ExtractScanPoints(scan, Pose2(), 30.0, 0.25, true);
  ASSERT_EQ(plain.size(), 6U);
  ASSERT_EQ(grazing.size(), 6U);
  for (std::size_t k = 1; k + 1 < 6; ++k) {
    EXPECT_LT(plain.normal_quality[k], 0.5F) << k;
    EXPECT_GE(grazing.normal_quality[k], 0.5F) << k;
    EXPECT_NEAR(std::abs(grazing.normals[k].y()), 1.0, 1e-4) << k;
  }
  // The two ends have a neighbour on one side only: no line to test.
  EXPECT_LT(grazing.normal_quality[0], 0.5F);

  LaserScan pole;
  pole.angle_min = -0.1;
  pole.angle_increment = std::numbers::pi / 180.0;
  pole.range_min = 0.05;
  pole.range_max = 80.0;
  pole.ranges.assign(11, 10.0F);  // background at 10 m
  pole.ranges[5] = 4.0F;          // a pole
  const ScanPoints with_pole = ExtractScanPoints(pole, Pose2(), 30.0, 0.25, true);
  ASSERT_EQ(with_pole.size(), 11U);
  EXPECT_LT(with_pole.normal_quality[5], 0.5F);
  EXPECT_GE(with_pole.normal_quality[4], 0.5F);
}

// A wall x = 1.2 m seen by 0.5 degree beams whose ranges carry noise of the beam spacing's
// order (3 cm against 1 cm): five beams span 4 cm of wall, too little to pin a normal. The wall
// normals' windows grow by the scan's own measured noise; the five-beam normals stay as they are,
// and a scan without noise gets wall normals equal to them.
LaserScan NoisyWall(double sigma, unsigned seed) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 3;
  scan.angle_increment = std::numbers::pi / 360.0;
  scan.range_min = 0.05;
  scan.range_max = 20.0;
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int k = 0; k <= 240; ++k) {
    const double range = 1.2 / std::cos(scan.Angle(static_cast<std::size_t>(k)));
    scan.ranges.push_back(static_cast<float>(range + noise(random)));
  }
  return scan;
}

double RmsNormalError(const std::vector<Eigen::Vector2d>& normals) {
  double sum = 0.0;
  for (const Eigen::Vector2d& normal : normals) {
    const double error = std::asin(std::min(1.0, std::abs(normal.y())));  // the wall's is (1, 0)
    sum += error * error;
  }
  return std::sqrt(sum / static_cast<double>(normals.size()));
}

TEST(ExtractScanPoints, WallNormalsFitMoreBeamsWhereTheMeasuredNoiseDemands) {
  NormalEstimation five_beams;
  NormalEstimation walls;
  walls.max_angle_sigma = 0.1;
  const LaserScan noisy = NoisyWall(0.03, 7);
  const ScanPoints fixed = ExtractScanPoints(noisy, Pose2(), 30.0, five_beams);
  const ScanPoints grown = ExtractScanPoints(noisy, Pose2(), 30.0, walls);
  ASSERT_EQ(fixed.size(), 241U);
  EXPECT_TRUE(fixed.wall_normals.empty());
  ASSERT_EQ(grown.wall_normals.size(), 241U);
  ASSERT_EQ(grown.wall_normal_quality.size(), 241U);
  EXPECT_EQ(grown.normals, fixed.normals);
  EXPECT_EQ(grown.normal_quality, fixed.normal_quality);
  // The noise across the wall is the range noise times the cosine of the incidence (0.5-1).
  EXPECT_GT(grown.surface_noise, 0.015);
  EXPECT_LT(grown.surface_noise, 0.035);
  EXPECT_GT(RmsNormalError(fixed.normals), 0.3);
  EXPECT_LT(RmsNormalError(grown.wall_normals), 0.2);  // 8 beams either side at most

  const ScanPoints clean = ExtractScanPoints(NoisyWall(0.001, 7), Pose2(), 30.0, walls);
  EXPECT_LT(clean.surface_noise, 0.002);
  EXPECT_EQ(clean.wall_normals, clean.normals);
  EXPECT_EQ(clean.wall_normal_quality, clean.normal_quality);
}

// A quiet laser (5 mm) at 1 degree: two thirds of its beams see a far, uneven wall (a 0.3 m
// step every beam at 20 m, where five beams span 1.4 m and the normal window stretches to six
// beam spacings), the rest a near wall. The far windows' residual is the wall's shape, not
// noise: the noise is measured on the compact windows only.
TEST(ExtractScanPoints, SurfaceNoiseIgnoresStretchedWindows) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 180.0;
  scan.range_min = 0.05;
  scan.range_max = 80.0;
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 0.005);
  for (int k = 0; k <= 180; ++k) {
    const double range = k < 120 ? 20.0 + 0.3 * (k % 2) : 1.0;
    scan.ranges.push_back(static_cast<float>(range + noise(random)));
  }
  const ScanPoints points = ExtractScanPoints(scan, Pose2(), 30.0, NormalEstimation{});
  ASSERT_EQ(points.size(), 181U);
  EXPECT_GT(points.surface_noise, 0.002);
  EXPECT_LT(points.surface_noise, 0.008);
}

}  // namespace
}  // namespace gridslam
