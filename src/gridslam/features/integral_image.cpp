#include "gridslam/features/integral_image.hpp"

#include <algorithm>

#include "gridslam/common/check.hpp"

namespace gridslam::features {

void IntegralImage::Compute(const cv::Mat& image) {
  GRIDSLAM_CHECK(image.type() == CV_8UC1) << "IntegralImage needs CV_8UC1, got " << image.type();
  GRIDSLAM_CHECK(image.total() <= static_cast<std::size_t>(INT32_MAX / 255))
      << "image too large for a 32-bit integral image";
  width_ = image.cols;
  height_ = image.rows;
  // Every entry is written below (the zero first row, then each row's zero first entry and its
  // sums), so the storage is only resized: zeroing all of it first was a second pass.
  table_.resize(static_cast<std::size_t>(width_ + 1) * static_cast<std::size_t>(height_ + 1));
  std::fill(table_.begin(), table_.begin() + stride(), 0);
  for (int y = 0; y < height_; ++y) {
    const auto* src = image.ptr<std::uint8_t>(y);
    const std::int32_t* above = Row(y);
    std::int32_t* out = table_.data() + static_cast<std::ptrdiff_t>(y + 1) * stride();
    out[0] = 0;
    std::int32_t row_sum = 0;
    for (int x = 0; x < width_; ++x) {
      row_sum += src[x];
      out[x + 1] = above[x + 1] + row_sum;
    }
  }
}

float IntegralImage::ClippedBoxMean(int x0, int y0, int x1, int y1, int* area) const {
  x0 = std::clamp(x0, 0, width_);
  x1 = std::clamp(x1, 0, width_);
  y0 = std::clamp(y0, 0, height_);
  y1 = std::clamp(y1, 0, height_);
  *area = std::max(0, x1 - x0) * std::max(0, y1 - y0);
  if (*area == 0) {
    return 0.0F;
  }
  return static_cast<float>(BoxSum(x0, y0, x1, y1)) / static_cast<float>(*area);
}

}  // namespace gridslam::features
