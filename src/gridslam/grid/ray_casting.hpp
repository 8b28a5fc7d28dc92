// Cell traversal of laser rays on a grid (docs/design.md §1.3): Bresenham's line between two cells,
// after clipping the metric segment to the grid's rectangle (Liang-Barsky), so a 30 m reading in a
// 15 m window costs only the cells inside the window. Used by the occupancy update to clear the
// cells a beam passed through; the beam's end cell is handled by the caller (marked only for real
// returns, never for max-range readings).
#pragma once

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <utility>

#include <Eigen/Core>

#include "gridslam/grid/map_limits.hpp"
#include "gridslam/grid/ring_layout.hpp"

namespace gridslam {

/// The part of the segment a -> b (metres) inside the rectangle of `limits`, shrunk by a tiny
/// margin so both ends fall in valid cells; nullopt if the segment misses the rectangle.
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> ClipSegment(const MapLimits& limits,
                                                                       const Eigen::Vector2d& a,
                                                                       const Eigen::Vector2d& b);

/// Calls visit(i, j) for every cell of Bresenham's 8-connected line from `from` to `to`, in order,
/// `from` included; `to` included only if `include_end`. No bounds checks: the caller passes cells
/// of the grid (e.g. the ends of a ClipSegment() result).
template <typename Visit>
void TraceLine(const Eigen::Array2i& from, const Eigen::Array2i& to, bool include_end,
               Visit&& visit) {
  int x = from.x();
  int y = from.y();
  const int dx = std::abs(to.x() - x);
  const int dy = -std::abs(to.y() - y);
  const int sx = x < to.x() ? 1 : -1;
  const int sy = y < to.y() ? 1 : -1;
  int err = dx + dy;
  while (x != to.x() || y != to.y()) {
    visit(x, y);
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y += sy;
    }
  }
  if (include_end) {
    visit(x, y);
  }
}

/// TraceLine() on toroidal storage: calls visit(index) with the storage index
/// (layout.Index(i, j)) of every cell TraceLine(from, to, include_end) visits, in the same order.
/// The storage column and row follow the line's steps, so a cell costs no more than on row-major
/// storage (no per-cell wrap arithmetic or multiplication).
template <typename Visit>
void TraceLineInRing(const RingLayout& layout, const Eigen::Array2i& from, const Eigen::Array2i& to,
                     bool include_end, Visit&& visit) {
  const int dx = std::abs(to.x() - from.x());
  const int dy = -std::abs(to.y() - from.y());
  const int sx = from.x() < to.x() ? 1 : -1;
  const int sy = from.y() < to.y() ? 1 : -1;
  // The line runs one way along each axis, so one comparison per step finds where it crosses the
  // storage's seam. Every step advances the major axis once: max(dx, -dy) steps reach `to` (a
  // counter, not the logical coordinates, keeps the loop within the registers).
  const int w = layout.Width();
  const auto area = static_cast<std::ptrdiff_t>(w) * layout.Height();
  const int column_seam = sx > 0 ? w : -1;
  const int column_wrap = sx > 0 ? -w : w;
  const std::ptrdiff_t row_step = sy > 0 ? w : -w;
  const std::ptrdiff_t row_seam = sy > 0 ? area : -static_cast<std::ptrdiff_t>(w);
  const std::ptrdiff_t row_wrap = sy > 0 ? -area : area;
  int column = layout.Column(from.x());
  std::ptrdiff_t row_start = static_cast<std::ptrdiff_t>(layout.Row(from.y())) * w;
  int err = dx + dy;
  for (int n = std::max(dx, -dy); n > 0; --n) {
    visit(static_cast<std::size_t>(row_start + column));
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      column += sx;
      if (column == column_seam) {
        column += column_wrap;
      }
    }
    if (e2 <= dx) {
      err += dx;
      row_start += row_step;
      if (row_start == row_seam) {
        row_start += row_wrap;
      }
    }
  }
  if (include_end) {
    visit(static_cast<std::size_t>(row_start + column));
  }
}

}  // namespace gridslam
