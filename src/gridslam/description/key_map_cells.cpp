#include "gridslam/description/key_map_cells.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "gridslam/common/check.hpp"
#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/matching/grid_verification.hpp"

namespace gridslam::description {

KeyMapCells::KeyMapCells(const Grid2D<float>& log_odds, float occupied_log_odds,
                         float observed_log_odds)
    : limits_(log_odds.Limits()),
      obstacle_((log_odds.size() + 63) / 64, 0),
      observed_((log_odds.size() + 63) / 64, 0) {
  const float* l = log_odds.data();
  const std::size_t n = log_odds.size();
  for (std::size_t w = 0; w * 64 < n; ++w) {
    const std::size_t end = std::min<std::size_t>(64, n - w * 64);
    const float* cells = l + w * 64;
    std::uint64_t obstacle = 0;
    std::uint64_t observed = 0;
    for (std::size_t b = 0; b < end; ++b) {
      obstacle |= static_cast<std::uint64_t>(cells[b] > occupied_log_odds) << b;
      observed |= static_cast<std::uint64_t>(std::abs(cells[b]) > observed_log_odds) << b;
    }
    obstacle_[w] = obstacle;
    observed_[w] = observed;
  }
}

namespace {

/// Calls f(k) for every set bit k of `bits`, in increasing order.
template <class F>
void ForEachBit(const std::vector<std::uint64_t>& bits, F&& f) {
  for (std::size_t w = 0; w < bits.size(); ++w) {
    for (std::uint64_t word = bits[w]; word != 0; word &= word - 1) {
      f(w * 64 + static_cast<std::size_t>(std::countr_zero(word)));
    }
  }
}

}  // namespace

cv::Mat ObstacleImage(const KeyMapCells& cells) {
  const MapLimits& limits = cells.Limits();
  cv::Mat image(limits.Height(), limits.Width(), CV_8U, cv::Scalar(255));
  auto* pixels = image.ptr<std::uint8_t>();
  ForEachBit(cells.ObstacleBits(), [&](std::size_t k) { pixels[k] = 0; });
  return image;
}

cv::Mat GridImage(const KeyMapCells& cells) {
  const MapLimits& limits = cells.Limits();
  cv::Mat image(limits.Height(), limits.Width(), CV_8U, cv::Scalar(128));
  auto* pixels = image.ptr<std::uint8_t>();
  ForEachBit(cells.ObservedBits(), [&](std::size_t k) { pixels[k] = 255; });
  ForEachBit(cells.ObstacleBits(), [&](std::size_t k) { pixels[k] = 0; });
  return image;
}

void SquaredObstacleDistances(const KeyMapCells& cells,
                              distance_transform::SquaredDistanceField& field) {
  const MapLimits& limits = cells.Limits();
  thread_local std::vector<std::uint8_t> sources;
  sources.assign(static_cast<std::size_t>(limits.NumCells()), 0);
  ForEachBit(cells.ObstacleBits(), [&](std::size_t k) { sources[k] = 1; });
  distance_transform::SquaredEuclideanDistanceTransform(sources.data(), limits.Width(),
                                                        limits.Height(), field);
}

KeyMapGeometry ComputeGeometry(const KeyMapCells& cells, const cv::Mat* distance_cells) {
  const MapLimits& limits = cells.Limits();
  const auto n = static_cast<std::size_t>(limits.NumCells());
  const double resolution = limits.Resolution();
  KeyMapGeometry geometry;
  geometry.distance = Grid2D<float>(limits, matching::kUnknownDistance);
  float* distance = geometry.distance.data();
  // The distance in cells, as DistanceTransformCells gives it: sqrt of the squared distance.
  thread_local std::vector<float> cells_distance;
  const float* d = nullptr;
  if (distance_cells != nullptr) {
    GRIDSLAM_CHECK(distance_cells->rows == limits.Height() &&
                   distance_cells->cols == limits.Width() && distance_cells->type() == CV_32F &&
                   distance_cells->isContinuous())
        << "distance image of another size";
    d = distance_cells->ptr<float>();
  } else {
    thread_local distance_transform::SquaredDistanceField field;
    SquaredObstacleDistances(cells, field);
    cells_distance.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      cells_distance[k] = std::sqrt(field.squared[k]);
    }
    d = cells_distance.data();
  }
  // Observed cells with an obstacle somewhere get their distance in metres.
  ForEachBit(cells.ObservedBits(), [&](std::size_t k) {
    if (std::isfinite(d[k])) {
      distance[k] = static_cast<float>(d[k] * resolution);
    }
  });
  std::size_t obstacles = 0;
  for (const std::uint64_t word : cells.ObstacleBits()) {
    obstacles += static_cast<std::size_t>(std::popcount(word));
  }
  geometry.obstacle_points.reserve(obstacles);
  const auto width = static_cast<std::size_t>(limits.Width());
  ForEachBit(cells.ObstacleBits(), [&](std::size_t k) {
    geometry.obstacle_points.push_back(
        limits.CellCenter({static_cast<int>(k % width), static_cast<int>(k / width)}));
  });
  return geometry;
}

}  // namespace gridslam::description
