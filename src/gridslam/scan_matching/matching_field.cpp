#include "gridslam/scan_matching/matching_field.hpp"

#include <algorithm>
#include <cmath>

#include "gridslam/grid/cell_shift.hpp"

namespace gridslam::scan_matching {
namespace {

// Moves a row-major field by (di, dj) cells in place (new (i, j) = old (i + di, j + dj)); labels
// are re-indexed by the constant offset of the shift. A label whose obstacle left the grid then
// names a wrong cell, but such a cell lies within the truncation radius of the edge the obstacles
// left by, which Update() recomputes right after, as it does the cells that entered.
void ShiftField(distance_transform::SquaredDistanceField& field, std::vector<float>& distance,
                float max_distance, int di, int dj) {
  const int w = field.width;
  const int h = field.height;
  ShiftCellsInPlace(field.squared, w, h, di, dj, distance_transform::kInfinity);
  ShiftCellsInPlace(field.nearest, w, h, di, dj, std::int32_t{-1});
  ShiftCellsInPlace(distance, w, h, di, dj, max_distance);
  const std::int32_t offset = dj * w + di;
  for (std::int32_t& label : field.nearest) {
    label = label < 0 ? label : label - offset;
  }
}

}  // namespace

void MatchingField::SetLimits(const MapLimits& limits) {
  limits_ = limits;
  origin_x_ = limits.Origin().x();
  origin_y_ = limits.Origin().y();
  inv_resolution_ = 1.0 / limits.Resolution();
}

void MatchingField::Rebuild(const RollingWindow& window) {
  SetLimits(window.Limits());
  const auto max_cells = static_cast<float>(max_distance_ / limits_.Resolution());
  distance_transform::SquaredEuclideanDistanceTransform(window.Obstacles().data(), limits_.Width(),
                                                        limits_.Height(), field_, true, max_cells);
  distance_.resize(field_.squared.size());
  const auto res = static_cast<float>(limits_.Resolution());
  const auto max_d = static_cast<float>(max_distance_);
  for (std::size_t k = 0; k < distance_.size(); ++k) {
    distance_[k] = std::min(max_d, std::sqrt(field_.squared[k]) * res);
  }
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
    std::copy(
        obstacles + static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + si0,
        obstacles + static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + si1,
        scratch_sources_.data() + static_cast<std::size_t>(j - sj0) * static_cast<std::size_t>(sw));
  }
  const auto max_cells = static_cast<float>(max_distance_ / limits_.Resolution());
  distance_transform::SquaredEuclideanDistanceTransform(scratch_sources_.data(), sw, sh,
                                                        scratch_field_, true, max_cells);
  const auto res = static_cast<float>(limits_.Resolution());
  const auto max_d = static_cast<float>(max_distance_);
  for (int j = j0; j < j1; ++j) {
    for (int i = i0; i < i1; ++i) {
      const std::size_t local = static_cast<std::size_t>(j - sj0) * static_cast<std::size_t>(sw) +
                                static_cast<std::size_t>(i - si0);
      const std::size_t global =
          static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i);
      const std::int32_t label = scratch_field_.nearest[local];
      field_.squared[global] = scratch_field_.squared[local];
      distance_[global] = std::min(max_d, std::sqrt(scratch_field_.squared[local]) * res);
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
    ShiftField(field_, distance_, static_cast<float>(max_distance_), shift.x(), shift.y());
    SetLimits(limits);
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
  if (changed.size() > static_cast<std::size_t>(w) * static_cast<std::size_t>(h) / 64) {
    Rebuild(window);
    return;
  }
  // Removed obstacles: the cells within r of one may have lost their nearest obstacle, so the box
  // of radius r around it is recomputed exactly (from the sources within 2r) unless an earlier box
  // of this update already covered it. This also settles every change inside those boxes.
  const std::uint8_t* obstacles = window.Obstacles().data();
  done_boxes_.clear();
  for (const std::int32_t index : changed) {
    if (obstacles[index] != 0) {
      continue;
    }
    const int i = index % w;
    const int j = index / w;
    const int i0 = std::max(0, i - r);
    const int j0 = std::max(0, j - r);
    const int i1 = std::min(w, i + r + 1);
    const int j1 = std::min(h, j + r + 1);
    bool covered = false;
    for (const Eigen::Array4i& box : done_boxes_) {
      if (box[0] <= i0 && box[1] <= j0 && box[2] >= i1 && box[3] >= j1) {
        covered = true;
        break;
      }
    }
    if (!covered) {
      // Grow the box a little so that neighbouring removals fall inside it.
      const int g = r / 2;
      const Eigen::Array4i box(std::max(0, i0 - g), std::max(0, j0 - g), std::min(w, i1 + g),
                               std::min(h, j1 + g));
      UpdateRegion(window, box[0], box[1], box[2], box[3]);
      done_boxes_.push_back(box);
    }
  }
  // Added obstacles: a brushfire stamp, d^2 = min(d^2, |cell - obstacle|^2) within the disk of
  // radius r (the truncation radius in cells).
  const float max_squared =
      static_cast<float>(max_distance_ * max_distance_ * inv_resolution_ * inv_resolution_);
  const auto res = static_cast<float>(limits_.Resolution());
  for (const std::int32_t index : changed) {
    if (obstacles[index] == 0) {
      continue;
    }
    const int i = index % w;
    const int j = index / w;
    for (int dj = std::max(-r, -j); dj <= std::min(r, h - 1 - j); ++dj) {
      for (int di = std::max(-r, -i); di <= std::min(r, w - 1 - i); ++di) {
        const auto sq = static_cast<float>(di * di + dj * dj);
        if (sq > max_squared) {
          continue;
        }
        const std::size_t cell = static_cast<std::size_t>(j + dj) * static_cast<std::size_t>(w) +
                                 static_cast<std::size_t>(i + di);
        if (sq < field_.squared[cell]) {
          field_.squared[cell] = sq;
          field_.nearest[cell] = index;
          distance_[cell] = std::sqrt(sq) * res;
        }
      }
    }
  }
}

}  // namespace gridslam::scan_matching
