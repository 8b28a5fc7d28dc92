#include "gridslam/grid/cell_shift.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "gridslam/grid/grid2d.hpp"

namespace gridslam {
namespace {

// A w x h array whose cell (i, j) holds 100 j + i + 1 (0 never occurs).
std::vector<int> Numbered(int w, int h) {
  std::vector<int> cells;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      cells.push_back(100 * j + i + 1);
    }
  }
  return cells;
}

TEST(CellShift, EveryCellTakesItsSourceOrTheFill) {
  const int w = 7;
  const int h = 5;
  for (int dj = -6; dj <= 6; ++dj) {
    for (int di = -8; di <= 8; ++di) {
      std::vector<int> cells = Numbered(w, h);
      ShiftCellsInPlace(cells, w, h, di, dj, 0);
      for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
          const int si = i + di;
          const int sj = j + dj;
          const bool inside = si >= 0 && si < w && sj >= 0 && sj < h;
          ASSERT_EQ(cells[static_cast<std::size_t>(j * w + i)], inside ? 100 * sj + si + 1 : 0)
              << "shift " << di << " " << dj << " cell " << i << " " << j;
        }
      }
    }
  }
}

TEST(CellShift, AGridMovesItsOriginWithItsCells) {
  Grid2D<float> grid(MapLimits(0.5, Eigen::Vector2d(1.0, -2.0), 4, 3), 0.0F);
  grid(3, 2) = 7.0F;
  grid.Shift(2, 1, -1.0F);
  EXPECT_TRUE(grid.Limits().Origin().isApprox(Eigen::Vector2d(2.0, -1.5)));
  EXPECT_EQ(grid(1, 1), 7.0F);   // the same place in the world
  EXPECT_EQ(grid(3, 2), -1.0F);  // entered
  EXPECT_EQ(grid(0, 0), 0.0F);
}

}  // namespace
}  // namespace gridslam
