#include "gridslam/scan_matching/matching_field.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::scan_matching {
namespace {

constexpr int kTile = 16;  // side of the change-tracking tiles [cells]

// Moves a row-major field by (di, dj) cells (new (i, j) = old (i + di, j + dj)); labels are
// re-indexed and dropped (with their distance) when their obstacle left the grid.
void ShiftField(distance_transform::SquaredDistanceField& field, int di, int dj) {
  const int w = field.width;
  const int h = field.height;
  std::vector<float> squared(field.squared.size(), distance_transform::kInfinity);
  std::vector<std::int32_t> nearest(field.nearest.size(), -1);
  for (int j = 0; j < h; ++j) {
    const int sj = j + dj;
    if (sj < 0 || sj >= h) {
      continue;
    }
    for (int i = 0; i < w; ++i) {
      const int si = i + di;
      if (si < 0 || si >= w) {
        continue;
      }
      const std::size_t src = static_cast<std::size_t>(sj) * static_cast<std::size_t>(w) +
                              static_cast<std::size_t>(si);
      const std::int32_t label = field.nearest[src];
      if (label < 0) {
        continue;
      }
      const int li = label % w - di;
      const int lj = label / w - dj;
      if (li < 0 || lj < 0 || li >= w || lj >= h) {
        continue;
      }
      const std::size_t dst = static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
                              static_cast<std::size_t>(i);
      squared[dst] = field.squared[src];
      nearest[dst] = lj * w + li;
    }
  }
  field.squared.swap(squared);
  field.nearest.swap(nearest);
}

}  // namespace

void MatchingField::Rebuild(const RollingWindow& window) {
  limits_ = window.Limits();
  const auto max_cells = static_cast<float>(max_distance_ / limits_.Resolution());
  distance_transform::SquaredEuclideanDistanceTransform(
      window.Obstacles().data(), limits_.Width(), limits_.Height(), field_, true, max_cells);
  valid_ = true;
  ++num_rebuilds_;
}

void MatchingField::UpdateRegion(const RollingWindow& window, int i0, int j0, int i1, int j1) {
  // Sources within the truncation radius of the region; outside them nothing can be nearer.
  const int w = limits_.Width();
  const int h = limits_.Height();
  const int r = static_cast<int>(std::ceil(max_distance_ / limits_.Resolution()));
  const int si0 = std::max(0, i0 - r);
  const int sj0 = std::max(0, j0 - r);
  const int si1 = std::min(w, i1 + r);
  const int sj1 = std::min(h, j1 + r);
  const int sw = si1 - si0;
  const int sh = sj1 - sj0;
  if (i0 >= i1 || j0 >= j1) {
    return;
  }
  scratch_sources_.resize(static_cast<std::size_t>(sw) * static_cast<std::size_t>(sh));
  const std::uint8_t* obstacles = window.Obstacles().data();
  for (int j = sj0; j < sj1; ++j) {
    std::copy(obstacles + static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + si0,
              obstacles + static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + si1,
              scratch_sources_.data() + static_cast<std::size_t>(j - sj0) * static_cast<std::size_t>(sw));
  }
  const auto max_cells = static_cast<float>(max_distance_ / limits_.Resolution());
  distance_transform::SquaredEuclideanDistanceTransform(scratch_sources_.data(), sw, sh,
                                                        scratch_field_, true, max_cells);
  for (int j = j0; j < j1; ++j) {
    for (int i = i0; i < i1; ++i) {
      const std::size_t local = static_cast<std::size_t>(j - sj0) * static_cast<std::size_t>(sw) +
                                static_cast<std::size_t>(i - si0);
      const std::size_t global = static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
                                 static_cast<std::size_t>(i);
      const std::int32_t label = scratch_field_.nearest[local];
      field_.squared[global] = scratch_field_.squared[local];
      field_.nearest[global] = label < 0 ? -1 : (sj0 + label / sw) * w + (si0 + label % sw);
    }
  }
  ++num_tile_updates_;
}

