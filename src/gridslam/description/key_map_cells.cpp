#include "gridslam/description/key_map_cells.hpp"

#include <cmath>

#include "gridslam/common/check.hpp"
#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/matching/grid_verification.hpp"

namespace gridslam::description {

KeyMapCells::KeyMapCells(const Grid2D<float>& log_odds, float occupied_log_odds,
                         float observed_log_odds)
    : limits_(log_odds.Limits()), bits_((2 * log_odds.size() + 63) / 64, 0) {
  const float* l = log_odds.data();
  for (std::size_t k = 0; k < log_odds.size(); ++k) {
    const std::uint64_t obstacle = l[k] > occupied_log_odds ? 1U : 0U;
    const std::uint64_t observed = std::abs(l[k]) > observed_log_odds ? 2U : 0U;
    bits_[(2 * k) / 64] |= (obstacle | observed) << ((2 * k) % 64);
  }
}

cv::Mat ObstacleImage(const KeyMapCells& cells) {
  const MapLimits& limits = cells.Limits();
  cv::Mat image(limits.Height(), limits.Width(), CV_8U);
  for (int j = 0; j < limits.Height(); ++j) {
    auto* row = image.ptr<std::uint8_t>(j);
    for (int i = 0; i < limits.Width(); ++i) {
      row[i] = cells.Obstacle(i, j) ? 0 : 255;
    }
  }
  return image;
}

KeyMapGeometry ComputeGeometry(const KeyMapCells& cells, const cv::Mat* distance_cells) {
  const MapLimits& limits = cells.Limits();
  cv::Mat computed;
  if (distance_cells == nullptr) {
    computed = distance_transform::DistanceTransformCells(ObstacleImage(cells));
    distance_cells = &computed;
  }
  GRIDSLAM_CHECK(distance_cells->rows == limits.Height() && distance_cells->cols == limits.Width() &&
                 distance_cells->type() == CV_32F)
      << "distance image of another size";
  const double resolution = limits.Resolution();
  KeyMapGeometry geometry;
  geometry.distance = Grid2D<float>(limits, matching::kUnknownDistance);
  for (int j = 0; j < limits.Height(); ++j) {
    const auto* d = distance_cells->ptr<float>(j);
    for (int i = 0; i < limits.Width(); ++i) {
      if (cells.Obstacle(i, j)) {
        geometry.obstacle_points.push_back(limits.CellCenter({i, j}));
      }
      if (cells.Observed(i, j) && std::isfinite(d[i])) {
        geometry.distance(i, j) = static_cast<float>(d[i] * resolution);
      }
    }
  }
  return geometry;
}

}  // namespace gridslam::description
