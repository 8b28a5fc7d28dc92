#include "gridslam/keymap/key_map_builder.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "gridslam/grid/log_odds.hpp"

namespace gridslam::keymap {
namespace {

Frame MakeFrame(double t, const Pose2& T_odom_base) {
  Frame frame;
  frame.time = FromSeconds(t);
  frame.corrected_time = frame.time;
  frame.T_odom_base = T_odom_base;
  frame.T_base_laser = Pose2(0.1, 0.0, 0.0);
  frame.scan.angle_min = -std::numbers::pi / 2;
  frame.scan.angle_increment = std::numbers::pi / 180;
  frame.scan.range_min = 0.01;
  frame.scan.range_max = 30.0;
  frame.scan.ranges.assign(181, 3.0F);
  return frame;
}

TEST(KeyMapBuilder, SnapshotsWhenTheWindowRollsAndExpressesScansInTheKeyFrame) {
  LocalMapOptions map_options;
  map_options.size = 8.0;
  RollingWindow window(map_options, Eigen::Vector2d::Zero());
  KeyMapBuilder builder(KeyMapOptions{});
  std::vector<KeyMap> keys;
  std::vector<Pose2> poses;
  for (int k = 0; k < 60; ++k) {  // 0.05 m per scan along x with a small turn
    const Pose2 pose(0.05 * k, 0.01 * k, 0.002 * k);
    const Frame frame = MakeFrame(100.0 + 0.1 * k, pose);
    window.Recentre(pose.translation());
    window.InsertScan(pose, ExtractScanPoints(frame.scan, frame.T_base_laser, 30.0));
    builder.AddScan(frame, pose);
    poses.push_back(pose);
    if (auto key = builder.MaybeSnapshot(window)) {
      keys.push_back(std::move(*key));
    }
  }
  if (auto key = builder.Finish(window)) {
    keys.push_back(std::move(*key));
  }
  ASSERT_GE(keys.size(), 3U);  // the window rolls every metre: at 1, 2 m and the final one
  std::size_t scan_index = 0;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const KeyMap& key = keys[k];
    EXPECT_EQ(key.id, static_cast<int>(k));
    EXPECT_EQ(key.T_odom_key.theta(), 0.0);
    EXPECT_NEAR(key.log_odds.Limits().Origin().x(), -0.5 * map_options.NumCells() * 0.05, 1e-9);
    for (const KeyMapScan& scan : key.scans) {
      ASSERT_LT(scan_index, poses.size());
      EXPECT_TRUE(IsApprox(key.T_odom_key * scan.T_key_scan, poses[scan_index], 1e-9, 1e-12));
      EXPECT_EQ(scan.scan.size(), 181U);
      ++scan_index;
    }
  }
  EXPECT_EQ(scan_index, poses.size());  // every scan in exactly one key map
  // The window rolled along x to centre the robot, so the last scan of the first key map is near
  // the key frame's origin along x (y stayed under shift_distance).
  const KeyMapScan& last = keys[0].scans.back();
  EXPECT_LT(std::abs(last.T_key_scan.x()), 0.05);
  EXPECT_LT(last.T_key_scan.translation().norm(), map_options.shift_distance);
}

TEST(KeyMapBuilder, SnapshotsAfterThePeriodWhenStanding) {
  LocalMapOptions map_options;
  map_options.size = 8.0;
  RollingWindow window(map_options, Eigen::Vector2d::Zero());
  KeyMapOptions options;
  options.keymap_period = 5.0;
  options.keep_scans = false;
  KeyMapBuilder builder(options);
  int snapshots = 0;
  for (int k = 0; k <= 120; ++k) {
    const Frame frame = MakeFrame(10.0 + 0.1 * k, Pose2());
    builder.AddScan(frame, Pose2());
    if (auto key = builder.MaybeSnapshot(window)) {
      ++snapshots;
      EXPECT_TRUE(key->scans.front().scan.ranges.empty());
    }
  }
  EXPECT_EQ(snapshots, 2);
}

TEST(KeyMapBuilder, KeyMapsAreTheCentreOfALargerWindow) {
  LocalMapOptions map_options;
  map_options.size = 8.0;
  RollingWindow window(map_options, Eigen::Vector2d(3.0, -2.0));
  Frame frame = MakeFrame(1.0, Pose2(3.0, -2.0, 0.4));
  frame.scan.ranges.assign(181, 1.5F);  // inside the key map
  window.InsertScan(frame.T_odom_base, ExtractScanPoints(frame.scan, frame.T_base_laser, 30.0));
  KeyMapOptions options;
  options.size = 4.0;
  KeyMapBuilder builder(options);
  builder.AddScan(frame, frame.T_odom_base);
  const std::optional<KeyMap> key = builder.Finish(window);
  ASSERT_TRUE(key);
  EXPECT_EQ(key->log_odds.Width(), 81);
  EXPECT_EQ(key->log_odds.Height(), 81);
  EXPECT_NEAR(key->log_odds.Limits().Origin().x(), -0.5 * 81 * 0.05, 1e-9);
  // Every cell of the key map equals the window cell at the same odometry-frame position.
  int occupied = 0;
  for (int j = 0; j < 81; ++j) {
    for (int i = 0; i < 81; ++i) {
      const Eigen::Vector2d p_odom =
          key->T_odom_key * key->log_odds.Limits().CellCenter(Eigen::Array2i(i, j));
      ASSERT_EQ(key->log_odds(i, j), window.LogOdds().at(window.Limits().CellIndex(p_odom)));
      occupied += key->log_odds(i, j) > 0.0F ? 1 : 0;
    }
  }
  EXPECT_GT(occupied, 10);
}

TEST(KeyMapImages, ClassifyCellsByProbability) {
  Grid2D<float> grid(MapLimits(0.05, Eigen::Vector2d::Zero(), 3, 1), 0.0F);
  grid(0, 0) = 2.0F;
  grid(2, 0) = -2.0F;
  const OccupancyImage image = ToOccupancyImage(grid, 0.6, 0.4);
  EXPECT_EQ(image(0, 0), kOccupiedCell);
  EXPECT_EQ(image(1, 0), kUnknownCell);
  EXPECT_EQ(image(2, 0), kFreeCell);
  const Grid2D<std::uint8_t> mask = ObstacleMask(grid, 0.6);
  EXPECT_EQ(mask(0, 0), 1);
  EXPECT_EQ(mask(1, 0), 0);
}

}  // namespace
}  // namespace gridslam::keymap
