#include "gridslam/grid/local_map_options.hpp"

#include <cmath>

namespace gridslam {

int LocalMapOptions::NumCells() const {
  const auto n = static_cast<int>(std::lround(size / resolution));
  return n % 2 == 0 ? n + 1 : n;
}

double LocalMapOptions::MatchingSize() const {
  return matching_size > 0.0 ? matching_size : 2.0 * (max_range + shift_distance);
}

LocalMapOptions LocalMapOptions::MatchingWindow() const {
  LocalMapOptions options = *this;
  options.size = MatchingSize();
  options.matching_size = options.size;
  return options;
}

Status LocalMapOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(resolution > 0.0, "local_map.resolution > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(size >= 10 * resolution, "local_map.size >= 10 cells"));
  GRIDSLAM_RETURN_IF_ERROR(Require(size / resolution <= 8000, "local_map.size <= 8000 cells"));
  GRIDSLAM_RETURN_IF_ERROR(Require(matching_size >= 0.0 && MatchingSize() / resolution <= 8000,
                                   "local_map.matching_size >= 0 (0 = automatic), <= 8000 cells"));
  GRIDSLAM_RETURN_IF_ERROR(Require(shift_distance > 0.0 && shift_distance < 0.5 * size,
                                   "0 < local_map.shift_distance < size / 2"));
  for (const double p : {hit_probability, miss_probability, min_probability, max_probability,
                         occupied_probability}) {
    GRIDSLAM_RETURN_IF_ERROR(Require(p > 0.0 && p < 1.0, "local_map probabilities in (0, 1)"));
  }
  GRIDSLAM_RETURN_IF_ERROR(Require(hit_probability > 0.5, "local_map.hit_probability > 0.5"));
  GRIDSLAM_RETURN_IF_ERROR(Require(miss_probability < 0.5, "local_map.miss_probability < 0.5"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(min_probability < 0.5 && max_probability > occupied_probability &&
                  occupied_probability >= 0.5,
              "local_map: min_probability < 0.5 <= occupied_probability < max_probability"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_range > 0.0, "local_map.max_range > 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(no_return_clearing_range >= 0.0, "local_map.no_return_clearing_range >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(surface_memory >= 1, "local_map.surface_memory >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(std::isfinite(normal_angle_sigma) && normal_angle_sigma >= 0.0,
                                   "local_map.normal_angle_sigma >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(std::isfinite(normal_noise_ratio) && normal_noise_ratio >= 0.0,
                                   "local_map.normal_noise_ratio >= 0"));
  return Status::Ok();
}

double LocalMapOptions::WallNormalNoise() const {
  return normal_noise_ratio * resolution / std::sqrt(12.0);
}

}  // namespace gridslam
