// Incremental fusion for map snapshots (Mapper::Snapshot, docs/online_api.md): each key map's
// scans are fused once into a log-odds grid in the key map's own frame; a component's map is the
// sum of these grids, each resampled (nearest cell) at the key map's estimate. Log-odds add, so
// a key map whose estimate moved is taken out at its old pose and put in at its new one; the
// cost of an update is proportional to the key maps added or moved (by more than a cell, or
// a turn moving its far corner by that much), not to the whole map. The grid grows (and is
// rebuilt) only when a key map falls outside it. Not bit-identical to the final fusion
// (fusion::FuseScans), which interpolates corrections between key maps and clamps once.
#pragma once

#include <map>
#include <vector>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::pipeline {

class SnapshotFusion {
 public:
  explicit SnapshotFusion(const fusion::FusionOptions& options) : options_(options) {}

  /// Fuses key map `id`'s scans (T_map_base = the scan's pose in the key map's frame). Once per
  /// key map; an id without scans is ignored.
  void AddKeyMap(int id, const std::vector<fusion::PosedScan>& scans_in_key_frame);
  [[nodiscard]] bool Has(int id) const { return local_.count(id) != 0; }

  struct Placed {
    int id = 0;
    Pose2 T_map_key;
  };
  struct UpdateStats {
    long added = 0;     ///< Key maps placed for the first time.
    long replaced = 0;  ///< Key maps taken out and put in again.
  };
  /// The map of component `component` with exactly the key maps `key_maps` (at their
  /// estimates): updates the stored grid incrementally and returns it.
  const Grid2D<float>& Update(int component, const std::vector<Placed>& key_maps,
                              UpdateStats& stats);

 private:
  struct Composite {
    Grid2D<float> grid;
    std::map<int, Pose2> placed;  ///< Key map id -> pose it was added at.
  };
  /// Adds `sign` * key map `id`'s grid at `T_map_key` into `grid`.
  void Place(Grid2D<float>& grid, int id, const Pose2& T_map_key, float sign) const;
  [[nodiscard]] bool Moved(int id, const Pose2& before, const Pose2& after) const;
  /// Metric bounds (min, max) of key map `id`'s grid at `T_map_key`.
  void Bounds(int id, const Pose2& T_map_key, Eigen::Vector2d& lo, Eigen::Vector2d& hi) const;

  fusion::FusionOptions options_;
  std::map<int, Grid2D<float>> local_;
  std::map<int, Composite> composites_;
};

}  // namespace gridslam::pipeline
