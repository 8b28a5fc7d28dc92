#include "gridslam/perturb/sensor_faults.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace gridslam::perturb {
namespace {

/// 181 beams over 180 deg, beam k at range 1 + 0.1 k (1 m .. 19 m), max 80 m.
LaserScan MakeScan() {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 180;
  scan.range_max = 80.0;
  for (int k = 0; k <= 180; ++k) {
    scan.ranges.push_back(static_cast<float>(1.0 + 0.1 * k));
  }
  return scan;
}

LaserScan Apply(const LaserScan& scan, const PerturbOptions& options) {
  simulation::Random noise(1, 1);
  simulation::Random dropout(1, 2);
  return PerturbScan(scan, options, noise, dropout);
}

TEST(SensorFaults, NoFaultKeepsTheScan) {
  const LaserScan scan = MakeScan();
  EXPECT_FALSE(PerturbsSensor(PerturbOptions{}));
  const LaserScan out = Apply(scan, {});
  EXPECT_EQ(out.ranges, scan.ranges);
  EXPECT_EQ(out.angle_min, scan.angle_min);
}

TEST(SensorFaults, RangeLimitTurnsLongReadingsIntoNoReturns) {
  PerturbOptions options;
  options.max_range = 8.0;
  const LaserScan out = Apply(MakeScan(), options);
  ASSERT_EQ(out.size(), 181U);
  EXPECT_DOUBLE_EQ(out.range_max, 8.0);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double r = 1.0 + 0.1 * static_cast<double>(k);
    EXPECT_EQ(out.IsHit(k), r < 8.0 - 1e-6) << k;
  }
  EXPECT_EQ(out.CountHits(), 70U);  // 1.0 .. 7.9 m
}

// 5.6 m has no exact float: the readings set to the limit must still be no-returns (they were hits
// on a circle around the robot before LaserScan compared in the readings' precision).
TEST(SensorFaults, ARangeLimitAFloatCannotHoldStillMakesNoReturns) {
  PerturbOptions options;
  options.max_range = 5.6;
  const LaserScan out = Apply(MakeScan(), options);
  std::size_t no_returns = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double r = 1.0 + 0.1 * static_cast<double>(k);
    EXPECT_EQ(out.IsHit(k), r < 5.6 - 1e-6) << k;
    no_returns += out.IsNoReturn(k) ? 1 : 0;
  }
  EXPECT_EQ(out.CountHits(), 46U);  // 1.0 .. 5.5 m
  EXPECT_EQ(no_returns, out.size() - 46U);
}

TEST(SensorFaults, FieldOfViewCropKeepsTheCentralBeams) {
  PerturbOptions options;
  options.fov_deg = 90.0;
  const LaserScan scan = MakeScan();
  const LaserScan out = Apply(scan, options);
  ASSERT_EQ(out.size(), 91U);  // -45 .. +45 deg
  EXPECT_NEAR(out.angle_min, -std::numbers::pi / 4, 1e-9);
  EXPECT_EQ(out.ranges.front(), scan.ranges[45]);
  EXPECT_EQ(out.ranges.back(), scan.ranges[135]);
}

TEST(SensorFaults, FieldOfViewCropOfAFullCircleStartingAtZeroWraps) {
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = std::numbers::pi / 180;
  scan.range_max = 30.0;
  for (int k = 0; k < 360; ++k) {
    scan.ranges.push_back(static_cast<float>(k));
  }
  PerturbOptions options;
  options.fov_deg = 20.0;
  const LaserScan out = Apply(scan, options);
  ASSERT_EQ(out.size(), 21U);
  EXPECT_NEAR(NormalizeAngle(out.angle_min), -DegToRad(10.0), 1e-9);
  EXPECT_EQ(out.ranges.front(), 350.0F);
  EXPECT_EQ(out.ranges[10], 0.0F);
  EXPECT_EQ(out.ranges.back(), 10.0F);
}

TEST(SensorFaults, BeamSubsamplingKeepsEveryKthBeamAndItsAngle) {
  PerturbOptions options;
  options.beam_step = 4;
  const LaserScan scan = MakeScan();
  const LaserScan out = Apply(scan, options);
  ASSERT_EQ(out.size(), 46U);
  for (std::size_t j = 0; j < out.size(); ++j) {
    EXPECT_EQ(out.ranges[j], scan.ranges[4 * j]);
    EXPECT_NEAR(out.Angle(j), scan.Angle(4 * j), 1e-12);
  }
}

TEST(SensorFaults, NoiseHasItsStandardDeviation) {
  PerturbOptions options;
  options.range_noise = 0.05;
  const LaserScan scan = MakeScan();
  simulation::Random noise(7, 1);
  simulation::Random dropout(7, 2);
  double ss = 0.0;
  double sum = 0.0;
  int n = 0;
  for (int rep = 0; rep < 50; ++rep) {
    const LaserScan out = PerturbScan(scan, options, noise, dropout);
    for (std::size_t k = 0; k < out.size(); ++k) {
      const double d = out.ranges[k] - scan.ranges[k];
      sum += d;
      ss += d * d;
      ++n;
    }
  }
  EXPECT_NEAR(sum / n, 0.0, 0.005);
  EXPECT_NEAR(std::sqrt(ss / n), 0.05, 0.005);
}

TEST(SensorFaults, DroppedBeamsBecomeZeroNoReturns) {
  PerturbOptions options;
  options.beam_dropout = 0.3;
  const LaserScan scan = MakeScan();
  simulation::Random noise(7, 1);
  simulation::Random dropout(7, 2);
  long dropped = 0;
  long total = 0;
  for (int rep = 0; rep < 50; ++rep) {
    const LaserScan out = PerturbScan(scan, options, noise, dropout);
    for (std::size_t k = 0; k < out.size(); ++k) {
      ++total;
      if (out.ranges[k] == 0.0F) {
        ++dropped;
        EXPECT_FALSE(out.IsHit(k));
      } else {
        EXPECT_EQ(out.ranges[k], scan.ranges[k]);
      }
    }
  }
  EXPECT_NEAR(static_cast<double>(dropped) / static_cast<double>(total), 0.3, 0.03);
}

}  // namespace
}  // namespace gridslam::perturb
