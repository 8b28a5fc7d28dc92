#include "gridslam/grid/rolling_window.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "gridslam/grid/log_odds.hpp"

namespace gridslam {
namespace {

// A 181-beam scan over 180 degrees of a wall at x = `distance` in front of the laser.
LaserScan WallScan(double distance, int beams = 181) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / (beams - 1);
  scan.range_min = 0.01;
  scan.range_max = 30.0;
  for (int k = 0; k < beams; ++k) {
    const double a = scan.Angle(static_cast<std::size_t>(k));
    const double c = std::cos(a);
    scan.ranges.push_back(c > 0.05 ? static_cast<float>(distance / c) : 81.83F);
  }
  return scan;
}

LocalMapOptions SmallWindow() {
  LocalMapOptions options;
  options.size = 8.0;
  return options;
}

TEST(LocalMapOptions, WindowHasAnOddNumberOfCells) {
  LocalMapOptions options;
  options.size = 15.0;
  EXPECT_EQ(options.NumCells(), 301);
  options.size = 12.0;
  EXPECT_EQ(options.NumCells(), 241);
  EXPECT_TRUE(options.Validate().ok());
  options.miss_probability = 0.6;
  EXPECT_FALSE(options.Validate().ok());
}

TEST(RollingWindow, StartsUnknownAndCentredOnTheRobot) {
  RollingWindow window(SmallWindow(), Eigen::Vector2d(1.02, -3.01));
  EXPECT_EQ(window.Limits().Width(), 161);
  EXPECT_TRUE(window.Limits().Contains(window.Limits().CellIndex({1.02, -3.01})));
  EXPECT_TRUE(
      (window.Limits().CellIndex(window.Centre()) == window.Limits().CellIndex({1.02, -3.01}))
          .all());
  EXPECT_EQ(window.NumObstacles(), 0);
  for (const float l : window.LogOdds().Cells()) {
    ASSERT_EQ(l, kUnknownLogOdds);
  }
}

TEST(RollingWindow, InsertMarksTheWallAndClearsInFrontOfIt) {
  RollingWindow window(SmallWindow(), Eigen::Vector2d::Zero());
  const ScanPoints points = ExtractScanPoints(WallScan(2.0), Pose2(), 30.0);
  window.InsertScan(Pose2(), points);
  const MapLimits& limits = window.Limits();
  const Eigen::Array2i wall = limits.CellIndex({2.0 + 0.01, 0.3});
  const Eigen::Array2i free = limits.CellIndex({1.0, 0.3});
  const Eigen::Array2i behind = limits.CellIndex({2.5, 0.3});
  EXPECT_EQ(window.Obstacles().at(wall), 1);
  EXPECT_GT(window.LogOdds().at(wall), 0.0F);
  EXPECT_LT(window.LogOdds().at(free), 0.0F);
  EXPECT_EQ(window.LogOdds().at(behind), kUnknownLogOdds);
  EXPECT_GT(window.NumObstacles(), 20);
  EXPECT_FALSE(window.ChangedCells().empty());
  // The mean hit point of a wall cell lies on the wall, and its normal is along x.
  const auto index = static_cast<std::int32_t>(window.Layout().Index(wall));
  EXPECT_NEAR(window.MeanPoint(index).x(), 2.0, 1e-3);
  const CellSurface& s = window.Surface(static_cast<std::size_t>(index));
  EXPECT_NEAR(std::abs(s.normal_x) / s.Planarity(), 1.0, 1e-3);
  EXPECT_GT(s.Planarity(), 0.45F);
}

TEST(RollingWindow, NoReturnsNaNAndEmptyScansNeverMarkObstacles) {
  for (const bool clear : {false, true}) {
    LocalMapOptions options = SmallWindow();
    options.clear_no_returns = clear;
    options.no_return_clearing_range = 2.0;
    RollingWindow window(options, Eigen::Vector2d::Zero());
    LaserScan scan = WallScan(2.0, 361);
    for (std::size_t k = 0; k < scan.size(); ++k) {
      const float values[] = {81.83F,
                              81.91F,
                              80.0F,
                              std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::infinity(),
                              -1.0F,
                              0.0F};
      scan.ranges[k] = values[k % 7];
    }
    window.InsertScan(Pose2(0.1, 0.2, 0.3), ExtractScanPoints(scan, Pose2(), 30.0));
    window.InsertScan(Pose2(), ExtractScanPoints(LaserScan{}, Pose2(), 30.0));
    EXPECT_EQ(window.NumObstacles(), 0);
    bool any_cleared = false;
    for (const float l : window.LogOdds().Cells()) {
      ASSERT_LE(l, 0.0F);
      any_cleared = any_cleared || l < 0.0F;
    }
    EXPECT_EQ(any_cleared, clear);
    // Clearing stops at the cap.
    const Eigen::Array2i far = window.Limits().CellIndex({3.0, 0.0});
    EXPECT_EQ(window.LogOdds().at(far), kUnknownLogOdds);
  }
}

TEST(RollingWindow, ShiftKeepsWorldCoordinatesAndForgetsLeavingCells) {
  RollingWindow window(SmallWindow(), Eigen::Vector2d::Zero());
  window.InsertScan(Pose2(), ExtractScanPoints(WallScan(2.02), Pose2(), 30.0));
  window.ClearChanges();
  const Eigen::Vector2d wall_point(2.02, 0.5);
  const float before = window.LogOdds().at(window.Limits().CellIndex(wall_point));
  const Eigen::Vector2d free_point(1.0, -0.5);
  const float free_before = window.LogOdds().at(window.Limits().CellIndex(free_point));
  const long obstacles = window.NumObstacles();

  EXPECT_TRUE((window.Recentre({0.5, 0.3}) == 0).all());  // under shift_distance
  const int expected_shift = window.Limits().CellIndex({1.3, -0.2}).x() - 80;
  const Eigen::Array2i shift = window.Recentre({1.3, -0.2});
  EXPECT_EQ(shift.x(), expected_shift);
  EXPECT_EQ(shift.y(), 0);
  EXPECT_TRUE((window.PendingShift() == shift).all());
  EXPECT_TRUE(
      (window.Limits().CellIndex(window.Centre()) == window.Limits().CellIndex({1.3, 0.0})).all());
  EXPECT_EQ(window.LogOdds().at(window.Limits().CellIndex(wall_point)), before);
  EXPECT_EQ(window.LogOdds().at(window.Limits().CellIndex(free_point)), free_before);
  EXPECT_EQ(window.NumObstacles(), obstacles);  // the wall is still inside
  const auto index =
      static_cast<std::int32_t>(window.Layout().Index(window.Limits().CellIndex(wall_point)));
  EXPECT_NEAR(window.MeanPoint(index).x(), 2.02, 1e-3);

  // Move far enough for the wall to leave: its cells are forgotten; entering cells are unknown.
  window.Recentre({8.0, 0.0});
  EXPECT_EQ(window.NumObstacles(), 0);
  for (const float l : window.LogOdds().Cells()) {
    ASSERT_EQ(l, kUnknownLogOdds);
  }
}

TEST(RollingWindow, ReportsAShiftBackAndForthSinceTheLastClear) {
  RollingWindow window(SmallWindow(), Eigen::Vector2d::Zero());
  EXPECT_FALSE(window.ShiftReversed());
  ASSERT_GT(window.Recentre({1.3, 0.0}).x(), 0);
  ASSERT_GT(window.Recentre({2.6, 1.3}).x(), 0);  // onwards in x, and a first step in y
  EXPECT_FALSE(window.ShiftReversed());
  ASSERT_LT(window.Recentre({1.3, 1.3}).x(), 0);  // back in x
  EXPECT_TRUE(window.ShiftReversed());
  window.ClearChanges();
  EXPECT_FALSE(window.ShiftReversed());
  ASSERT_LT(window.Recentre({1.3, 0.0}).y(), 0);  // a first step since the clear
  EXPECT_FALSE(window.ShiftReversed());
}

TEST(RollingWindow, SnapshotIsExpressedInTheCentreFrame) {
  RollingWindow window(SmallWindow(), Eigen::Vector2d(10.0, 5.0));
  window.InsertScan(Pose2(10.0, 5.0, 0.0), ExtractScanPoints(WallScan(2.0), Pose2(), 30.0));
  const Grid2D<float> snapshot = window.SnapshotInCentreFrame();
  const Eigen::Vector2d centre = window.Centre();
  const Eigen::Vector2d p_odom(12.01, 5.4);
  EXPECT_EQ(snapshot.at(snapshot.Limits().CellIndex(p_odom - centre)),
            window.LogOdds().at(window.Limits().CellIndex(p_odom)));
  EXPECT_NEAR(snapshot.Limits().Origin().x(), -0.5 * 161 * 0.05, 1e-9);
}

TEST(RollingWindow, MissesCanTurnAnObstacleBackToFree) {
  RollingWindow window(SmallWindow(), Eigen::Vector2d::Zero());
  window.InsertScan(Pose2(), ExtractScanPoints(WallScan(1.0), Pose2(), 30.0));
  const Eigen::Array2i cell = window.Limits().CellIndex({1.01, 0.0});
  ASSERT_EQ(window.Obstacles().at(cell), 1);
  window.ClearChanges();
  for (int k = 0; k < 5; ++k) {  // the obstacle moved away
    window.InsertScan(Pose2(), ExtractScanPoints(WallScan(3.0), Pose2(), 30.0));
  }
  EXPECT_EQ(window.Obstacles().at(cell), 0);
  EXPECT_FALSE(window.ChangedCells().empty());
  EXPECT_EQ(window.Surface(window.Layout().Index(cell)).hits, 0);
}

// A scan of random returns in [0.5, 6] m all around (some beyond the window's edge).
ScanPoints RandomScan(std::mt19937& rng) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi;
  scan.angle_increment = 2.0 * std::numbers::pi / 120;
  scan.range_min = 0.05;
  scan.range_max = 20.0;
  std::uniform_real_distribution<float> range(0.5F, 6.0F);
  for (int k = 0; k < 120; ++k) {
    scan.ranges.push_back(range(rng));
  }
  return ExtractScanPoints(scan, Pose2(), 30.0);
}

