// Geometry of a 2D grid: resolution, origin and size (Cartographer's MapLimits, ROS map_server).
// Cell (i, j) (column i along +x, row j along +y) covers
// [origin + i*res, origin + (i+1)*res) x [origin_y + j*res, ...) and has its centre at
// origin + (i + 0.5, j + 0.5) * res. `origin` is the metric position of the corner of cell (0, 0),
// as map_server's YAML `origin` and nav_msgs/MapMetaData (docs/frames.md).
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "gridslam/common/check.hpp"

namespace gridslam {

class MapLimits {
 public:
  MapLimits() = default;
  MapLimits(double resolution, const Eigen::Vector2d& origin, int width, int height)
      : resolution_(resolution), origin_(origin), width_(width), height_(height) {
    GRIDSLAM_CHECK(resolution > 0.0) << "resolution " << resolution;
    GRIDSLAM_CHECK(width >= 0 && height >= 0) << "size " << width << "x" << height;
  }

  [[nodiscard]] double Resolution() const { return resolution_; }
  [[nodiscard]] const Eigen::Vector2d& Origin() const { return origin_; }
  [[nodiscard]] int Width() const { return width_; }
  [[nodiscard]] int Height() const { return height_; }
  [[nodiscard]] long NumCells() const { return static_cast<long>(width_) * height_; }

  /// Index of the cell containing `p` (which may lie outside the map).
  [[nodiscard]] Eigen::Array2i CellIndex(const Eigen::Vector2d& p) const {
    return {static_cast<int>(std::floor((p.x() - origin_.x()) / resolution_)),
            static_cast<int>(std::floor((p.y() - origin_.y()) / resolution_))};
  }
  /// Metric centre of cell (i, j).
  [[nodiscard]] Eigen::Vector2d CellCenter(const Eigen::Array2i& cell) const {
    return origin_ + (cell.cast<double>() + 0.5).matrix() * resolution_;
  }
  /// Continuous cell coordinates of `p`: the centre of cell (i, j) maps to (i, j).
  [[nodiscard]] Eigen::Vector2d ToCellCoordinates(const Eigen::Vector2d& p) const {
    return (p - origin_) / resolution_ - Eigen::Vector2d(0.5, 0.5);
  }
  [[nodiscard]] bool Contains(const Eigen::Array2i& cell) const {
    return cell.x() >= 0 && cell.y() >= 0 && cell.x() < width_ && cell.y() < height_;
  }
  /// Row-major linear index (row j, column i), valid only if Contains(cell).
  [[nodiscard]] long LinearIndex(const Eigen::Array2i& cell) const {
    return static_cast<long>(cell.y()) * width_ + cell.x();
  }

 private:
  double resolution_ = 0.05;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int width_ = 0;
  int height_ = 0;
};

}  // namespace gridslam
