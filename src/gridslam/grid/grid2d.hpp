// A dense 2D array of cells with its MapLimits: the storage under occupancy grids, distance
// fields and feature images. Row-major, row j = y index (row 0 at the lowest y), column i = x.
#pragma once

#include <utility>
#include <vector>

#include "gridslam/grid/cell_shift.hpp"
#include "gridslam/grid/map_limits.hpp"

namespace gridslam {

template <typename T>
class Grid2D {
 public:
  Grid2D() = default;
  Grid2D(const MapLimits& limits, T fill)
      : limits_(limits), cells_(static_cast<std::size_t>(limits.NumCells()), fill) {}
  /// Takes `cells` (row-major, limits.NumCells() of them) as they are.
  Grid2D(const MapLimits& limits, std::vector<T> cells)
      : limits_(limits), cells_(std::move(cells)) {}

  [[nodiscard]] const MapLimits& Limits() const { return limits_; }
  [[nodiscard]] int Width() const { return limits_.Width(); }
  [[nodiscard]] int Height() const { return limits_.Height(); }

  T& operator()(int i, int j) { return cells_[Index(i, j)]; }
  const T& operator()(int i, int j) const { return cells_[Index(i, j)]; }
  T& at(const Eigen::Array2i& c) { return (*this)(c.x(), c.y()); }
  const T& at(const Eigen::Array2i& c) const { return (*this)(c.x(), c.y()); }

  [[nodiscard]] T* data() { return cells_.data(); }
  [[nodiscard]] const T* data() const { return cells_.data(); }
  [[nodiscard]] std::size_t size() const { return cells_.size(); }
  [[nodiscard]] std::vector<T>& Cells() { return cells_; }
  [[nodiscard]] const std::vector<T>& Cells() const { return cells_; }

  /// Moves the grid by (di, dj) cells in place: new (i, j) = old (i + di, j + dj), the origin
  /// moves by (di, dj) cells, entering cells get `fill` (T trivially copyable).
  void Shift(int di, int dj, const T& fill) {
    ShiftCellsInPlace(cells_, Width(), Height(), di, dj, fill);
    limits_ = MapLimits(limits_.Resolution(),
                        limits_.Origin() + Eigen::Vector2d(di, dj) * limits_.Resolution(), Width(),
                        Height());
  }

 private:
  [[nodiscard]] std::size_t Index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(limits_.Width()) +
           static_cast<std::size_t>(i);
  }
  MapLimits limits_;
  std::vector<T> cells_;
};

/// Occupancy values as nav_msgs/OccupancyGrid: -1 unknown, 0 free ... 100 occupied.
using OccupancyImage = Grid2D<signed char>;
constexpr signed char kUnknownCell = -1;
constexpr signed char kFreeCell = 0;
constexpr signed char kOccupiedCell = 100;

}  // namespace gridslam