std::vector<Eigen::Array2i> LogicalChanges(const RollingWindow& window) {
  std::vector<Eigen::Array2i> cells;
  for (const std::int32_t index : window.ChangedCells()) {
    cells.push_back(window.Layout().Cell(static_cast<std::size_t>(index)));
  }
  return cells;
}

// Every layer, read cell by cell in logical coordinates, is the same in both windows.
void ExpectSameLogicalCells(const RollingWindow& a, const RollingWindow& b) {
  ASSERT_EQ(a.Limits().Origin(), b.Limits().Origin());
  ASSERT_EQ(a.NumObstacles(), b.NumObstacles());
  long obstacles = 0;
  for (int j = 0; j < a.Limits().Height(); ++j) {
    for (int i = 0; i < a.Limits().Width(); ++i) {
      ASSERT_EQ(a.LogOdds()(i, j), b.LogOdds()(i, j)) << "cell " << i << ", " << j;
      ASSERT_EQ(a.Obstacles()(i, j), b.Obstacles()(i, j));
      obstacles += a.Obstacles()(i, j);
      const auto ia = static_cast<std::int32_t>(a.Layout().Index(i, j));
      const auto ib = static_cast<std::int32_t>(b.Layout().Index(i, j));
      const CellSurface& sa = a.Surface(static_cast<std::size_t>(ia));
      const CellSurface& sb = b.Surface(static_cast<std::size_t>(ib));
      ASSERT_EQ(sa.hits, sb.hits);
      ASSERT_EQ(sa.mean_x, sb.mean_x);
      ASSERT_EQ(sa.mean_y, sb.mean_y);
      ASSERT_EQ(sa.normal_x, sb.normal_x);
      ASSERT_EQ(sa.normal_y, sb.normal_y);
      ASSERT_EQ(a.MeanPoint(ia), b.MeanPoint(ib));
    }
  }
  ASSERT_EQ(obstacles, a.NumObstacles());
  const std::vector<Eigen::Array2i> ca = LogicalChanges(a);
  const std::vector<Eigen::Array2i> cb = LogicalChanges(b);
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t k = 0; k < ca.size(); ++k) {
    ASSERT_TRUE((ca[k] == cb[k]).all());
  }
  ASSERT_EQ(a.SnapshotInCentreFrame(41).Cells(), b.SnapshotInCentreFrame(41).Cells());
}

