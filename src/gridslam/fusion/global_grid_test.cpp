#include "gridslam/fusion/global_grid.hpp"

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace gridslam::fusion {
namespace {

// A scan of a wall 2 m ahead of the laser, 181 beams over +-30 degrees.
LaserScan WallScan() {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 6;
  scan.angle_increment = (std::numbers::pi / 3) / 180.0;
  scan.range_min = 0.0;
  scan.range_max = 80.0;
  for (int k = 0; k <= 180; ++k) {
    scan.ranges.push_back(
        static_cast<float>(2.0 / std::cos(scan.Angle(static_cast<std::size_t>(k)))));
  }
  return scan;
}

TEST(GlobalGrid, ScansAtTheirPosesMarkTheWallAndClearTheWay) {
  const LaserScan scan = WallScan();
  // The same wall seen from two poses: from (0,0) looking +x, and from (3, 2) turned by 90 deg,
  // 2 m in front of it, so both see a wall at x = 2 and y = 4 respectively.
  const std::vector<PosedScan> scans = {{Pose2(0, 0, 0), Pose2(), &scan},
                                        {Pose2(3, 2, std::numbers::pi / 2), Pose2(), &scan}};
  const FusionOptions options;
  const Grid2D<float> grid = FuseScans(scans, options);
  const OccupancyImage image = ToOccupancy(grid, options);
  const MapLimits& l = image.Limits();
  EXPECT_EQ(image.at(l.CellIndex({2.01, 0.0})), kOccupiedCell);
  EXPECT_EQ(image.at(l.CellIndex({3.0, 4.01})), kOccupiedCell);
  EXPECT_EQ(image.at(l.CellIndex({1.0, 0.0})), kFreeCell);
  EXPECT_EQ(image.at(l.CellIndex({3.0, 3.0})), kFreeCell);
  EXPECT_EQ(image.at(l.CellIndex({-0.5, 1.5})), kUnknownCell);
}

TEST(GlobalGrid, NearestKeyMapAtIdentityReproducesTheKeyMap) {
  keymap::KeyMap key_map;
  key_map.log_odds = Grid2D<float>(MapLimits(0.05, Eigen::Vector2d(-1.0, -1.0), 40, 40), 0.0F);
  key_map.log_odds(10, 12) = 2.0F;
  key_map.log_odds(30, 5) = -1.0F;
  FusionOptions options;
  options.method = "nearest";
  const Grid2D<float> grid = FuseNearestKeyMap({{Pose2(), &key_map}}, options);
  EXPECT_FLOAT_EQ(grid.at(grid.Limits().CellIndex(key_map.log_odds.Limits().CellCenter({10, 12}))),
                  2.0F);
  EXPECT_FLOAT_EQ(grid.at(grid.Limits().CellIndex(key_map.log_odds.Limits().CellCenter({30, 5}))),
                  -1.0F);
}

// The tiled fusion holds the same cells as the dense one, bit for bit, whether its bands of rows
// are inserted by one thread or several (random scans crossing many bands, saturating cells).
TEST(GlobalGrid, TiledFusionEqualsDenseFusionWithAnyNumberOfThreads) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> position(-15.0, 15.0);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<float> range(0.3F, 25.0F);
  std::vector<LaserScan> laser(60);
  std::vector<PosedScan> scans;
  for (LaserScan& scan : laser) {
    scan.angle_min = -std::numbers::pi / 2;
    scan.angle_increment = std::numbers::pi / 180.0;
    scan.range_min = 0.1;
    scan.range_max = 30.0;
    for (int k = 0; k <= 180; ++k) {
      scan.ranges.push_back(k % 17 == 0 ? 40.0F : range(rng));
    }
    scans.push_back({Pose2(position(rng), position(rng), angle(rng)), Pose2(0.1, 0.0, 0.0), &scan});
  }
  FusionOptions options;
  options.min_motion = 0.0;
  options.min_rotation = 0.0;
  const Grid2D<float> dense = FuseScans(scans, options);
  for (const long dense_cells : {kDenseFusionCells, 0L}) {  // dense first, or tiles only
    for (const int threads : {1, 2, 3, 7}) {
      const Grid2D<float> tiled = FuseScansTiled(scans, options, threads, dense_cells).ToDense();
      ASSERT_EQ(tiled.Width(), dense.Width());
      ASSERT_EQ(tiled.Height(), dense.Height());
      ASSERT_EQ(tiled.Limits().Origin(), dense.Limits().Origin());
      EXPECT_EQ(std::memcmp(tiled.data(), dense.data(), dense.size() * sizeof(float)), 0)
          << threads << " threads, dense up to " << dense_cells << " cells";
    }
  }
}

}  // namespace
}  // namespace gridslam::fusion
