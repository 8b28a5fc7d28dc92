#include "gridslam/grid/rolling_window.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>

#include "gridslam/grid/log_odds.hpp"
#include "gridslam/grid/ray_casting.hpp"

namespace gridslam {
namespace {

// Beyond this many listed changes per update the consumer rebuilds everything anyway.
constexpr std::size_t kMaxListedChanges = 1U << 16;

// Moves a row-major w x h array in place by (di, dj) cells (new (i, j) = old (i + di, j + dj));
// entering cells get `fill`. T must be trivially copyable.
template <typename T>
void ShiftInPlace(std::vector<T>& cells, int w, int h, int di, int dj, const T& fill) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto uw = static_cast<std::size_t>(w);
  const int i0 = std::max(0, -di);  // first destination column with a source
  const int i1 = std::min(w, w - di);
  const auto count = static_cast<std::size_t>(std::max(0, i1 - i0));
  auto move_row = [&](int j) {
    T* row = cells.data() + static_cast<std::size_t>(j) * uw;
    const int src_j = j + dj;
    if (src_j < 0 || src_j >= h || count == 0) {
      std::fill(row, row + uw, fill);
      return;
    }
    const T* src = cells.data() + static_cast<std::size_t>(src_j) * uw + (i0 + di);
    const auto before = static_cast<std::size_t>(i0);
    std::memmove(static_cast<void*>(row + before), static_cast<const void*>(src),
                 count * sizeof(T));
    for (std::size_t i = 0; i < before; ++i) {
      row[i] = fill;
    }
    for (std::size_t i = before + count; i < uw; ++i) {
      row[i] = fill;
    }
  };
  if (dj >= 0) {  // sources lie at or after their destinations: go forwards
    for (int j = 0; j < h; ++j) {
      move_row(j);
    }
  } else {
    for (int j = h - 1; j >= 0; --j) {
      move_row(j);
    }
  }
}

// `grid` moved by (di, dj) cells: new (i, j) = old (i + di, j + dj); the origin moves by (di, dj)
// cells, entering cells get `fill`. In place: the cells are moved, not copied into a new grid.
template <typename T>
void Shift(Grid2D<T>& grid, int di, int dj, const T& fill) {
  const MapLimits& old = grid.Limits();
  const MapLimits limits(old.Resolution(),
                         old.Origin() + Eigen::Vector2d(di, dj) * old.Resolution(), old.Width(),
                         old.Height());
  std::vector<T> cells = std::move(grid.Cells());
  ShiftInPlace(cells, old.Width(), old.Height(), di, dj, fill);
  grid = Grid2D<T>(limits, std::move(cells));
}

}  // namespace

RollingWindow::RollingWindow(const LocalMapOptions& options, const Eigen::Vector2d& centre_odom,
                             bool track_surfaces)
    : options_(options), track_surfaces_(track_surfaces) {
  GRIDSLAM_CHECK(options.Validate().ok()) << options.Validate().error().ToString();
  hit_ = static_cast<float>(ProbabilityToLogOdds(options.hit_probability));
  miss_ = static_cast<float>(ProbabilityToLogOdds(options.miss_probability));
  min_ = static_cast<float>(ProbabilityToLogOdds(options.min_probability));
  max_ = static_cast<float>(ProbabilityToLogOdds(options.max_probability));
  occupied_ = static_cast<float>(ProbabilityToLogOdds(options.occupied_probability));
  const int n = options.NumCells();
  const double res = options.resolution;
  // Cells lie on the lattice of multiples of the resolution; the centre cell holds centre_odom.
  const Eigen::Vector2d origin((std::floor(centre_odom.x() / res) - n / 2) * res,
                               (std::floor(centre_odom.y() / res) - n / 2) * res);
  const MapLimits limits(res, origin, n, n);
  log_odds_ = Grid2D<float>(limits, kUnknownLogOdds);
  obstacles_ = Grid2D<std::uint8_t>(limits, 0);
  if (track_surfaces_) {
    surfaces_.assign(static_cast<std::size_t>(limits.NumCells()), CellSurface{});
  }
  stamps_.assign(static_cast<std::size_t>(limits.NumCells()), 0);
}

Eigen::Vector2d RollingWindow::Centre() const {
  const MapLimits& limits = Limits();
  return limits.CellCenter(Eigen::Array2i(limits.Width() / 2, limits.Height() / 2));
}

Eigen::Vector2d RollingWindow::MeanPoint(std::int32_t index) const {
  const int w = Limits().Width();
  const CellSurface& s = surfaces_[static_cast<std::size_t>(index)];
  return Limits().CellCenter(Eigen::Array2i(index % w, index / w)) +
         Eigen::Vector2d(s.mean_x, s.mean_y);
}

