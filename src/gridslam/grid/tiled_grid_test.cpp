#include "gridslam/grid/tiled_grid.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

TEST(TiledGrid, CopyRowReadsWhatGetReadsAcrossTilesAndUnwrittenTiles) {
  constexpr int kSize = TiledGrid<float>::kTileSize;
  // Three tiles wide (the last one partial), two high; the middle column of tiles never written.
  TiledGrid<float> grid(MapLimits(0.05, Eigen::Vector2d::Zero(), 2 * kSize + 10, kSize + 3), -1.0F);
  for (int j = 0; j < grid.Height(); ++j) {
    for (int i = 0; i < grid.Width(); ++i) {
      if (i < kSize || i >= 2 * kSize) {
        grid.Mutable(i, j) = static_cast<float>(1000 * j + i);
      }
    }
  }
  for (const int j : {0, kSize - 1, kSize, grid.Height() - 1}) {
    for (const auto& [begin, end] : std::vector<std::pair<int, int>>{{0, grid.Width()},
                                                                     {3, 5},
                                                                     {kSize - 2, 2 * kSize + 4},
                                                                     {2 * kSize + 1, grid.Width()},
                                                                     {7, 7}}) {
      std::vector<float> row(static_cast<std::size_t>(end - begin), 42.0F);
      grid.CopyRow(j, begin, end, row.data());
      for (int i = begin; i < end; ++i) {
        ASSERT_EQ(row[static_cast<std::size_t>(i - begin)], grid.Get(i, j))
            << "row " << j << ", cell " << i;
      }
    }
  }
  EXPECT_EQ(grid.Get(kSize + 1, 0), -1.0F);  // the unwritten tile reads as the fill
}

}  // namespace
}  // namespace gridslam
