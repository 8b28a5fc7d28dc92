// Cell traversal of laser rays on a grid (docs/design.md §1.3): Bresenham's line between two cells,
// after clipping the metric segment to the grid's rectangle (Liang-Barsky), so a 30 m reading in a
// 15 m window costs only the cells inside the window. Used by the occupancy update to clear the
// cells a beam passed through; the beam's end cell is handled by the caller (marked only for real
// returns, never for max-range readings).
#pragma once

#include <cstdlib>
#include <optional>
#include <utility>

#include <Eigen/Core>

#include "gridslam/grid/map_limits.hpp"

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

}  // namespace gridslam
