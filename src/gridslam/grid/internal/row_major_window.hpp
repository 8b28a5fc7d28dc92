// Test-only reference: the rolling window as it was before its layers moved to toroidal storage
// (RingGrid). Every layer is a plain row-major Grid2D, cell (i, j) at index j * width + i, and
// recentring moves every layer with Grid2D::Shift (ShiftCellsInPlace, memmove), as the window did
// up to commit d09d003. The update rules are copied from that version line by line, so the
// RollingWindow on ring storage can be checked against it cell by cell: the two must agree bit for
// bit in logical coordinates (log-odds, obstacles, surfaces, obstacle count, the changed cells in
// order, the pending shift) whatever the ring's storage offsets.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/local_map_options.hpp"
#include "gridslam/grid/log_odds.hpp"
#include "gridslam/grid/ray_casting.hpp"
#include "gridslam/grid/rolling_window.hpp"
#include "gridslam/grid/scan_points.hpp"

namespace gridslam::internal {

class RowMajorWindow {
 public:
  /// As RollingWindow(options, centre_odom, true): surfaces are always tracked.
  RowMajorWindow(const LocalMapOptions& options, const Eigen::Vector2d& centre_odom)
      : options_(options) {
    hit_ = static_cast<float>(ProbabilityToLogOdds(options.hit_probability));
    miss_ = static_cast<float>(ProbabilityToLogOdds(options.miss_probability));
    min_ = static_cast<float>(ProbabilityToLogOdds(options.min_probability));
    max_ = static_cast<float>(ProbabilityToLogOdds(options.max_probability));
    occupied_ = static_cast<float>(ProbabilityToLogOdds(options.occupied_probability));
    const int n = options.NumCells();
    const double res = options.resolution;
    const Eigen::Vector2d origin((std::floor(centre_odom.x() / res) - n / 2) * res,
                                 (std::floor(centre_odom.y() / res) - n / 2) * res);
    const MapLimits limits(res, origin, n, n);
    log_odds_ = Grid2D<float>(limits, kUnknownLogOdds);
    obstacles_ = Grid2D<std::uint8_t>(limits, 0);
    surfaces_ = Grid2D<CellSurface>(limits, CellSurface{});
    stamps_.assign(static_cast<std::size_t>(limits.NumCells()), 0);
  }

  [[nodiscard]] const MapLimits& Limits() const { return log_odds_.Limits(); }
  [[nodiscard]] const Grid2D<float>& LogOdds() const { return log_odds_; }
  [[nodiscard]] const Grid2D<std::uint8_t>& Obstacles() const { return obstacles_; }
  [[nodiscard]] const Grid2D<CellSurface>& Surfaces() const { return surfaces_; }
  /// Mean hit point of cell (i, j) in the odometry frame [m].
  [[nodiscard]] Eigen::Vector2d MeanPoint(int i, int j) const {
    const CellSurface& s = surfaces_(i, j);
    return Limits().CellCenter(Eigen::Array2i(i, j)) + Eigen::Vector2d(s.mean_x, s.mean_y);
  }
  [[nodiscard]] long NumObstacles() const { return num_obstacles_; }
  /// Row-major indices (j * width + i) of the cells that changed obstacle status, in order.
  [[nodiscard]] const std::vector<std::int32_t>& ChangedCells() const { return changed_; }
  [[nodiscard]] const Eigen::Array2i& PendingShift() const { return pending_shift_; }
  [[nodiscard]] bool ChangesOverflow() const { return changes_overflow_; }
  void ClearChanges() {
    changed_.clear();
    pending_shift_.setZero();
    changes_overflow_ = false;
  }

  Eigen::Array2i Recentre(const Eigen::Vector2d& p_odom) {
    const MapLimits& limits = Limits();
    const Eigen::Array2i offset =
        limits.CellIndex(p_odom) - Eigen::Array2i(limits.Width() / 2, limits.Height() / 2);
    const int trigger =
        std::max(1, static_cast<int>(std::lround(options_.shift_distance / options_.resolution)));
    const Eigen::Array2i shift(std::abs(offset.x()) >= trigger ? offset.x() : 0,
                               std::abs(offset.y()) >= trigger ? offset.y() : 0);
    if ((shift == 0).all()) {
      return shift;
    }
    log_odds_.Shift(shift.x(), shift.y(), kUnknownLogOdds);
    obstacles_.Shift(shift.x(), shift.y(), std::uint8_t{0});
    surfaces_.Shift(shift.x(), shift.y(), CellSurface{});
    num_obstacles_ = std::count(obstacles_.Cells().begin(), obstacles_.Cells().end(), 1);
    const int w = Limits().Width();
    const int h = Limits().Height();
    std::size_t kept = 0;
    for (const std::int32_t index : changed_) {
      const int i = index % w - shift.x();
      const int j = index / w - shift.y();
      if (i >= 0 && j >= 0 && i < w && j < h) {
        changed_[kept++] = j * w + i;
      }
    }
    changed_.resize(kept);
    pending_shift_ += shift;
    return shift;
  }

