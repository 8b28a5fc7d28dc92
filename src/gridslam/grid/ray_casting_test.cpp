#include "gridslam/grid/ray_casting.hpp"

#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

std::vector<Eigen::Array2i> Trace(Eigen::Array2i a, Eigen::Array2i b, bool include_end) {
  std::vector<Eigen::Array2i> cells;
  TraceLine(a, b, include_end, [&](int i, int j) { cells.emplace_back(i, j); });
  return cells;
}

TEST(TraceLine, VisitsAConnectedLineFromStartToEnd) {
  for (const auto& end : {Eigen::Array2i(7, 3), Eigen::Array2i(-4, 9), Eigen::Array2i(-6, -6),
                          Eigen::Array2i(0, -5), Eigen::Array2i(0, 0)}) {
    const auto cells = Trace(Eigen::Array2i(0, 0), end, true);
    ASSERT_FALSE(cells.empty());
    EXPECT_TRUE((cells.front() == Eigen::Array2i(0, 0)).all());
    EXPECT_TRUE((cells.back() == end).all());
    EXPECT_EQ(cells.size(),
              static_cast<std::size_t>(std::max(std::abs(end.x()), std::abs(end.y())) + 1));
    for (std::size_t k = 1; k < cells.size(); ++k) {
      EXPECT_LE((cells[k] - cells[k - 1]).abs().maxCoeff(), 1);  // 8-connected, no gaps
    }
    const auto without_end = Trace(Eigen::Array2i(0, 0), end, false);
    EXPECT_EQ(without_end.size(), cells.size() - 1);
  }
}

TEST(ClipSegment, KeepsInsidePartsAndRejectsMisses) {
  const MapLimits limits(0.1, Eigen::Vector2d(0.0, 0.0), 10, 10);  // [0, 1] x [0, 1]
  const auto inside = ClipSegment(limits, {0.2, 0.2}, {0.8, 0.5});
  ASSERT_TRUE(inside);
  EXPECT_TRUE(inside->first.isApprox(Eigen::Vector2d(0.2, 0.2)));
  EXPECT_TRUE(inside->second.isApprox(Eigen::Vector2d(0.8, 0.5)));
  const auto out = ClipSegment(limits, {0.5, 0.5}, {3.5, 0.5});
  ASSERT_TRUE(out);
  EXPECT_NEAR(out->second.x(), 1.0, 1e-6);
  EXPECT_TRUE((limits.CellIndex(out->second) == Eigen::Array2i(9, 5)).all());
  const auto through = ClipSegment(limits, {-1.0, -1.0}, {2.0, 2.0});
  ASSERT_TRUE(through);
  EXPECT_TRUE(limits.Contains(limits.CellIndex(through->first)));
  EXPECT_TRUE(limits.Contains(limits.CellIndex(through->second)));
  EXPECT_FALSE(ClipSegment(limits, {-1.0, 2.0}, {2.0, 3.0}));
  EXPECT_FALSE(ClipSegment(limits, {1.5, 0.5}, {1.5, 0.9}));
}

TEST(TraceLineInRing, VisitsTheStorageOfTraceLinesCells) {
  std::mt19937 rng(7);
  const int w = 19;
  const int h = 11;
  std::uniform_int_distribution<int> column(0, w - 1);
  std::uniform_int_distribution<int> row(0, h - 1);
  for (int trial = 0; trial < 500; ++trial) {
    RingLayout layout(w, h);
    layout.Shift(column(rng), row(rng));
    const Eigen::Array2i from(column(rng), row(rng));
    const Eigen::Array2i to(column(rng), row(rng));
    const bool include_end = trial % 2 == 0;
    std::vector<std::size_t> expected;
    TraceLine(from, to, include_end, [&](int i, int j) { expected.push_back(layout.Index(i, j)); });
    std::vector<std::size_t> visited;
    TraceLineInRing(layout, from, to, include_end,
                    [&](std::size_t index) { visited.push_back(index); });
    ASSERT_EQ(visited, expected) << "from " << from.transpose() << " to " << to.transpose();
  }
}

}  // namespace
}  // namespace gridslam
