// The rolling-window local occupancy map of the front end (docs/design.md §1.3; docs/method.md
// §1.4): a log-odds grid (0.05 m cells; 25 m side by default, key maps are its central 15 m)
// axis-aligned with the front end's odometry frame and centred on the robot. When the robot is
// more than `shift_distance` from the centre along x or y, the window moves by the whole offset
// along that axis, in whole cells, so world coordinates of the cells that stay are unchanged;
// cells leaving are forgotten and cells entering start unknown. Scans are inserted with an
// inverse sensor model (hits at the end cell, misses along the Bresenham ray, each cell updated
// at most once per scan as in Cartographer's ProbabilityGrid; max-range readings never mark and
// clear only if enabled, up to a cap). Besides the log-odds, the window can keep for every cell
// the running mean of the points that hit it and of their surface normals (sub-cell
// point-to-line correspondences for the matcher), and it tracks which cells changed obstacle
// status so a distance field over the obstacles can be updated incrementally. Every layer lies on
// toroidal storage (RingGrid, one RingLayout for all): recentring rotates the view and clears the
// entering strips instead of moving the whole window. Cell indices the window hands out or takes
// (ChangedCells(), MeanPoint(), Surface(), the data() of its layers) are storage indices,
// Layout().Index(i, j); logical cells are (i, j) in Limits().
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/local_map_options.hpp"
#include "gridslam/grid/ring_grid.hpp"
#include "gridslam/grid/scan_points.hpp"

namespace gridslam {

/// What an obstacle cell knows about the surface that hit it (20 bytes).
struct CellSurface {
  float mean_x = 0.0F;  ///< Running mean of the hits, relative to the cell centre [m].
  float mean_y = 0.0F;
  /// Running mean of the hits' unit normals, each weighted by its quality and flipped to agree
  /// with the mean so far: its direction is the surface normal, its length (in [0, 1]) how
  /// consistent the normals were.
  float normal_x = 0.0F;
  float normal_y = 0.0F;
  std::uint16_t hits = 0;  ///< Hits averaged (capped at surface_memory).

  [[nodiscard]] float Planarity() const {
    return std::sqrt(normal_x * normal_x + normal_y * normal_y);
  }
};

class RollingWindow {
 public:
  /// An unknown window centred on the cell containing `centre_odom`. Without `track_surfaces`
  /// the per-cell mean points and normals are not kept (Surfaces() is empty, MeanPoint() must
  /// not be called).
  RollingWindow(const LocalMapOptions& options, const Eigen::Vector2d& centre_odom,
                bool track_surfaces = true);

  [[nodiscard]] const LocalMapOptions& Options() const { return options_; }
  /// Geometry in the odometry frame; the origin changes only in whole cells.
  [[nodiscard]] const MapLimits& Limits() const { return log_odds_.Limits(); }
  /// Metric centre of the centre cell (the key-map frame's origin, docs/design.md §1.3).
  [[nodiscard]] Eigen::Vector2d Centre() const;
  /// Where logical cell (i, j) lies in the storage of every layer.
  [[nodiscard]] const RingLayout& Layout() const { return log_odds_.Layout(); }
  [[nodiscard]] const RingGrid<float>& LogOdds() const { return log_odds_; }
  /// 1 where the cell is an obstacle (probability > occupied_probability), else 0.
  [[nodiscard]] const RingGrid<std::uint8_t>& Obstacles() const { return obstacles_; }
  /// Surface statistics of every cell, in the storage order of Layout(); null without
  /// track_surfaces.
  [[nodiscard]] const CellSurface* Surfaces() const {
    return surfaces_.size() == 0 ? nullptr : surfaces_.data();
  }
  [[nodiscard]] const CellSurface& Surface(std::size_t index) const {
    return surfaces_.data()[index];
  }
  [[nodiscard]] bool TracksSurfaces() const { return track_surfaces_; }
  /// Mean hit point of cell `index` (storage index) in the odometry frame [m].
  [[nodiscard]] Eigen::Vector2d MeanPoint(std::int32_t index) const;
  [[nodiscard]] long NumObstacles() const { return num_obstacles_; }
  [[nodiscard]] long NumInsertedScans() const { return num_scans_; }

  /// Shifts the window if `p_odom` is at least shift_distance from the centre along an axis;
  /// returns the shift (di, dj) in cells: new cell (i, j) is old cell (i + di, j + dj).
  Eigen::Array2i Recentre(const Eigen::Vector2d& p_odom);

  /// Inserts `scan` (points in the base frame) seen from the robot pose `T_odom_base`.
  void InsertScan(const Pose2& T_odom_base, const ScanPoints& scan);

  /// Storage indices of the cells whose obstacle status changed since the last
  /// ClearChanges(), and the accumulated shift over that time; `changes_overflow` if too many to
  /// list (then treat every cell as changed; the list is empty).
  [[nodiscard]] const std::vector<std::int32_t>& ChangedCells() const { return changed_; }
  [[nodiscard]] const Eigen::Array2i& PendingShift() const { return pending_shift_; }
  [[nodiscard]] bool ChangesOverflow() const { return changes_overflow_; }
  /// The window moved back and forth along an axis since the last ClearChanges(): cells that
  /// left and came back were cleared although the net shift does not cover them, so an
  /// incremental follower must start afresh.
  [[nodiscard]] bool ShiftReversed() const { return shift_reversed_; }
  void ClearChanges();

  /// The central `num_cells` x `num_cells` part (odd; 0 or more than the window = all of it) of
  /// the log-odds grid, with MapLimits in the frame centred on Centre() (yaw 0).
  [[nodiscard]] Grid2D<float> SnapshotInCentreFrame(int num_cells = 0) const;

 private:
  void ApplyHit(std::size_t index);
  /// A miss took the cell's probability to or below occupied_probability.
  void ClearObstacle(std::size_t index);
  void MarkChanged(std::size_t index);
  void TraceFree(const Eigen::Vector2d& from, const Eigen::Vector2d& to, bool to_is_hit);

  LocalMapOptions options_;
  bool track_surfaces_ = true;
  float hit_ = 0.0F;
  float miss_ = 0.0F;
  float min_ = 0.0F;
  float max_ = 0.0F;
  float occupied_ = 0.0F;
  RingGrid<float> log_odds_;
  RingGrid<std::uint8_t> obstacles_;
  RingGrid<CellSurface> surfaces_;  ///< Empty without track_surfaces.
  /// Last scan that updated each cell, by storage index; never shifted (every stamp is older
  /// than the next scan's, wherever it now lies).
  std::vector<std::uint32_t> stamps_;
  std::uint32_t stamp_ = 0;
  long num_obstacles_ = 0;
  long num_scans_ = 0;
  std::vector<std::int32_t> changed_;
  Eigen::Array2i pending_shift_ = Eigen::Array2i::Zero();
  Eigen::Array2i shift_sign_ = Eigen::Array2i::Zero();  ///< Of the shifts since ClearChanges.
  bool shift_reversed_ = false;
  bool changes_overflow_ = false;
};

}  // namespace gridslam
