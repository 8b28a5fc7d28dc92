#include "gridslam/grid/rolling_window.hpp"

#include <algorithm>
#include <cmath>

#include "gridslam/grid/log_odds.hpp"
#include "gridslam/grid/ray_casting.hpp"

namespace gridslam {
namespace {

// Beyond this many listed changes per update the consumer rebuilds everything anyway.
constexpr std::size_t kMaxListedChanges = 1U << 16;

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
  log_odds_ = RingGrid<float>(limits, kUnknownLogOdds);
  obstacles_ = RingGrid<std::uint8_t>(limits, 0);
  if (track_surfaces_) {
    surfaces_ = RingGrid<CellSurface>(limits, CellSurface{});
  }
  stamps_.assign(static_cast<std::size_t>(limits.NumCells()), 0);
}

Eigen::Vector2d RollingWindow::Centre() const {
  const MapLimits& limits = Limits();
  return limits.CellCenter(Eigen::Array2i(limits.Width() / 2, limits.Height() / 2));
}

Eigen::Vector2d RollingWindow::MeanPoint(std::int32_t index) const {
  const auto storage = static_cast<std::size_t>(index);
  const CellSurface& s = surfaces_.data()[storage];
  return Limits().CellCenter(Layout().Cell(storage)) + Eigen::Vector2d(s.mean_x, s.mean_y);
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
  // Pending changes keep their storage; those whose cells leave are dropped (read with the
  // layout before the shift).
  const RingLayout before = Layout();
  std::size_t kept = 0;
  for (const std::int32_t index : changed_) {
    const Eigen::Array2i cell = before.Cell(static_cast<std::size_t>(index)) - shift;
    if (Limits().Contains(cell)) {
      changed_[kept++] = index;
    }
  }
  changed_.resize(kept);
  // The obstacles that leave are those in the storage the entering cells take over.
  const std::uint8_t* obstacles = obstacles_.data();
  before.ForEachReplacedRun(shift.x(), shift.y(), [&](std::size_t index, std::size_t count) {
    num_obstacles_ -= std::count(obstacles + index, obstacles + index + count, 1);
  });
  log_odds_.Shift(shift.x(), shift.y(), kUnknownLogOdds);
  obstacles_.Shift(shift.x(), shift.y(), std::uint8_t{0});
  if (track_surfaces_) {
    surfaces_.Shift(shift.x(), shift.y(), CellSurface{});
  }
  // The stamps stay where they are: every one of them is older than the next scan's stamp, so
  // they cannot collide with it wherever they now lie.
  pending_shift_ += shift;
  for (int a = 0; a < 2; ++a) {
    const int sign = (shift[a] > 0) - (shift[a] < 0);
    if (sign != 0) {
      shift_reversed_ = shift_reversed_ || (shift_sign_[a] != 0 && shift_sign_[a] != sign);
      shift_sign_[a] = sign;
    }
  }
  return shift;
}

void RollingWindow::MarkChanged(std::size_t index) {
  if (changes_overflow_) {
    return;
  }
  if (changed_.size() < kMaxListedChanges) {
    changed_.push_back(static_cast<std::int32_t>(index));
  } else {
    // Every cell counts as changed now: the list is dropped, so that a window whose follower
    // updates rarely (the front end's key-map window) does not filter a full list at every shift.
    changes_overflow_ = true;
    changed_.clear();
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

void RollingWindow::ClearObstacle(std::size_t index) {
  obstacles_.data()[index] = 0;
  --num_obstacles_;
  if (track_surfaces_) {
    surfaces_.data()[index] = CellSurface{};
  }
  MarkChanged(index);
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
  // The layers and constants in locals: the stores into the layers (a byte store may alias
  // anything) would otherwise make the compiler reload every member at every cell.
  std::uint32_t* const stamps = stamps_.data();
  float* const log_odds = log_odds_.data();
  const std::uint8_t* const obstacles = obstacles_.data();
  const std::uint32_t stamp = stamp_;
  const float miss = miss_;
  const float min = min_;
  const float occupied = occupied_;
  TraceLineInRing(Layout(), a, b, include_end, [&](std::size_t index) {
    if (stamps[index] == stamp) {
      return;
    }
    stamps[index] = stamp;
    float& l = log_odds[index];
    l = std::max(l + miss, min);
    if (obstacles[index] != 0 && l <= occupied) {
      ClearObstacle(index);
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
    const std::size_t index = Layout().Index(cell);
    if (stamps_[index] != stamp_) {
      stamps_[index] = stamp_;
      ApplyHit(index);
    }
    if (!track_surfaces_) {
      continue;
    }
    CellSurface& s = surfaces_.data()[index];
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
  shift_sign_.setZero();
  shift_reversed_ = false;
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
  log_odds_.CopyRegion(i0, j0, i0 + cw, j0 + ch, out.data());
  return out;
}

}  // namespace gridslam
