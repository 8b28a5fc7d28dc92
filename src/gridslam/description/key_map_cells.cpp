#include "gridslam/description/key_map_cells.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "gridslam/common/check.hpp"
#include "gridslam/common/thread_scratch.hpp"
#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/matching/grid_verification.hpp"

namespace gridslam::description {

namespace {

/// The bits of 64 flags (each 0 or 1): bit b = flags[b]. Eight flags at a time: one multiply
/// gathers the low bit of every byte of a little-endian word into its top byte (the partial
/// products land on distinct bits, so nothing carries into it).
std::uint64_t PackFlags(const std::uint8_t* flags) {
  static_assert(std::endian::native == std::endian::little);
  std::uint64_t bits = 0;
  for (int g = 0; g < 8; ++g) {
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, flags + 8 * g, 8);
    bits |= ((bytes * 0x0102040810204080ULL) >> 56) << (8 * g);
  }
  return bits;
}

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

KeyMapCells::KeyMapCells(const Grid2D<float>& log_odds, float occupied_log_odds,
                         float observed_log_odds)
    : limits_(log_odds.Limits()),
      obstacle_((log_odds.size() + 63) / 64, 0),
      observed_((log_odds.size() + 63) / 64, 0) {
  const float* l = log_odds.data();
  const std::size_t n = log_odds.size();
  // The flags of 64 cells as bytes first (a loop the compiler vectorises), then packed.
  std::array<std::uint8_t, 64> obstacle{};
  std::array<std::uint8_t, 64> observed{};
  for (std::size_t w = 0; w * 64 < n; ++w) {
    const std::size_t end = std::min<std::size_t>(64, n - w * 64);
    const float* cells = l + w * 64;
    if (end < 64) {
      obstacle.fill(0);
      observed.fill(0);
    }
    for (std::size_t b = 0; b < end; ++b) {
      obstacle[b] = cells[b] > occupied_log_odds ? 1 : 0;
      observed[b] = std::abs(cells[b]) > observed_log_odds ? 1 : 0;
    }
    obstacle_[w] = PackFlags(obstacle.data());
    observed_[w] = PackFlags(observed.data());
  }
}

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
  struct SourcesTag {};
  auto& sources = ThreadScratch<SourcesTag, std::vector<std::uint8_t>>();
  sources.assign(static_cast<std::size_t>(limits.NumCells()), 0);
  ForEachBit(cells.ObstacleBits(), [&](std::size_t k) { sources[k] = 1; });
  distance_transform::SquaredEuclideanDistanceTransform(sources.data(), limits.Width(),
                                                        limits.Height(), field);
}

namespace {

/// The geometry of `cells`; `distance(k)` is the distance of cell k in cells, as
/// DistanceTransformCells gives it. It is read only on observed cells.
template <class Distance>
KeyMapGeometry Geometry(const KeyMapCells& cells, Distance&& distance_of) {
  const MapLimits& limits = cells.Limits();
  const double resolution = limits.Resolution();
  KeyMapGeometry geometry;
  geometry.distance = Grid2D<float>(limits, matching::kUnknownDistance);
  float* distance = geometry.distance.data();
  // Observed cells with an obstacle somewhere get their distance in metres.
  ForEachBit(cells.ObservedBits(), [&](std::size_t k) {
    const float d = distance_of(k);
    if (std::isfinite(d)) {
      distance[k] = static_cast<float>(d * resolution);
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

}  // namespace

KeyMapGeometry ComputeGeometry(const KeyMapCells& cells, const cv::Mat* distance_cells) {
  if (distance_cells == nullptr) {
    struct FieldTag {};
    auto& field = ThreadScratch<FieldTag, distance_transform::SquaredDistanceField>();
    SquaredObstacleDistances(cells, field);
    return ComputeGeometry(cells, field);
  }
  const MapLimits& limits = cells.Limits();
  GRIDSLAM_CHECK(distance_cells->rows == limits.Height() &&
                 distance_cells->cols == limits.Width() && distance_cells->type() == CV_32F &&
                 distance_cells->isContinuous())
      << "distance image of another size";
  const float* d = distance_cells->ptr<float>();
  return Geometry(cells, [d](std::size_t k) { return d[k]; });
}

KeyMapGeometry ComputeGeometry(const KeyMapCells& cells,
                               const distance_transform::SquaredDistanceField& field) {
  const MapLimits& limits = cells.Limits();
  GRIDSLAM_CHECK(field.width == limits.Width() && field.height == limits.Height() &&
                 field.squared.size() == static_cast<std::size_t>(limits.NumCells()))
      << "squared distances of another size";
  // The distance in cells, as DistanceTransformCells gives it: sqrt of the squared distance, taken
  // only where it is read (observed cells).
  const float* squared = field.squared.data();
  return Geometry(cells, [squared](std::size_t k) { return std::sqrt(squared[k]); });
}

}  // namespace gridslam::description
