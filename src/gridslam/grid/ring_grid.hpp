// A grid of cells on toroidal storage (RingLayout): Grid2D's logical view (MapLimits, cell (i, j)
// along +x, +y) over storage that a Shift() rotates instead of moving, so recentring a rolling
// window costs the cells that enter, not its area. Hot loops address the storage directly through
// Layout().Index(i, j) and data(); everything else reads logical cells with operator() / at().
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/map_limits.hpp"
#include "gridslam/grid/ring_layout.hpp"

namespace gridslam {

template <typename T>
class RingGrid {
 public:
  RingGrid() = default;
  RingGrid(const MapLimits& limits, T fill)
      : limits_(limits),
        layout_(limits.Width(), limits.Height()),
        cells_(static_cast<std::size_t>(limits.NumCells()), fill) {}

  [[nodiscard]] const MapLimits& Limits() const { return limits_; }
  [[nodiscard]] const RingLayout& Layout() const { return layout_; }
  [[nodiscard]] int Width() const { return limits_.Width(); }
  [[nodiscard]] int Height() const { return limits_.Height(); }

  /// Logical cell (i, j), which must lie in the grid.
  T& operator()(int i, int j) { return cells_[layout_.Index(i, j)]; }
  const T& operator()(int i, int j) const { return cells_[layout_.Index(i, j)]; }
  T& at(const Eigen::Array2i& c) { return (*this)(c.x(), c.y()); }
  const T& at(const Eigen::Array2i& c) const { return (*this)(c.x(), c.y()); }

  /// The storage, indexed by Layout().Index(i, j) (not row-major in logical cells).
  [[nodiscard]] T* data() { return cells_.data(); }
  [[nodiscard]] const T* data() const { return cells_.data(); }
  [[nodiscard]] std::size_t size() const { return cells_.size(); }
  /// Every cell, in storage order (for whole-grid scans whose order does not matter).
  [[nodiscard]] const std::vector<T>& Cells() const { return cells_; }

  /// Moves the view by (di, dj) cells: new (i, j) = old (i + di, j + dj), the origin moves by
  /// (di, dj) cells (as Grid2D::Shift), entering cells get `fill`. Writes only the entering cells.
  void Shift(int di, int dj, const T& fill) {
    layout_.ForEachReplacedRun(di, dj, [&](std::size_t index, std::size_t count) {
      std::fill_n(cells_.data() + index, count, fill);
    });
    layout_.Shift(di, dj);
    limits_ = MapLimits(limits_.Resolution(),
                        limits_.Origin() + Eigen::Vector2d(di, dj) * limits_.Resolution(), Width(),
                        Height());
  }

  /// Copies logical cells [i0, i1) x [j0, j1) (inside the grid) to `out`, row-major, i1 - i0 wide.
  void CopyRegion(int i0, int j0, int i1, int j1, T* out) const {
    for (int j = j0; j < j1; ++j) {
      layout_.ForEachRowRun(j, i0, i1, [&](std::size_t index, std::size_t count) {
        out = std::copy_n(cells_.data() + index, count, out);
      });
    }
  }

  /// The logical cells as a row-major Grid2D with the same limits.
  [[nodiscard]] Grid2D<T> ToGrid2D() const {
    std::vector<T> cells(cells_.size());
    CopyRegion(0, 0, Width(), Height(), cells.data());
    return Grid2D<T>(limits_, std::move(cells));
  }

 private:
  MapLimits limits_;
  RingLayout layout_;
  std::vector<T> cells_;
};

}  // namespace gridslam
