#include "gridslam/scan_matching/matching_field.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::scan_matching {

void MatchingField::SetLimits(const MapLimits& limits, const RingLayout& layout) {
  limits_ = limits;
  layout_ = layout;
  origin_x_ = limits.Origin().x();
  origin_y_ = limits.Origin().y();
  inv_resolution_ = 1.0 / limits.Resolution();
}

void MatchingField::Rebuild(const RollingWindow& window) {
  SetLimits(window.Limits(), window.Layout());
  const int w = limits_.Width();
  const int h = limits_.Height();
  // The transform runs on the obstacles in logical order, straight into the field; the field is
  // then rotated in place into the storage order (no second full-size field: this is rare).
  scratch_sources_.resize(static_cast<std::size_t>(limits_.NumCells()));
  window.Obstacles().CopyRegion(0, 0, w, h, scratch_sources_.data());
  const auto max_cells = static_cast<float>(max_distance_ / limits_.Resolution());
  distance_transform::SquaredEuclideanDistanceTransform(scratch_sources_.data(), w, h, field_, true,
                                                        max_cells);
  const auto res = static_cast<float>(limits_.Resolution());
  const auto max_d = static_cast<float>(max_distance_);
  distance_.resize(field_.squared.size());
  for (std::size_t k = 0; k < distance_.size(); ++k) {
    distance_[k] = std::min(max_d, std::sqrt(field_.squared[k]) * res);
    const std::int32_t label = field_.nearest[k];
    field_.nearest[k] =
        label < 0 ? -1 : static_cast<std::int32_t>(layout_.Index(label % w, label / w));
  }
  RotateIntoStorage(field_.squared);
  RotateIntoStorage(field_.nearest);
  RotateIntoStorage(distance_);
  valid_ = true;
  ++num_rebuilds_;
}

template <typename T>
void MatchingField::RotateIntoStorage(std::vector<T>& cells) const {
  // Logical column i goes to storage column (i + offset_x) mod w, row j to (j + offset_y) mod h.
  const auto w = static_cast<std::ptrdiff_t>(limits_.Width());
  const auto h = static_cast<std::ptrdiff_t>(limits_.Height());
  const std::ptrdiff_t ox = layout_.OffsetX();
  const std::ptrdiff_t oy = layout_.OffsetY();
  if (ox != 0) {
    for (std::ptrdiff_t j = 0; j < h; ++j) {
      const auto row = cells.begin() + j * w;
      std::rotate(row, row + (w - ox), row + w);
    }
  }
  if (oy != 0) {
    std::rotate(cells.begin(), cells.begin() + (h - oy) * w, cells.end());
  }
}

void MatchingField::UpdateRegion(const RollingWindow& window, int i0, int j0, int i1, int j1) {
  if (i0 >= i1 || j0 >= j1) {
    return;
  }
  // Sources within the truncation radius of the region; outside them nothing can be nearer. They
  // are copied out in logical order: the transform must not see the storage's wrap-around.
  const int w = limits_.Width();
  const int h = limits_.Height();
  const int r = static_cast<int>(std::ceil(max_distance_ / limits_.Resolution()));
  const int si0 = std::max(0, i0 - r);
  const int sj0 = std::max(0, j0 - r);
  const int si1 = std::min(w, i1 + r);
  const int sj1 = std::min(h, j1 + r);
  const int sw = si1 - si0;
  const int sh = sj1 - sj0;
  scratch_sources_.resize(static_cast<std::size_t>(sw) * static_cast<std::size_t>(sh));
  window.Obstacles().CopyRegion(si0, sj0, si1, sj1, scratch_sources_.data());
  const auto max_cells = static_cast<float>(max_distance_ / limits_.Resolution());
  // Only the region's rows of the transform: the rows above and below only hold sources.
  distance_transform::SquaredEuclideanDistanceTransformRows(
      scratch_sources_.data(), sw, sh, j0 - sj0, j1 - sj0, scratch_field_, true, max_cells);
  const auto res = static_cast<float>(limits_.Resolution());
  const auto max_d = static_cast<float>(max_distance_);
  for (int j = j0; j < j1; ++j) {
    const std::size_t row = static_cast<std::size_t>(layout_.Row(j)) * static_cast<std::size_t>(w);
    int column = layout_.Column(i0);
    for (int i = i0; i < i1; ++i) {
      const std::size_t local = static_cast<std::size_t>(j - j0) * static_cast<std::size_t>(sw) +
                                static_cast<std::size_t>(i - si0);
      const std::size_t global = row + static_cast<std::size_t>(column);
      column = column + 1 == w ? 0 : column + 1;
      const std::int32_t label = scratch_field_.nearest[local];
      field_.squared[global] = scratch_field_.squared[local];
      distance_[global] = std::min(max_d, std::sqrt(scratch_field_.squared[local]) * res);
      field_.nearest[global] =
          label < 0 ? -1
                    : static_cast<std::int32_t>(layout_.Index(si0 + label % sw, sj0 + label / sw));
    }
  }
  ++num_tile_updates_;
}

void MatchingField::Update(const RollingWindow& window) {
  const MapLimits& limits = window.Limits();
  const Eigen::Array2i shift = window.PendingShift();
  const int w = limits.Width();
  const int h = limits.Height();
  if (!valid_ || window.ChangesOverflow() || window.ShiftReversed() || w != limits_.Width() ||
      h != limits_.Height() || std::abs(shift.x()) >= w / 2 || std::abs(shift.y()) >= h / 2) {
    Rebuild(window);
    return;
  }
  const int r = static_cast<int>(std::ceil(max_distance_ / limits.Resolution()));
  if ((shift != 0).any()) {
    // The window's storage did not move, nor does the field's: the view rotates with the
    // window's. Labels are storage indices and need no re-indexing. A label whose obstacle left
    // names the entering cell that took its storage, but such a cell lies within the truncation
    // radius of the edge the obstacles left by, recomputed below with the cells that entered
    // (which hold what the leaving cells held).
    RingLayout layout = layout_;
    layout.Shift(shift.x(), shift.y());
    if (!(layout == window.Layout())) {  // not the window this field followed
      Rebuild(window);
      return;
    }
    SetLimits(limits, layout);
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
    const Eigen::Array2i c = layout_.Cell(static_cast<std::size_t>(index));
    const int i = c.x();
    const int j = c.y();
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
    const Eigen::Array2i c = layout_.Cell(static_cast<std::size_t>(index));
    const int i = c.x();
    const int j = c.y();
    const int di0 = std::max(-r, -i);
    for (int dj = std::max(-r, -j); dj <= std::min(r, h - 1 - j); ++dj) {
      const std::size_t row =
          static_cast<std::size_t>(layout_.Row(j + dj)) * static_cast<std::size_t>(w);
      int column = layout_.Column(i + di0);
      for (int di = di0; di <= std::min(r, w - 1 - i);
           ++di, column = column + 1 == w ? 0 : column + 1) {
        const auto sq = static_cast<float>(di * di + dj * dj);
        if (sq > max_squared) {
          continue;
        }
        const std::size_t cell = row + static_cast<std::size_t>(column);
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
