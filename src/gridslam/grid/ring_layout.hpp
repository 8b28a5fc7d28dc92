// Where the cells of a toroidal (ring-buffer) grid lie in its row-major storage. A rolling window
// that recentres moves its view over the storage instead of moving the cells: logical cell (i, j)
// lives at storage column (i + offset_x) mod width and storage row (j + offset_y) mod height, so a
// shift changes the two offsets and only the cells that enter the view need writing (the strips,
// not the whole area; the memmove of every layer on every recentring was a quarter of the mapper's
// time with the 62 m matching window).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdlib>

#include <Eigen/Core>

namespace gridslam {

class RingLayout {
 public:
  RingLayout() = default;
  /// A width x height storage whose logical cells start unrotated (offsets 0).
  RingLayout(int width, int height) : width_(width), height_(height) {}

  [[nodiscard]] int Width() const { return width_; }
  [[nodiscard]] int Height() const { return height_; }
  [[nodiscard]] int OffsetX() const { return offset_x_; }
  [[nodiscard]] int OffsetY() const { return offset_y_; }

  /// Storage column of logical column i, 0 <= i < Width().
  [[nodiscard]] int Column(int i) const {
    const int c = i + offset_x_;
    return c >= width_ ? c - width_ : c;
  }
  /// Storage row of logical row j, 0 <= j < Height().
  [[nodiscard]] int Row(int j) const {
    const int r = j + offset_y_;
    return r >= height_ ? r - height_ : r;
  }
  /// Storage index of logical cell (i, j), which must lie in the grid.
  [[nodiscard]] std::size_t Index(int i, int j) const {
    return static_cast<std::size_t>(Row(j)) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(Column(i));
  }
  [[nodiscard]] std::size_t Index(const Eigen::Array2i& cell) const {
    return Index(cell.x(), cell.y());
  }
  /// Logical cell stored at storage index `index` (< Width() * Height()).
  [[nodiscard]] Eigen::Array2i Cell(std::size_t index) const {
    const auto w = static_cast<std::size_t>(width_);
    const int i = static_cast<int>(index % w) - offset_x_;
    const int j = static_cast<int>(index / w) - offset_y_;
    return {i < 0 ? i + width_ : i, j < 0 ? j + height_ : j};
  }

  /// Calls run(index, count) for the storage runs of logical row j, columns [i0, i1) (0 <= i0 <=
  /// i1 <= Width()) in logical order: one run, or two where the row wraps around the storage.
  template <typename Run>
  void ForEachRowRun(int j, int i0, int i1, Run&& run) const {
    const std::size_t row = static_cast<std::size_t>(Row(j)) * static_cast<std::size_t>(width_);
    const int count = i1 - i0;
    if (count <= 0) {
      return;
    }
    const int c0 = Column(i0);
    const int first = std::min(count, width_ - c0);
    run(row + static_cast<std::size_t>(c0), static_cast<std::size_t>(first));
    if (count > first) {
      run(row, static_cast<std::size_t>(count - first));
    }
  }

  /// Calls run(index, count) for storage runs that together hold, once each, the cells a
  /// Shift(di, dj) drops from the view: the storage the entering cells take over.
  template <typename Run>
  void ForEachReplacedRun(int di, int dj, Run&& run) const {
    if (std::abs(di) >= width_ || std::abs(dj) >= height_) {
      run(std::size_t{0}, static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
      return;
    }
    // Leaving columns over every row, then leaving rows over the columns that stay.
    const int ci0 = di >= 0 ? 0 : width_ + di;
    const int ci1 = di >= 0 ? di : width_;
    const int keep_i0 = di >= 0 ? di : 0;
    const int keep_i1 = di >= 0 ? width_ : width_ + di;
    const int rj0 = dj >= 0 ? 0 : height_ + dj;
    const int rj1 = dj >= 0 ? dj : height_;
    if (ci1 > ci0) {
      for (int j = 0; j < height_; ++j) {
        ForEachRowRun(j, ci0, ci1, run);
      }
    }
    for (int j = rj0; j < rj1; ++j) {
      if (keep_i1 - keep_i0 == width_) {  // a whole storage row: one run, order does not matter
        run(static_cast<std::size_t>(Row(j)) * static_cast<std::size_t>(width_),
            static_cast<std::size_t>(width_));
      } else {
        ForEachRowRun(j, keep_i0, keep_i1, run);
      }
    }
  }

  /// Moves the view by (di, dj) cells: new logical (i, j) is old logical (i + di, j + dj). The
  /// storage is not touched; the cells ForEachReplacedRun(di, dj) named now hold entering cells.
  void Shift(int di, int dj) {
    if (width_ == 0 || height_ == 0) {
      return;
    }
    offset_x_ = Wrap(offset_x_ + di % width_, width_);
    offset_y_ = Wrap(offset_y_ + dj % height_, height_);
  }

  bool operator==(const RingLayout&) const = default;

 private:
  static int Wrap(int v, int n) { return v < 0 ? v + n : (v >= n ? v - n : v); }

  int width_ = 0;
  int height_ = 0;
  int offset_x_ = 0;
  int offset_y_ = 0;
};

}  // namespace gridslam
