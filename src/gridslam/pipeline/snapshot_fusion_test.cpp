// Incremental snapshot fusion: a key map placed, moved and taken out gives the same grid as
// placing it fresh at its new pose; a key map that did not move is not placed again.
#include "gridslam/pipeline/snapshot_fusion.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::pipeline {
namespace {

/// A laser in front of a wall 3 m away.
LaserScan WallScan() {
  LaserScan scan;
  scan.angle_min = -0.5;
  scan.angle_increment = 0.01;
  scan.range_min = 0.1;
  scan.range_max = 30.0;
  for (int k = 0; k <= 100; ++k) {
    scan.ranges.push_back(
        static_cast<float>(3.0 / std::cos(scan.Angle(static_cast<std::size_t>(k)))));
  }
  return scan;
}

/// Sum of log-odds at `p` (world) in `grid`, 0 outside.
float ValueAt(const Grid2D<float>& grid, const Eigen::Vector2d& p) {
  const Eigen::Array2i c = grid.Limits().CellIndex(p);
  return grid.Limits().Contains(c) ? grid.at(c) : 0.0F;
}

TEST(SnapshotFusion, PlacesMovesAndRemovesKeyMaps) {
  const LaserScan scan = WallScan();
  SnapshotFusion fusion{fusion::FusionOptions{}};
  fusion.AddKeyMap(0, {{Pose2(), Pose2(), &scan}});
  ASSERT_TRUE(fusion.Has(0));
  SnapshotFusion::UpdateStats stats;
  const Grid2D<float>& first = fusion.Update(0, {{0, Pose2()}}, stats);
  EXPECT_EQ(stats.added, 1);
  EXPECT_GT(ValueAt(first, {3.02, 0.0}), 0.0F);  // the wall is occupied
  EXPECT_LT(ValueAt(first, {1.5, 0.0}), 0.0F);   // in front of it free

  // Not moved (less than a cell): nothing is placed again.
  stats = {};
  fusion.Update(0, {{0, Pose2(0.01, 0.0, 0.0)}}, stats);
  EXPECT_EQ(stats.added + stats.replaced, 0);

  // Moved 1 m along y: the wall follows, the old place is empty again.
  stats = {};
  const Pose2 moved(0.0, 1.0, 0.0);
  const Grid2D<float> after = fusion.Update(0, {{0, moved}}, stats);
  EXPECT_EQ(stats.replaced, 1);
  SnapshotFusion fresh{fusion::FusionOptions{}};
  fresh.AddKeyMap(0, {{Pose2(), Pose2(), &scan}});
  SnapshotFusion::UpdateStats unused;
  const Grid2D<float>& expected = fresh.Update(0, {{0, moved}}, unused);
  for (double x = -1.0; x < 5.0; x += 0.05) {
    for (double y = -3.0; y < 4.0; y += 0.05) {
      ASSERT_NEAR(ValueAt(after, {x, y}), ValueAt(expected, {x, y}), 1e-4) << x << " " << y;
    }
  }
  EXPECT_NEAR(ValueAt(after, {3.02, -1.6}), 0.0F, 1e-6);

  // Gone from the component: taken out.
  stats = {};
  const Grid2D<float> empty = fusion.Update(0, {}, stats);
  for (const float v : empty.Cells()) {
    ASSERT_NEAR(v, 0.0F, 1e-4);
  }
}

}  // namespace
}  // namespace gridslam::pipeline
