#include "gridslam/grid/ring_grid.hpp"

#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

void ExpectSameCells(const RingGrid<int>& ring, const Grid2D<int>& reference) {
  ASSERT_EQ(ring.Width(), reference.Width());
  ASSERT_EQ(ring.Height(), reference.Height());
  ASSERT_EQ(ring.Limits().Origin(), reference.Limits().Origin());
  for (int j = 0; j < ring.Height(); ++j) {
    for (int i = 0; i < ring.Width(); ++i) {
      ASSERT_EQ(ring(i, j), reference(i, j)) << "cell " << i << ", " << j;
      ASSERT_EQ(ring.data()[ring.Layout().Index(i, j)], reference(i, j));
      ASSERT_TRUE((ring.Layout().Cell(ring.Layout().Index(i, j)) == Eigen::Array2i(i, j)).all());
    }
  }
  const Grid2D<int> copy = ring.ToGrid2D();
  ASSERT_EQ(copy.Cells(), reference.Cells());
}

// The ring grid equals a physically shifted grid (Grid2D::Shift, memmove) after many random
// writes and shifts, small and large, along one axis or both.
TEST(RingGrid, EqualsAPhysicallyShiftedGridAfterRandomWritesAndShifts) {
  std::mt19937 rng(5);
  for (const auto& [w, h] : {std::pair{7, 5}, std::pair{1, 9}, std::pair{23, 17}}) {
    const MapLimits limits(0.05, Eigen::Vector2d(-1.0, 2.0), w, h);
    RingGrid<int> ring(limits, -1);
    Grid2D<int> reference(limits, -1);
    std::uniform_int_distribution<int> column(0, w - 1);
    std::uniform_int_distribution<int> row(0, h - 1);
    std::uniform_int_distribution<int> shift_x(-w - 2, w + 2);
    std::uniform_int_distribution<int> shift_y(-h - 2, h + 2);
    std::uniform_int_distribution<int> kind(0, 3);
    int value = 0;
    for (int step = 0; step < 400; ++step) {
      for (int k = 0; k < 10; ++k) {
        const int i = column(rng);
        const int j = row(rng);
        ring(i, j) = value;
        reference(i, j) = value;
        ++value;
      }
      // Mostly small shifts along one axis, as a window recentres; sometimes both or far.
      int di = shift_x(rng) / 3;
      int dj = shift_y(rng) / 3;
      switch (kind(rng)) {
        case 0:
          dj = 0;
          break;
        case 1:
          di = 0;
          break;
        case 2:
          di = shift_x(rng);
          dj = shift_y(rng);
          break;
        default:
          break;
      }
      ring.Shift(di, dj, -2 - step);
      reference.Shift(di, dj, -2 - step);
      ExpectSameCells(ring, reference);
    }
  }
}

TEST(RingLayout, ReplacedRunsCoverTheLeavingCellsOnce) {
  std::mt19937 rng(11);
  const int w = 13;
  const int h = 8;
  RingLayout layout(w, h);
  std::uniform_int_distribution<int> shift_x(-w, w);
  std::uniform_int_distribution<int> shift_y(-h, h);
  for (int step = 0; step < 300; ++step) {
    const int di = shift_x(rng);
    const int dj = shift_y(rng);
    std::multiset<std::size_t> replaced;
    layout.ForEachReplacedRun(di, dj, [&](std::size_t index, std::size_t count) {
      for (std::size_t k = 0; k < count; ++k) {
        replaced.insert(index + k);
      }
    });
    std::multiset<std::size_t> leaving;
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        const int ni = i - di;
        const int nj = j - dj;
        if (ni < 0 || nj < 0 || ni >= w || nj >= h) {
          leaving.insert(layout.Index(i, j));
        }
      }
    }
    ASSERT_EQ(replaced, leaving) << "shift " << di << ", " << dj;
    layout.Shift(di, dj);
    ASSERT_GE(layout.OffsetX(), 0);
    ASSERT_LT(layout.OffsetX(), w);
    ASSERT_GE(layout.OffsetY(), 0);
    ASSERT_LT(layout.OffsetY(), h);
  }
}

TEST(RingGrid, CopiesRegionsAcrossTheStorageEdge) {
  const MapLimits limits(0.1, Eigen::Vector2d::Zero(), 6, 4);
  RingGrid<int> ring(limits, 0);
  ring.Shift(4, 3, 0);  // offsets (4, 3): logical rows and columns wrap inside the storage
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 6; ++i) {
      ring(i, j) = 10 * j + i;
    }
  }
  std::vector<int> out(3 * 2);
  ring.CopyRegion(1, 1, 4, 3, out.data());
  EXPECT_EQ(out, (std::vector<int>{11, 12, 13, 21, 22, 23}));
}

}  // namespace
}  // namespace gridslam