void MatchingField::Update(const RollingWindow& window) {
  const MapLimits& limits = window.Limits();
  const Eigen::Array2i shift = window.PendingShift();
  const int w = limits.Width();
  const int h = limits.Height();
  if (!valid_ || window.ChangesOverflow() || w != limits_.Width() || h != limits_.Height() ||
      std::abs(shift.x()) >= w / 2 || std::abs(shift.y()) >= h / 2) {
    Rebuild(window);
    return;
  }
  const int r = static_cast<int>(std::ceil(max_distance_ / limits.Resolution()));
  if ((shift != 0).any()) {
    ShiftField(field_, shift.x(), shift.y());
    limits_ = limits;
    // Cells within r of an edge where obstacles left, and the cells that entered.
    if (shift.x() > 0) {
      UpdateRegion(window, 0, 0, r, h);
      UpdateRegion(window, w - shift.x(), 0, w, h);
    } else if (shift.x() < 0) {
      UpdateRegion(window, w - r, 0, w, h);
      UpdateRegion(window, 0, 0, -shift.x(), h);
    }
    if (shift.y() > 0) {
      UpdateRegion(window, 0, 0, w, r);
      UpdateRegion(window, 0, h - shift.y(), w, h);
    } else if (shift.y() < 0) {
      UpdateRegion(window, 0, h - r, w, h);
      UpdateRegion(window, 0, 0, w, -shift.y());
    }
  }
  const std::vector<std::int32_t>& changed = window.ChangedCells();
  if (changed.empty()) {
    return;
  }
  // Tiles holding changed cells; each run of dirty tiles along a tile row is recomputed with a
  // margin of r cells (every cell whose truncated distance can have changed).
  const int tiles_x = (w + kTile - 1) / kTile;
  const int tiles_y = (h + kTile - 1) / kTile;
  dirty_tiles_.assign(static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y), 0);
  for (const std::int32_t index : changed) {
    const int tx = (index % w) / kTile;
    const int ty = (index / w) / kTile;
    dirty_tiles_[static_cast<std::size_t>(ty) * static_cast<std::size_t>(tiles_x) +
                 static_cast<std::size_t>(tx)] = 1;
  }
  const long num_dirty = std::count(dirty_tiles_.begin(), dirty_tiles_.end(), 1);
  if (num_dirty * 3 > static_cast<long>(dirty_tiles_.size())) {
    Rebuild(window);
    return;
  }
  for (int ty = 0; ty < tiles_y; ++ty) {
    int tx = 0;
    while (tx < tiles_x) {
      if (dirty_tiles_[static_cast<std::size_t>(ty) * static_cast<std::size_t>(tiles_x) +
                       static_cast<std::size_t>(tx)] == 0) {
        ++tx;
        continue;
      }
      const int start = tx;
      while (tx < tiles_x && dirty_tiles_[static_cast<std::size_t>(ty) *
                                              static_cast<std::size_t>(tiles_x) +
                                          static_cast<std::size_t>(tx)] != 0) {
        ++tx;
      }
      UpdateRegion(window, std::max(0, start * kTile - r), std::max(0, ty * kTile - r),
                   std::min(w, tx * kTile + r), std::min(h, (ty + 1) * kTile + r));
    }
  }
}

double MatchingField::Interpolate(const Eigen::Vector2d& p, Eigen::Vector2d* gradient) const {
  const Eigen::Vector2d c = limits_.ToCellCoordinates(p);
  const double fx0 = std::floor(c.x());
  const double fy0 = std::floor(c.y());
  const auto i0 = static_cast<int>(fx0);
  const auto j0 = static_cast<int>(fy0);
  const double fx = c.x() - fx0;
  const double fy = c.y() - fy0;
  const double res = limits_.Resolution();
  const int w = limits_.Width();
  const int h = limits_.Height();
  auto value = [&](int i, int j) {
    if (i < 0 || j < 0 || i >= w || j >= h) {
      return max_distance_;
    }
    const float sq = field_.squared[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
                                    static_cast<std::size_t>(i)];
    return std::min(max_distance_, std::sqrt(static_cast<double>(sq)) * res);
  };
  const double v00 = value(i0, j0);
  const double v10 = value(i0 + 1, j0);
  const double v01 = value(i0, j0 + 1);
  const double v11 = value(i0 + 1, j0 + 1);
  if (gradient != nullptr) {
    gradient->x() = ((1.0 - fy) * (v10 - v00) + fy * (v11 - v01)) / res;
    gradient->y() = ((1.0 - fx) * (v01 - v00) + fx * (v11 - v10)) / res;
  }
  return (1.0 - fx) * (1.0 - fy) * v00 + fx * (1.0 - fy) * v10 + (1.0 - fx) * fy * v01 +
         fx * fy * v11;
}

}  // namespace gridslam::scan_matching
