#include "gridslam/quality/quality_image.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace gridslam::quality {

Grid2D<float> DisagreementShare(const SelfCheckResult& result, const SelfCheckOptions& options,
                                float min_returns) {
  const MapLimits& limits = result.returns_per_cell.Limits();
  Grid2D<float> share(limits, -1.0F);
  if (limits.NumCells() == 0) {
    return share;
  }
  // Grid2D is row-major with Width() columns: wrap without copying.
  cv::Mat returns(limits.Height(), limits.Width(), CV_32F,
                  const_cast<float*>(result.returns_per_cell.data()));
  cv::Mat disagreeing(limits.Height(), limits.Width(), CV_32F,
                      const_cast<float*>(result.disagreeing_per_cell.data()));
  cv::Mat smooth_returns;
  cv::Mat smooth_disagreeing;
  const double sigma = options.heat_radius / limits.Resolution();
  if (sigma > 0.0) {
    cv::GaussianBlur(returns, smooth_returns, cv::Size(0, 0), sigma);
    cv::GaussianBlur(disagreeing, smooth_disagreeing, cv::Size(0, 0), sigma);
  } else {
    smooth_returns = returns;
    smooth_disagreeing = disagreeing;
  }
  for (int j = 0; j < limits.Height(); ++j) {
    const auto* r = smooth_returns.ptr<float>(j);
    const auto* d = smooth_disagreeing.ptr<float>(j);
    for (int i = 0; i < limits.Width(); ++i) {
      if (r[i] >= min_returns) {
        share(i, j) = std::clamp(d[i] / r[i], 0.0F, 1.0F);
      }
    }
  }
  return share;
}

cv::Mat RenderQualityImage(const OccupancyImage& map, const Grid2D<float>& share) {
  const MapLimits& limits = map.Limits();
  cv::Mat image(limits.Height(), limits.Width(), CV_8UC3);
  for (int j = 0; j < limits.Height(); ++j) {
    for (int i = 0; i < limits.Width(); ++i) {
      const signed char v = map(i, j);
      const double g = v == kOccupiedCell ? 0.0 : (v == kFreeCell ? 255.0 : 205.0);
      const float s = share.Limits().Contains({i, j}) ? share(i, j) : -1.0F;
      const double a = s > 0.0F ? std::min(1.0, 2.0 * s) : 0.0;
      // Blend towards pure red (BGR 0, 0, 255); walls stay dark enough to read.
      const auto blue = static_cast<std::uint8_t>((1.0 - a) * g);
      const auto red = static_cast<std::uint8_t>((1.0 - a) * g + a * 255.0);
      image.at<cv::Vec3b>(limits.Height() - 1 - j, i) = cv::Vec3b(blue, blue, red);
    }
  }
  return image;
}

}  // namespace gridslam::quality
