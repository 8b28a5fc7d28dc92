#include "gridslam/simulation/sensor_models.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gridslam::simulation {
namespace {

World Box() {
  WorldBuilder builder(20.0, 20.0, 0.05);
  builder.Carve(1.0, 1.0, 19.0, 19.0);
  return builder.Build("box", {});
}

LaserSimOptions Noiseless() {
  LaserSimOptions options;
  options.range_noise = 0.0;
  options.spurious_probability = 0.0;
  options.missing_probability = 0.0;
  return options;
}

TEST(LaserSimulatorTest, GeometryAndNoiselessRangesMatchTheWorld) {
  const World world = Box();
  const LaserSimulator laser(world, Noiseless());
  Random random(1);
  const LaserScan scan = laser.Scan(Pose2(5.0, 10.0, 0.0), random);
  ASSERT_EQ(scan.size(), 181U);
  EXPECT_NEAR(scan.angle_min, -std::numbers::pi / 2.0, 1e-12);
  EXPECT_NEAR(scan.Angle(180), std::numbers::pi / 2.0, 1e-12);
  EXPECT_NEAR(scan.ranges[90], 14.0, 1e-5);  // ahead: wall face at x = 19
  EXPECT_NEAR(scan.ranges[0], 9.0, 1e-5);    // right: wall face at y = 1
  EXPECT_NEAR(scan.ranges[180], 9.0, 1e-5);  // left: wall face at y = 19
  EXPECT_EQ(scan.CountHits(), 181U);
}

TEST(LaserSimulatorTest, FarWallsAreNoReturnsWrittenAsTheConfiguredValue) {
  const World world = Box();
  LaserSimOptions options = Noiseless();
  options.max_range = 10.0;
  options.no_return_range = 81.91;
  const LaserSimulator laser(world, options);
  Random random(1);
  const LaserScan scan = laser.Scan(Pose2(5.0, 10.0, 0.0), random);
  EXPECT_FLOAT_EQ(scan.ranges[90], 81.91F);  // 14 m ahead: beyond max_range
  EXPECT_FALSE(scan.IsHit(90));
  EXPECT_TRUE(scan.IsHit(0));
}

TEST(LaserSimulatorTest, NoiseAndDropoutsHaveTheConfiguredStatistics) {
  const World world = Box();
  LaserSimOptions options;
  options.range_noise = 0.02;
  options.missing_probability = 0.05;
  options.spurious_probability = 0.02;
  const LaserSimulator laser(world, options);
  const LaserSimulator exact(world, Noiseless());
  Random random(2);
  Random unused(3);
  double sum_sq = 0.0;
  double normal = 0;
  double missing = 0;
  double shorter = 0;
  double beams = 0;
  for (int k = 0; k < 200; ++k) {
    const Pose2 pose(3.0 + 0.05 * k, 10.0, 0.01 * k);
    const LaserScan noisy = laser.Scan(pose, random);
    const LaserScan truth = exact.Scan(pose, unused);
    for (std::size_t b = 0; b < noisy.size(); ++b, beams += 1) {
      const double e = noisy.ranges[b] - truth.ranges[b];
      if (!noisy.IsHit(b)) {
        missing += 1;
      } else if (e < -0.2) {
        shorter += 1;
      } else {
        sum_sq += e * e;
        normal += 1;
      }
    }
  }
  EXPECT_NEAR(std::sqrt(sum_sq / normal), 0.02, 0.001);
  EXPECT_NEAR(missing / beams, 0.05, 0.01);
  EXPECT_NEAR(shorter / beams, 0.02, 0.006);
}

TEST(OdometrySimulatorTest, NoiselessOdometryIsExactAndBiasScales) {
  OdometryNoiseOptions options{0, 0, 0, 0, 0, 0, 0};
  Random random(4);
  const Pose2 step(0.1, 0.01, 0.05);
  EXPECT_TRUE(IsApprox(OdometrySimulator(options).Measure(step, random), step));
  options.translation_scale_bias = 0.1;
  options.rotation_scale_bias = -0.2;
  const Pose2 biased = OdometrySimulator(options).Measure(step, random);
  EXPECT_TRUE(IsApprox(biased, Pose2(0.11, 0.011, 0.04), 1e-12, 1e-12));
}

TEST(OdometrySimulatorTest, ErrorVarianceGrowsLinearlyWithDistance) {
  OdometryNoiseOptions options;
  const OdometrySimulator odometry(options);
  Random random(5);
  // Drive 1 m and 4 m straight in 1 cm steps, many times: the heading error's standard deviation
  // doubles (variance x4), as for a random walk.
  std::vector<double> sigma;
  for (const int steps : {100, 400}) {
    double sum_sq = 0.0;
    const int runs = 400;
    for (int r = 0; r < runs; ++r) {
      Pose2 pose;
      for (int k = 0; k < steps; ++k) {
        pose = pose * odometry.Measure(Pose2(0.01, 0.0, 0.0), random);
      }
      sum_sq += pose.theta() * pose.theta();
    }
    sigma.push_back(std::sqrt(sum_sq / runs));
  }
  EXPECT_NEAR(sigma[0], options.rotation_noise_per_meter, 0.15 * options.rotation_noise_per_meter);
  EXPECT_NEAR(sigma[1] / sigma[0], 2.0, 0.3);
}

}  // namespace
}  // namespace gridslam::simulation
