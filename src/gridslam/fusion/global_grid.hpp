// Fusion of the key maps into one global occupancy grid (docs/design.md §1.8; docs/method.md
// §1.5.7). Two methods: re-inserting every scan at its corrected pose into a log-odds grid (the
// sharpest map, the default), and the paper's nearest-key-map (Voronoi) assignment, where each
// global cell takes its value from the key map whose optimized centre is nearest and that has
// observed it.
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/tiled_grid.hpp"
#include "gridslam/keymap/key_map.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::fusion {

struct FusionOptions {
  std::string method = "scans";     ///< "scans" (re-insert scans) or "nearest" (paper's Voronoi).
  double resolution = 0.05;         ///< Cell side of the global grid [m], 0.005 to 10.
  double max_range = 30.0;          ///< Returns farther than this are not inserted [m], <= 1000.
  double hit_probability = 0.7;     ///< Inverse sensor model at a beam's end cell [-].
  double miss_probability = 0.4;    ///< Inverse sensor model along the beam [-].
  double clamp_probability = 0.97;  ///< Log-odds clamp, symmetric [-].
  double occupied_probability = 0.65;  ///< Output: occupied above this [-].
  double free_probability = 0.35;      ///< Output: free below this [-].
  double min_motion = 0.05;    ///< A scan is inserted after this much travel since the last [m]...
  double min_rotation = 0.05;  ///< ... or this much rotation [rad].
  double margin = 1.0;         ///< Border around the observed area [m], 0 to 100.

  template <class V>
  void Visit(V& v) {
    v("method", method, "Fusion: scans (re-insert scans at corrected poses) or nearest (paper)");
    v("resolution", resolution, "Cell side of the global map [m]");
    v("max_range", max_range, "Returns farther than this are not inserted [m]");
    v("hit_probability", hit_probability, "Occupancy probability at a beam's end [-]");
    v("miss_probability", miss_probability, "Occupancy probability along a beam [-]");
    v("clamp_probability", clamp_probability, "Probability clamp of the log-odds [-]");
    v("occupied_probability", occupied_probability, "Output: occupied above this [-]");
    v("free_probability", free_probability, "Output: free below this [-]");
    v("min_motion", min_motion, "Insert a scan after this much travel [m] ...");
    v("min_rotation", min_rotation, "... or this much rotation [rad]");
    v("margin", margin, "Border around the observed area [m]");
  }
  [[nodiscard]] Status Validate() const;
};

/// A scan at its corrected pose in the map frame. `scan` is borrowed.
struct PosedScan {
  Pose2 T_map_base;
  Pose2 T_base_laser;
  const LaserScan* scan = nullptr;
};

/// The most cells a fused map may have (2.5e8 floats, 1 GB): a trajectory spanning more (a
/// corrupt pose, or far too fine a resolution) throws std::length_error before allocating.
constexpr long kMaxFusedCells = 250'000'000L;

/// Re-inserts the scans into a log-odds grid covering them (method "scans"). Throws
/// std::length_error if the grid would exceed kMaxFusedCells.
Grid2D<float> FuseScans(const std::vector<PosedScan>& scans, const FusionOptions& options);
/// Maps of at most this many cells (64 MB of floats) are fused densely, then tiled.
constexpr long kDenseFusionCells = 16'000'000L;

/// FuseScans into a tiled grid (the same limits and cells; tiles no scan touched are not
/// allocated): what the mapper's final fusion uses. Up to kDenseFusionCells the cells are fused
/// in a dense grid first (faster), beyond straight into tiles (memory bounded by the area the
/// scans cover). `threads` > 1 inserts bands of rows at once, each band's cells updated in
/// FuseScans' order: the same values for any number of threads.
/// `dense_cells`: the kDenseFusionCells threshold (tests set 0 to fuse into tiles always).
TiledGrid<float> FuseScansTiled(const std::vector<PosedScan>& scans, const FusionOptions& options,
                                int threads = 1, long dense_cells = kDenseFusionCells);

/// FuseScansTiled at options.resolution, or, when the scans span more than kMaxFusedCells at
/// it, at the finest of resolution * 2^k (k = 1, 2, ...; at most 10 m) that fits: a trajectory
/// that ran away (scan matching without odometry along a featureless corridor) still gives a
/// map, coarser, and the run keeps its other outputs. The grid's limits carry the resolution
/// used. Throws as FuseScans when even 10 m cells do not fit (or a pose is not finite).
TiledGrid<float> FuseScansFitting(const std::vector<PosedScan>& scans, FusionOptions options,
                                  int threads = 1);

/// A key map at its optimized pose (borrowed).
struct PosedKeyMap {
  Pose2 T_map_key;
  const keymap::KeyMap* key_map = nullptr;
};

/// The paper's fusion (method "nearest"): every cell copies the log-odds of the key map whose
/// centre is nearest among those that observed the cell. Throws as FuseScans.
Grid2D<float> FuseNearestKeyMap(const std::vector<PosedKeyMap>& key_maps,
                                const FusionOptions& options);

/// The occupancy image of a fused log-odds grid (nav_msgs convention).
OccupancyImage ToOccupancy(const Grid2D<float>& log_odds, const FusionOptions& options);
OccupancyImage ToOccupancy(const TiledGrid<float>& log_odds, const FusionOptions& options);

}  // namespace gridslam::fusion
