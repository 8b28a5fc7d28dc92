#include "gridslam/grid/map_limits.hpp"

#include <gtest/gtest.h>

#include "gridslam/grid/grid2d.hpp"

namespace gridslam {
namespace {

TEST(MapLimits, CellCentresAndIndicesFollowTheCornerConvention) {
  const MapLimits limits(0.05, Eigen::Vector2d(-1.0, 2.0), 40, 20);
  const Eigen::Array2i cell(3, 7);
  const Eigen::Vector2d centre = limits.CellCenter(cell);
  EXPECT_NEAR(centre.x(), -1.0 + 3.5 * 0.05, 1e-12);
  EXPECT_NEAR(centre.y(), 2.0 + 7.5 * 0.05, 1e-12);
  EXPECT_TRUE((limits.CellIndex(centre) == cell).all());
  EXPECT_TRUE((limits.CellIndex(Eigen::Vector2d(-1.0, 2.0)) == Eigen::Array2i(0, 0)).all());
  EXPECT_TRUE((limits.CellIndex(Eigen::Vector2d(-1.001, 2.0)) == Eigen::Array2i(-1, 0)).all());
  EXPECT_TRUE(limits.ToCellCoordinates(centre).isApprox(Eigen::Vector2d(3.0, 7.0)));
  EXPECT_FALSE(limits.Contains(Eigen::Array2i(40, 0)));
  EXPECT_EQ(limits.LinearIndex(cell), 7 * 40 + 3);
}

TEST(Grid2D, StoresRowMajor) {
  Grid2D<int> grid(MapLimits(0.1, Eigen::Vector2d::Zero(), 3, 2), 0);
  grid(2, 1) = 5;
  EXPECT_EQ(grid.data()[5], 5);
  EXPECT_EQ(grid.at(Eigen::Array2i(2, 1)), 5);
}

}  // namespace
}  // namespace gridslam
