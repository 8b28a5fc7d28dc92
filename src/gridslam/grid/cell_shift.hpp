// Moving a row-major array of cells by whole cells, in place: what a rolling window does to its
// layers when it recentres.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <vector>

namespace gridslam {

/// Moves the row-major w x h array `cells` in place by (di, dj) cells: new (i, j) = old (i + di,
/// j + dj); entering cells get `fill`. T must be trivially copyable. No allocation: rows are
/// moved with memmove in the order that never overwrites a source before it is read.
template <typename T>
void ShiftCellsInPlace(std::vector<T>& cells, int w, int h, int di, int dj, const T& fill) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto uw = static_cast<std::size_t>(w);
  // Destination columns [first, first + count) have a source; the rest of the row is filled.
  const auto first = static_cast<std::size_t>(std::clamp(-di, 0, w));
  const auto count = static_cast<std::size_t>(std::max(0, w - std::abs(di)));
  const std::size_t after = uw - std::min(uw, first + count);
  auto move_row = [&](int j) {
    T* row = cells.data() + static_cast<std::size_t>(j) * uw;
    const int src_j = j + dj;
    if (src_j < 0 || src_j >= h || count == 0) {
      std::fill_n(row, uw, fill);
      return;
    }
    const T* src = cells.data() + static_cast<std::size_t>(src_j) * uw +
                   static_cast<std::size_t>(static_cast<int>(first) + di);
    std::memmove(static_cast<void*>(row + first), static_cast<const void*>(src), count * sizeof(T));
    std::fill_n(row, first, fill);
    std::fill_n(row + first + count, after, fill);
  };
  if (dj >= 0) {  // sources lie at or after their destinations: go forwards
    for (int j = 0; j < h; ++j) {
      move_row(j);
    }
  } else {
    for (int j = h - 1; j >= 0; --j) {
      move_row(j);
    }
  }
}

}  // namespace gridslam
