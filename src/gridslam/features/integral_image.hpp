// Integral image (summed-area table) of an 8-bit image, the basis of SURF's constant-time box
// filters (Bay et al. 2008, §2.1, Eq. (1); docs/method.md §2.1). The table has (H+1)·(W+1)
// 32-bit entries with a zero first row and column: II(x, y) = Σ_{i<x, j<y} I(i, j), so the sum
// over the half-open box [x0, x1) × [y0, y1) takes four look-ups.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace gridslam::features {

class IntegralImage {
 public:
  IntegralImage() = default;
  /// Builds the table of `image`. Contract: CV_8UC1 with at most 2^31 / 255 pixels.
  explicit IntegralImage(const cv::Mat& image) { Compute(image); }

  /// Rebuilds the table for `image` (same contract), reusing the storage.
  void Compute(const cv::Mat& image);

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  [[nodiscard]] bool empty() const { return width_ == 0 || height_ == 0; }
  /// Distance between consecutive table rows [entries]; stride() = width() + 1.
  [[nodiscard]] int stride() const { return width_ + 1; }
  /// Row y of the table (0 <= y <= height()), entries 0 .. width().
  [[nodiscard]] const std::int32_t* Row(int y) const {
    return table_.data() + static_cast<std::ptrdiff_t>(y) * stride();
  }
  /// II(x, y): the sum over [0, x) × [0, y). Contract: 0 <= x <= width(), 0 <= y <= height().
  [[nodiscard]] std::int32_t At(int x, int y) const { return Row(y)[x]; }

  /// Sum over [x0, x1) × [y0, y1). Contract: 0 <= x0 <= x1 <= width(), 0 <= y0 <= y1 <= height().
  [[nodiscard]] std::int32_t BoxSum(int x0, int y0, int x1, int y1) const {
    const std::int32_t* r0 = Row(y0);
    const std::int32_t* r1 = Row(y1);
    return r1[x1] - r1[x0] - r0[x1] + r0[x0];
  }

  /// Mean over the part of [x0, x1) × [y0, y1) inside the image, and that part's area in
  /// `*area` (0 and mean 0 when they do not intersect). Any box is allowed.
  [[nodiscard]] float ClippedBoxMean(int x0, int y0, int x1, int y1, int* area) const;

 private:
  std::vector<std::int32_t> table_;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace gridslam::features
