// The scan matcher's view of the rolling local map: the exact Euclidean distance transform of its
// obstacle cells (Felzenszwalb-Huttenlocher, distance_transform/), truncated at the maximum
// correspondence distance, with the nearest obstacle cell of every cell. Nearest-obstacle labels
// give the matcher O(1) correspondences (the map-side point and normal of each scan point, as
// PL-ICP's closest segment, paper reconstruction §6); the distances give a smooth (bilinear)
// distance field and the correlative search's score. The field follows the window's changes
// incrementally: only tiles around cells whose obstacle status changed, and strips uncovered by
// a shift, are recomputed (exactly: a cell's truncated distance can only change within the
// truncation radius of a changed cell).
#pragma once

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
  [[nodiscard]] double MaxDistance() const { return max_distance_; }
  /// Nearest obstacle (linear index) of the cell with linear index `index`; -1 if none within
  /// MaxDistance().
  [[nodiscard]] std::int32_t Nearest(std::size_t index) const { return field_.nearest[index]; }
  /// Squared distance to the nearest obstacle in cells^2 (+inf beyond MaxDistance()).
  [[nodiscard]] float SquaredDistanceCells(std::size_t index) const {
    return field_.squared[index];
  }
  /// Distance to the nearest obstacle at `p` [m], bilinear between cell centres and clamped at
  /// MaxDistance(); `gradient` (may be null) receives its derivative with respect to p.
  double Interpolate(const Eigen::Vector2d& p, Eigen::Vector2d* gradient) const;

  [[nodiscard]] long NumRebuilds() const { return num_rebuilds_; }
  [[nodiscard]] long NumTileUpdates() const { return num_tile_updates_; }

 private:
  void UpdateRegion(const RollingWindow& window, int i0, int j0, int i1, int j1);

  double max_distance_;
  MapLimits limits_;
  distance_transform::SquaredDistanceField field_;
  distance_transform::SquaredDistanceField scratch_field_;
  std::vector<std::uint8_t> scratch_sources_;
  std::vector<std::uint8_t> dirty_tiles_;
  bool valid_ = false;
  long num_rebuilds_ = 0;
  long num_tile_updates_ = 0;
};

}  // namespace gridslam::scan_matching
