// The scan matcher's view of the rolling local map: the exact Euclidean distance transform of its
// obstacle cells (Felzenszwalb-Huttenlocher, distance_transform/), truncated at the maximum
// correspondence distance, with the nearest obstacle cell of every cell. Nearest-obstacle labels
// give the matcher O(1) correspondences (the map-side point and normal of each scan point, as
// PL-ICP's closest segment, docs/method.md §6); the distances give a smooth (bilinear)
// distance field and the correlative search's score. The field follows the window's changes
// incrementally and exactly (a cell's truncated distance can only change within the truncation
// radius r of a cell whose obstacle status changed): a new obstacle is stamped into the disk of
// radius r around it (brushfire), a removed one has the box of radius r around it recomputed with
// the exact transform from the sources within 2r, and after a shift the strips whose neighbours
// left are recomputed. The field lies on the window's toroidal storage (RingLayout): a shift
// moves nothing, and every index it takes or returns (Nearest() labels included) is a storage
// index of the window it follows, so Nearest() names the window's cell directly and stays valid
// across shifts.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/grid/rolling_window.hpp"

namespace gridslam::scan_matching {

class MatchingField {
 public:
  /// `max_distance` [m]: distances beyond are reported as "no obstacle near".
  explicit MatchingField(double max_distance) : max_distance_(max_distance) {}

  /// Brings the field up to date with `window` (its obstacles, the changes and the shift it
  /// reports since its last ClearChanges()). Does not clear the window's changes.
  void Update(const RollingWindow& window);

  /// Recomputes everything from `window` (what Update() does after a large change).
  void Rebuild(const RollingWindow& window);

  [[nodiscard]] const MapLimits& Limits() const { return limits_; }
  /// Storage of logical cell (i, j): the window's layout at the last Update() or Rebuild().
  [[nodiscard]] const RingLayout& Layout() const { return layout_; }
  [[nodiscard]] double MaxDistance() const { return max_distance_; }
  /// Nearest obstacle (the window's storage index) of the cell with storage index `index`; -1 if
  /// none within MaxDistance().
  [[nodiscard]] std::int32_t Nearest(std::size_t index) const { return field_.nearest[index]; }
  /// Squared distance to the nearest obstacle in cells^2 (+inf beyond MaxDistance()).
  [[nodiscard]] float SquaredDistanceCells(std::size_t index) const {
    return field_.squared[index];
  }
  /// Distance to the nearest obstacle of the cell with storage index `index` [m], clamped at
  /// MaxDistance().
  [[nodiscard]] float Distance(std::size_t index) const { return distance_[index]; }
  /// Distance to the nearest obstacle at `p` [m], bilinear between cell centres and clamped at
  /// MaxDistance(); `gradient` (may be null) receives its derivative with respect to p. Where the
  /// four cell centres around p are not all in the grid, MaxDistance() with a zero gradient.
  double Interpolate(const Eigen::Vector2d& p, Eigen::Vector2d* gradient) const {
    const double cx = (p.x() - origin_x_) * inv_resolution_ - 0.5;
    const double cy = (p.y() - origin_y_) * inv_resolution_ - 0.5;
    const double fx0 = std::floor(cx);
    const double fy0 = std::floor(cy);
    const auto i0 = static_cast<int>(fx0);
    const auto j0 = static_cast<int>(fy0);
    const double fx = cx - fx0;
    const double fy = cy - fy0;
    const int w = limits_.Width();
    const int h = limits_.Height();
    if (i0 < 0 || j0 < 0 || i0 + 1 >= w || j0 + 1 >= h) {
      // Outside the window nothing is known: no distance, no gradient (a clamped value at the
      // border would pull points along walls that leave the window).
      if (gradient != nullptr) {
        gradient->setZero();
      }
      return max_distance_;
    }
    // The four cells in storage: the next column or row may wrap around to storage 0.
    const int c0 = layout_.Column(i0);
    const int c1 = c0 + 1 == w ? 0 : c0 + 1;
    const int r0 = layout_.Row(j0);
    const int r1 = r0 + 1 == h ? 0 : r0 + 1;
    const float* row0 =
        distance_.data() + static_cast<std::size_t>(r0) * static_cast<std::size_t>(w);
    const float* row1 =
        distance_.data() + static_cast<std::size_t>(r1) * static_cast<std::size_t>(w);
    const double v00 = row0[c0];
    const double v10 = row0[c1];
    const double v01 = row1[c0];
    const double v11 = row1[c1];
    if (gradient != nullptr) {
      gradient->x() = ((1.0 - fy) * (v10 - v00) + fy * (v11 - v01)) * inv_resolution_;
      gradient->y() = ((1.0 - fx) * (v01 - v00) + fx * (v11 - v10)) * inv_resolution_;
    }
    return (1.0 - fx) * (1.0 - fy) * v00 + fx * (1.0 - fy) * v10 + (1.0 - fx) * fy * v01 +
           fx * fy * v11;
  }

  [[nodiscard]] long NumRebuilds() const { return num_rebuilds_; }
  [[nodiscard]] long NumTileUpdates() const { return num_tile_updates_; }

 private:
  /// The exact transform of logical cells [i0, i1) x [j0, j1) from the sources within the
  /// truncation radius around them, written to the storage.
  void UpdateRegion(const RollingWindow& window, int i0, int j0, int i1, int j1);
  void SetLimits(const MapLimits& limits, const RingLayout& layout);
  /// Moves a field computed in logical row-major order into the storage order of layout_.
  template <typename T>
  void RotateIntoStorage(std::vector<T>& cells) const;

  double max_distance_;
  MapLimits limits_;
  RingLayout layout_;
  /// Squared distances and nearest labels by storage index (its width and height are unused).
  distance_transform::SquaredDistanceField field_;
  std::vector<float> distance_;  ///< sqrt of field_.squared in metres, clamped at max_distance_.
  double origin_x_ = 0.0;
  double origin_y_ = 0.0;
  double inv_resolution_ = 1.0;
  distance_transform::SquaredDistanceField scratch_field_;
  std::vector<std::uint8_t> scratch_sources_;
  std::vector<Eigen::Array4i> done_boxes_;  ///< Boxes (i0, j0, i1, j1) recomputed this update.
  bool valid_ = false;
  long num_rebuilds_ = 0;
  long num_tile_updates_ = 0;
};

}  // namespace gridslam::scan_matching
