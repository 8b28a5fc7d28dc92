#include "gridslam/matching/feature_set.hpp"

#include <cmath>

namespace gridslam::matching {

std::string FeatureSetError(const FeatureSet& features) {
  const int n = features.size();
  const cv::Mat& d = features.descriptors;
  if (n == 0) {
    return {};
  }
  if (d.rows != n) {
    return "descriptor rows (" + std::to_string(d.rows) + ") != points (" + std::to_string(n) + ")";
  }
  if (d.channels() != 1 || (d.depth() != CV_32F && d.depth() != CV_8U) || d.cols <= 0) {
    return "descriptors must be single-channel CV_32F or CV_8U with at least one column";
  }
  const auto bad_size = [n](const auto& v) {
    return !v.empty() && static_cast<int>(v.size()) != n;
  };
  if (bad_size(features.laplacian_sign) || bad_size(features.scales) || bad_size(features.angles)) {
    return "laplacian_sign, scales and angles must be empty or have one value per point";
  }
  for (const Eigen::Vector2d& p : features.points) {
    if (!p.allFinite()) {
      return "non-finite keypoint position";
    }
  }
  return {};
}

}  // namespace gridslam::matching
