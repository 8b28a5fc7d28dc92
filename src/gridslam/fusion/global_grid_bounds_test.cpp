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
