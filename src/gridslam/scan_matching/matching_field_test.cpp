#include "gridslam/scan_matching/matching_field.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::scan_matching {
namespace {

// A scan of `beams` returns at random ranges in [1, 4] m (a cluttered scene).
ScanPoints RandomScan(std::mt19937& rng, int beams = 90) {
  LaserScan scan;
  scan.angle_min = -M_PI;
  scan.angle_increment = 2.0 * M_PI / beams;
  scan.range_min = 0.05;
  scan.range_max = 20.0;
  std::uniform_real_distribution<float> range(1.0F, 4.0F);
  for (int k = 0; k < beams; ++k) {
    scan.ranges.push_back(range(rng));
  }
  return ExtractScanPoints(scan, Pose2(), 30.0);
}

void ExpectSameDistances(const MatchingField& incremental, const RollingWindow& window,
                         double max_distance) {
  MatchingField full(max_distance);
  full.Rebuild(window);
  const MapLimits& limits = window.Limits();
  ASSERT_TRUE(incremental.Limits().Origin().isApprox(limits.Origin()));
  for (long k = 0; k < limits.NumCells(); ++k) {
    const auto index = static_cast<std::size_t>(k);
    ASSERT_EQ(incremental.SquaredDistanceCells(index), full.SquaredDistanceCells(index))
        << "cell " << k;
    ASSERT_EQ(incremental.Distance(index), full.Distance(index));
    const std::int32_t nearest = incremental.Nearest(index);
    if (nearest >= 0) {
      // Any nearest obstacle at the same distance is fine.
      ASSERT_EQ(window.Obstacles().data()[nearest], 1);
      const Eigen::Array2i d =
          window.Layout().Cell(index) - window.Layout().Cell(static_cast<std::size_t>(nearest));
      const int di = d.x();
      const int dj = d.y();
      ASSERT_EQ(static_cast<float>(di * di + dj * dj), full.SquaredDistanceCells(index));
    } else {
      ASSERT_EQ(full.Nearest(index), -1);
    }
  }
}

// A random drive through a rolling window whose field is updated after every `scans[u]` scans
// and must then hold the distances a rebuild gives. Returns the field's rebuilds.
long DriveAndCompare(std::uint32_t seed, const std::vector<int>& scans) {
  LocalMapOptions options;
  options.size = 8.0;
  std::mt19937 rng(seed);
  RollingWindow window(options, Eigen::Vector2d::Zero());
  const double max_distance = 0.3;
  MatchingField field(max_distance);
  std::uniform_real_distribution<double> step(-0.25, 0.45);
  Pose2 pose;
  for (const int n : scans) {
    for (int k = 0; k < n; ++k) {
      pose = pose * Pose2(step(rng), 0.3 * step(rng), 0.5 * step(rng));
      window.Recentre(pose.translation());
      window.InsertScan(pose, RandomScan(rng));
    }
    field.Update(window);
    window.ClearChanges();
    ExpectSameDistances(field, window, max_distance);
  }
  return field.NumRebuilds();
}

TEST(MatchingField, IncrementalUpdatesEqualARebuild) {
  EXPECT_EQ(DriveAndCompare(17, std::vector<int>(40, 1)), 1);  // only the first update rebuilds
}

// The front end's key-map field follows its window only when a match uses it: one update over
// the changes and shifts of several scans must hold the same distances as a rebuild too.
TEST(MatchingField, UpdatesAfterSeveralScansEqualARebuild) {
  const std::vector<int> scans = {1, 3, 7, 12, 2, 5, 9, 4};
  EXPECT_LT(DriveAndCompare(23, scans), static_cast<long>(scans.size()));  // incremental ran
}

TEST(MatchingField, InterpolatesBetweenCellCentresAndClampsOutside) {
  LocalMapOptions options;
  options.size = 4.0;
  RollingWindow window(options, Eigen::Vector2d::Zero());
  LaserScan scan;  // one return 1 m ahead
  scan.angle_min = 0.0;
  scan.angle_increment = 0.01;
  scan.range_min = 0.05;
  scan.range_max = 20.0;
  scan.ranges = {1.0F};
  window.InsertScan(Pose2(), ExtractScanPoints(scan, Pose2(), 30.0));
  MatchingField field(0.5);
  field.Update(window);
  const Eigen::Vector2d obstacle =
      window.Limits().CellCenter(window.Limits().CellIndex({1.0, 0.0}));
  Eigen::Vector2d gradient;
  EXPECT_NEAR(field.Interpolate(obstacle, &gradient), 0.0, 1e-9);
  EXPECT_NEAR(field.Interpolate(obstacle + Eigen::Vector2d(0.0, 0.1), &gradient), 0.1, 1e-6);
  EXPECT_NEAR(gradient.y(), 1.0, 1e-6);
  EXPECT_NEAR(field.Interpolate(obstacle + Eigen::Vector2d(0.0, 0.025), nullptr), 0.025, 1e-6);
  EXPECT_NEAR(field.Interpolate({30.0, 0.0}, &gradient), 0.5, 1e-12);  // outside
  EXPECT_EQ(gradient.norm(), 0.0);
  const double edge = window.Limits().Origin().x() + 0.01;  // within half a cell of the border
  EXPECT_NEAR(field.Interpolate({edge, 0.0}, &gradient), 0.5, 1e-12);
  EXPECT_EQ(gradient.norm(), 0.0);
}

}  // namespace
}  // namespace gridslam::scan_matching