Eigen::Array2i RollingWindow::Recentre(const Eigen::Vector2d& p_odom) {
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
  Shift(log_odds_, shift.x(), shift.y(), kUnknownLogOdds);
  Shift(obstacles_, shift.x(), shift.y(), std::uint8_t{0});
  if (track_surfaces_) {
    ShiftInPlace(surfaces_, Limits().Width(), Limits().Height(), shift.x(), shift.y(),
                 CellSurface{});
  }
  std::fill(stamps_.begin(), stamps_.end(), 0U);
  stamp_ = 0;
  num_obstacles_ = std::count(obstacles_.Cells().begin(), obstacles_.Cells().end(), 1);
  // Pending changes follow their cells; those that left are dropped.
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

void RollingWindow::MarkChanged(std::size_t index) {
  if (changed_.size() < kMaxListedChanges) {
    changed_.push_back(static_cast<std::int32_t>(index));
  } else {
    changes_overflow_ = true;
  }
}

void RollingWindow::ApplyHit(std::size_t index) {
  float& l = log_odds_.data()[index];
  l = std::min(l + hit_, max_);
  std::uint8_t& obstacle = obstacles_.data()[index];
  if (obstacle == 0 && l > occupied_) {
    obstacle = 1;
    ++num_obstacles_;
    MarkChanged(index);
  }
}

void RollingWindow::ApplyMiss(std::size_t index) {
  float& l = log_odds_.data()[index];
  l = std::max(l + miss_, min_);
  std::uint8_t& obstacle = obstacles_.data()[index];
  if (obstacle != 0 && l <= occupied_) {
    obstacle = 0;
    --num_obstacles_;
    if (track_surfaces_) {
      surfaces_[index] = CellSurface{};
    }
    MarkChanged(index);
  }
}

void RollingWindow::TraceFree(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                              bool to_is_hit) {
  const MapLimits& limits = Limits();
  const auto clipped = ClipSegment(limits, from, to);
  if (!clipped) {
    return;
  }
  const Eigen::Array2i a = limits.CellIndex(clipped->first);
  const Eigen::Array2i b = limits.CellIndex(clipped->second);
  // The end cell of a return is its hit cell; a ray cut at the border passes through its last cell.
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

void RollingWindow::InsertScan(const Pose2& T_odom_base, const ScanPoints& scan) {
  ++stamp_;
  if (stamp_ == 0) {  // wrapped around: forget old stamps
    std::fill(stamps_.begin(), stamps_.end(), 0U);
    stamp_ = 1;
  }
  ++num_scans_;
  const MapLimits& limits = Limits();
  const Eigen::Matrix2d R = T_odom_base.Rotation();
  const PointTransform to_odom(T_odom_base);
  const Eigen::Vector2d origin = T_odom_base * scan.origin;
  const double max_range2 = options_.max_range * options_.max_range;
  const auto memory = static_cast<std::uint16_t>(std::clamp(options_.surface_memory, 1, 60000));
  // Hits first, so that no ray of the same scan clears a cell this scan hit.
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
    if (!track_surfaces_) {
      continue;
    }
    CellSurface& s = surfaces_[index];
    s.hits = std::min<std::uint16_t>(static_cast<std::uint16_t>(s.hits + 1), memory);
    const float a = 1.0F / static_cast<float>(s.hits);
    const Eigen::Vector2f local = (p - limits.CellCenter(cell)).cast<float>();
    s.mean_x += a * (local.x() - s.mean_x);
    s.mean_y += a * (local.y() - s.mean_y);
    Eigen::Vector2f n = (R * scan.normals[k]).cast<float>() * scan.normal_quality[k];
    if (n.x() * s.normal_x + n.y() * s.normal_y < 0.0F) {
      n = -n;  // normals have no sign: agree with the mean so far
    }
    s.normal_x += a * (n.x() - s.normal_x);
    s.normal_y += a * (n.y() - s.normal_y);
  }
  for (std::size_t k = 0; k < scan.size(); ++k) {
    const Eigen::Vector2d& pb = scan.points[k];
    const double range2 = (pb - scan.origin).squaredNorm();
    if (range2 > max_range2) {  // clear only up to max_range, never mark
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

void RollingWindow::ClearChanges() {
  changed_.clear();
  pending_shift_.setZero();
  changes_overflow_ = false;
}

Grid2D<float> RollingWindow::SnapshotInCentreFrame(int num_cells) const {
  const MapLimits& limits = Limits();
  const int w = limits.Width();
  const int h = limits.Height();
  const int cw = num_cells > 0 && num_cells < w ? num_cells : w;
  const int ch = num_cells > 0 && num_cells < h ? num_cells : h;
  // Same centre cell: the crop starts (w - cw) / 2 cells in (both odd, so the offset is whole).
  const int i0 = w / 2 - cw / 2;
  const int j0 = h / 2 - ch / 2;
  const Eigen::Vector2d origin = limits.Origin() + Eigen::Vector2d(i0, j0) * limits.Resolution();
  Grid2D<float> out(MapLimits(limits.Resolution(), origin - Centre(), cw, ch), kUnknownLogOdds);
  for (int j = 0; j < ch; ++j) {
    std::copy(&log_odds_(i0, j0 + j), &log_odds_(i0, j0 + j) + cw, &out(0, j));
  }
  return out;
}

}  // namespace gridslam
