// Issue 17: a corrupt pose (1e308, or 1e5 m away) made FuseScans allocate without bound and
// crash. The grid size is now checked before anything is allocated.
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "gridslam/fusion/global_grid.hpp"

namespace gridslam::fusion {
namespace {

LaserScan ShortScan() {
  LaserScan scan;
  scan.angle_min = -0.5;
  scan.angle_increment = 0.1;
  scan.range_min = 0.0;
  scan.range_max = 80.0;
  scan.ranges.assign(11, 2.0F);
  return scan;
}

TEST(GlobalGridBounds, AHugeExtentThrowsBeforeAllocating) {
  const LaserScan scan = ShortScan();
  const FusionOptions options;
  for (const double far : {1e5, 1e12, 1e308}) {
    const std::vector<PosedScan> scans = {{Pose2(0, 0, 0), Pose2(), &scan},
                                          {Pose2(far, far, 0), Pose2(), &scan}};
    EXPECT_THROW((void)FuseScans(scans, options), std::length_error) << far;
  }
  // A normal extent still fuses.
  const std::vector<PosedScan> near = {{Pose2(0, 0, 0), Pose2(), &scan},
                                       {Pose2(30, 20, 0), Pose2(), &scan}};
  EXPECT_GT(FuseScans(near, options).Limits().Width(), 600);
}

// A trajectory that ran away 6 km along a corridor: too many cells at 5 cm, so the map is fused
// at the finest power-of-two multiple that fits, with the walls where the scans put them; an
// extent no resolution fits (or a pose that is not finite) still throws.
TEST(GlobalGridBounds, ARunawayTrajectoryIsFusedCoarserNotLost) {
  const LaserScan scan = ShortScan();
  const FusionOptions options;
  ASSERT_DOUBLE_EQ(options.resolution, 0.05);
  const std::vector<PosedScan> runaway = {{Pose2(0, 0, 0), Pose2(), &scan},
                                          {Pose2(6000.0, 300.0, 0), Pose2(), &scan}};
  EXPECT_THROW((void)FuseScansTiled(runaway, options), std::length_error);
  const TiledGrid<float> grid = FuseScansFitting(runaway, options);
  // 6004 m x 304 m: 1.2e8 cells at 0.1 m fit in 2.5e8, 7.3e8 at 0.05 m do not.
  EXPECT_DOUBLE_EQ(grid.Limits().Resolution(), 0.1);
  for (const Eigen::Vector2d& wall : {Eigen::Vector2d(2.0, 0.0), Eigen::Vector2d(6002.0, 300.0)}) {
    const Eigen::Array2i cell = grid.Limits().CellIndex(wall);
    EXPECT_GT(grid.Get(cell), 0.0F) << wall.transpose();
  }
  // An extent that fits keeps the configured resolution.
  const std::vector<PosedScan> near = {{Pose2(0, 0, 0), Pose2(), &scan},
                                       {Pose2(30, 20, 0), Pose2(), &scan}};
  EXPECT_DOUBLE_EQ(FuseScansFitting(near, options).Limits().Resolution(), 0.05);
  for (const double far : {1e12, 1e308}) {
    const std::vector<PosedScan> scans = {{Pose2(0, 0, 0), Pose2(), &scan},
                                          {Pose2(far, far, 0), Pose2(), &scan}};
    EXPECT_THROW((void)FuseScansFitting(scans, options), std::length_error) << far;
  }
}

TEST(GlobalGridBounds, OptionsThatSizeMemoryAreBounded) {
  FusionOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.resolution = 1e-7;
  EXPECT_FALSE(options.Validate().ok());
  options = FusionOptions();
  options.margin = 1e6;
  EXPECT_FALSE(options.Validate().ok());
  options = FusionOptions();
  options.max_range = 1e9;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace gridslam::fusion
