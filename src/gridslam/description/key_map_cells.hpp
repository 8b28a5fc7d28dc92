// The compact form of a described key map (issue 19: memory bounded by the area mapped): what the
// alignment of key maps needs besides the features is the distance field of the key map and the
// centres of its obstacle cells (docs/design.md §1.5), and both follow exactly from two bits per
// cell, "obstacle" (a source of the distance transform) and "observed". A key map keeps these bits
// (2 bits per cell instead of a float field: 23 KB instead of 362 KB for a 15 m key map at 5 cm),
// and its geometry is recomputed when an alignment needs it, bit for bit what
// KeyMapDescriber::Describe computed (the distance transform is exact and deterministic).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::description {

class KeyMapCells {
 public:
  KeyMapCells() = default;
  /// Obstacle: log-odds above `occupied_log_odds`; observed: |log-odds| above `observed_log_odds`.
  KeyMapCells(const Grid2D<float>& log_odds, float occupied_log_odds, float observed_log_odds);

  [[nodiscard]] const MapLimits& Limits() const { return limits_; }
  [[nodiscard]] bool Obstacle(int i, int j) const { return Bit(obstacle_, Index(i, j)); }
  [[nodiscard]] bool Observed(int i, int j) const { return Bit(observed_, Index(i, j)); }
  /// The bits of the cells in row-major order, 64 per word (bit k % 64 of word k / 64).
  [[nodiscard]] const std::vector<std::uint64_t>& ObstacleBits() const { return obstacle_; }
  [[nodiscard]] const std::vector<std::uint64_t>& ObservedBits() const { return observed_; }
  /// Heap bytes held.
  [[nodiscard]] std::size_t Bytes() const {
    return (obstacle_.capacity() + observed_.capacity()) * sizeof(std::uint64_t);
  }

 private:
  [[nodiscard]] std::size_t Index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(limits_.Width()) +
           static_cast<std::size_t>(i);
  }
  [[nodiscard]] static bool Bit(const std::vector<std::uint64_t>& bits, std::size_t k) {
    return ((bits[k / 64] >> (k % 64)) & 1U) != 0;
  }
  MapLimits limits_;
  std::vector<std::uint64_t> obstacle_;
  std::vector<std::uint64_t> observed_;
};

/// What the verification and the refinement of an alignment read of a key map.
struct KeyMapGeometry {
  /// Distance to the nearest obstacle [m]; matching::kUnknownDistance on unobserved cells.
  Grid2D<float> distance;
  /// Centres of the obstacle cells [m], row by row.
  std::vector<Eigen::Vector2d> obstacle_points;

  /// Heap bytes held.
  [[nodiscard]] std::size_t Bytes() const {
    return distance.size() * sizeof(float) + obstacle_points.capacity() * sizeof(Eigen::Vector2d);
  }
};

/// The binary obstacle image of the cells, CV_8U: obstacles 0, the rest 255 (pixel (u, v) = cell
/// (i, j)).
cv::Mat ObstacleImage(const KeyMapCells& cells);

/// The occupancy image of the cells, CV_8U: obstacles 0, observed 255, the rest 128.
cv::Mat GridImage(const KeyMapCells& cells);

/// The squared distance of every cell to the nearest obstacle [cells^2] (+inf without any), as
/// distance_transform::DistanceTransformCells(ObstacleImage(cells)) squared: the same numbers.
void SquaredObstacleDistances(const KeyMapCells& cells,
                              distance_transform::SquaredDistanceField& field);

/// The geometry of `cells`. `distance_cells`, if given, is the distance transform of
/// ObstacleImage(cells) in cells (distance_transform::DistanceTransformCells), else it is
/// computed here (the same numbers).
KeyMapGeometry ComputeGeometry(const KeyMapCells& cells, const cv::Mat* distance_cells = nullptr);

/// The geometry of `cells` from the squared distances SquaredObstacleDistances(cells) gives (the
/// same numbers as ComputeGeometry(cells); only the observed cells' square roots are taken).
KeyMapGeometry ComputeGeometry(const KeyMapCells& cells,
                               const distance_transform::SquaredDistanceField& field);

}  // namespace gridslam::description