  void InsertScan(const Pose2& T_odom_base, const ScanPoints& scan) {
    ++stamp_;
    if (stamp_ == 0) {
      std::fill(stamps_.begin(), stamps_.end(), 0U);
      stamp_ = 1;
    }
    const MapLimits& limits = Limits();
    const Eigen::Matrix2d R = T_odom_base.Rotation();
    const PointTransform to_odom(T_odom_base);
    const Eigen::Vector2d origin = T_odom_base * scan.origin;
    const double max_range2 = options_.max_range * options_.max_range;
    const auto memory = static_cast<std::uint16_t>(std::clamp(options_.surface_memory, 1, 60000));
    for (std::size_t k = 0; k < scan.size(); ++k) {
      if ((scan.points[k] - scan.origin).squaredNorm() > max_range2) {
        continue;
      }
      const Eigen::Vector2d p = to_odom(scan.points[k]);
      const Eigen::Array2i cell = limits.CellIndex(p);
      if (!limits.Contains(cell)) {
        continue;
      }
      const auto index = static_cast<std::size_t>(limits.LinearIndex(cell));
      if (stamps_[index] != stamp_) {
        stamps_[index] = stamp_;
        ApplyHit(index);
      }
      CellSurface& s = surfaces_.data()[index];
      s.hits = std::min<std::uint16_t>(static_cast<std::uint16_t>(s.hits + 1), memory);
      const float a = 1.0F / static_cast<float>(s.hits);
      const Eigen::Vector2f local = (p - limits.CellCenter(cell)).cast<float>();
      s.mean_x += a * (local.x() - s.mean_x);
      s.mean_y += a * (local.y() - s.mean_y);
      Eigen::Vector2f n = (R * scan.normals[k]).cast<float>() * scan.normal_quality[k];
      if (n.x() * s.normal_x + n.y() * s.normal_y < 0.0F) {
        n = -n;
      }
      s.normal_x += a * (n.x() - s.normal_x);
      s.normal_y += a * (n.y() - s.normal_y);
    }
    for (std::size_t k = 0; k < scan.size(); ++k) {
      const Eigen::Vector2d& pb = scan.points[k];
      const double range2 = (pb - scan.origin).squaredNorm();
      if (range2 > max_range2) {
        const Eigen::Vector2d dir = (pb - scan.origin) / std::sqrt(range2);
        TraceFree(origin, origin + R * dir * options_.max_range, false);
      } else {
        TraceFree(origin, to_odom(pb), true);
      }
    }
    if (options_.clear_no_returns) {
      for (const Eigen::Vector2d& dir : scan.no_return_directions) {
        TraceFree(origin, origin + R * dir * options_.no_return_clearing_range, false);
      }
    }
  }

 private:
  static constexpr std::size_t kMaxListedChanges = 1U << 16;

  void MarkChanged(std::size_t index) {
    if (changed_.size() < kMaxListedChanges) {
      changed_.push_back(static_cast<std::int32_t>(index));
    } else {
      changes_overflow_ = true;
    }
  }

  void ApplyHit(std::size_t index) {
    float& l = log_odds_.data()[index];
    l = std::min(l + hit_, max_);
    std::uint8_t& obstacle = obstacles_.data()[index];
    if (obstacle == 0 && l > occupied_) {
      obstacle = 1;
      ++num_obstacles_;
      MarkChanged(index);
    }
  }

  void ApplyMiss(std::size_t index) {
    float& l = log_odds_.data()[index];
    l = std::max(l + miss_, min_);
    std::uint8_t& obstacle = obstacles_.data()[index];
    if (obstacle != 0 && l <= occupied_) {
      obstacle = 0;
      --num_obstacles_;
      surfaces_.data()[index] = CellSurface{};
      MarkChanged(index);
    }
  }

  void TraceFree(const Eigen::Vector2d& from, const Eigen::Vector2d& to, bool to_is_hit) {
    const MapLimits& limits = Limits();
    const auto clipped = ClipSegment(limits, from, to);
    if (!clipped) {
      return;
    }
    const Eigen::Array2i a = limits.CellIndex(clipped->first);
    const Eigen::Array2i b = limits.CellIndex(clipped->second);
    const bool include_end = !(to_is_hit && limits.Contains(limits.CellIndex(to)));
    const auto w = static_cast<std::size_t>(limits.Width());
    TraceLine(a, b, include_end, [&](int i, int j) {
      const std::size_t index = static_cast<std::size_t>(j) * w + static_cast<std::size_t>(i);
      if (stamps_[index] != stamp_) {
        stamps_[index] = stamp_;
        ApplyMiss(index);
      }
    });
  }

  LocalMapOptions options_;
  float hit_ = 0.0F;
  float miss_ = 0.0F;
  float min_ = 0.0F;
  float max_ = 0.0F;
  float occupied_ = 0.0F;
  Grid2D<float> log_odds_;
  Grid2D<std::uint8_t> obstacles_;
  Grid2D<CellSurface> surfaces_;
  std::vector<std::uint32_t> stamps_;  ///< Never shifted, as in the original.
  std::uint32_t stamp_ = 0;
  long num_obstacles_ = 0;
  std::vector<std::int32_t> changed_;
  Eigen::Array2i pending_shift_ = Eigen::Array2i::Zero();
  bool changes_overflow_ = false;
};

}  // namespace gridslam::internal