// The window's storage rotates as it recentres (RingGrid): two windows over the same cells whose
// storage is rotated differently must agree cell by cell after many random scans and shifts. A
// power-of-two resolution keeps the origins exact, so both see the same geometry.
TEST(RollingWindow, StorageRotationDoesNotChangeTheCells) {
  LocalMapOptions options = SmallWindow();
  options.resolution = 0.0625;
  RollingWindow a(options, Eigen::Vector2d(0.5, -0.25));
  RollingWindow b(options, Eigen::Vector2d(3.5, -2.75));
  ASSERT_TRUE((b.Recentre({0.5, -0.25}) != 0).all());
  ASSERT_EQ(a.Limits().Origin(), b.Limits().Origin());
  ASSERT_FALSE(a.Layout() == b.Layout());
  a.ClearChanges();
  b.ClearChanges();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> step(-0.3, 0.6);
  Pose2 pose(0.5, -0.25, 0.0);
  for (int k = 0; k < 60; ++k) {
    pose = pose * Pose2(step(rng), 0.5 * step(rng), step(rng));
    const Eigen::Array2i shift = a.Recentre(pose.translation());
    ASSERT_TRUE((b.Recentre(pose.translation()) == shift).all());
    const ScanPoints scan = RandomScan(rng);
    a.InsertScan(pose, scan);
    b.InsertScan(pose, scan);
    ExpectSameLogicalCells(a, b);
    if (k % 3 == 0) {
      a.ClearChanges();
      b.ClearChanges();
    }
  }
  EXPECT_GT(a.NumObstacles(), 50);
}

}  // namespace
}  // namespace gridslam
