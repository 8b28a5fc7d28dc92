#include "gridslam/pipeline/snapshot_fusion.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::pipeline {

void SnapshotFusion::AddKeyMap(int id, const std::vector<fusion::PosedScan>& scans_in_key_frame) {
  if (scans_in_key_frame.empty() || Has(id)) {
    return;
  }
  const Grid2D<float> fused = fusion::FuseScans(scans_in_key_frame, options_);
  // Cropped to the observed cells: placing a key map costs the area of its grid.
  Eigen::Array2i lo(fused.Width(), fused.Height());
  Eigen::Array2i hi(-1, -1);
  for (int j = 0; j < fused.Height(); ++j) {
    for (int i = 0; i < fused.Width(); ++i) {
      if (fused(i, j) != 0.0F) {
        lo = lo.min(Eigen::Array2i(i, j));
        hi = hi.max(Eigen::Array2i(i, j));
      }
    }
  }
  if (hi.x() < lo.x()) {
    return;
  }
  const MapLimits& limits = fused.Limits();
  const MapLimits cropped(limits.Resolution(),
                          limits.Origin() + (lo.cast<double>() * limits.Resolution()).matrix(),
                          hi.x() - lo.x() + 1, hi.y() - lo.y() + 1);
  Grid2D<float> local(cropped, 0.0F);
  for (int j = 0; j < cropped.Height(); ++j) {
    for (int i = 0; i < cropped.Width(); ++i) {
      local(i, j) = fused(lo.x() + i, lo.y() + j);
    }
  }
  local_.emplace(id, std::move(local));
}

void SnapshotFusion::Bounds(int id, const Pose2& T_map_key, Eigen::Vector2d& lo,
                            Eigen::Vector2d& hi) const {
  const MapLimits& limits = local_.at(id).Limits();
  const Eigen::Vector2d o = limits.Origin();
  const Eigen::Vector2d size(limits.Width() * limits.Resolution(),
                             limits.Height() * limits.Resolution());
  for (const Eigen::Vector2d& c :
       {o, Eigen::Vector2d(o.x() + size.x(), o.y()), Eigen::Vector2d(o.x(), o.y() + size.y()),
        Eigen::Vector2d(o + size)}) {
    const Eigen::Vector2d p = T_map_key * c;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

bool SnapshotFusion::Moved(int id, const Pose2& before, const Pose2& after) const {
  // The farthest cell of the key map's grid from its origin moves by about |d theta| * radius.
  const MapLimits& limits = local_.at(id).Limits();
  const Eigen::Vector2d o = limits.Origin();
  const Eigen::Vector2d size(limits.Width() * limits.Resolution(),
                             limits.Height() * limits.Resolution());
  const double radius = std::max(std::max(o.norm(), (o + size).norm()),
                                 std::max(Eigen::Vector2d(o.x() + size.x(), o.y()).norm(),
                                          Eigen::Vector2d(o.x(), o.y() + size.y()).norm()));
  const double tolerance = options_.resolution;
  return (after.translation() - before.translation()).norm() > tolerance ||
         std::abs(Between(before, after).theta()) * radius > tolerance;
}

void SnapshotFusion::Place(Grid2D<float>& grid, int id, const Pose2& T_map_key, float sign) const {
  const Grid2D<float>& local = local_.at(id);
  const MapLimits& g = grid.Limits();
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300);
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-1e300);
  Bounds(id, T_map_key, lo, hi);
  const Eigen::Array2i c0 = g.CellIndex(lo).max(Eigen::Array2i(0, 0));
  const Eigen::Array2i c1 = g.CellIndex(hi).min(Eigen::Array2i(g.Width() - 1, g.Height() - 1));
  const Pose2 T_key_map = T_map_key.Inverse();
  for (int j = c0.y(); j <= c1.y(); ++j) {
    for (int i = c0.x(); i <= c1.x(); ++i) {
      const Eigen::Array2i l = local.Limits().CellIndex(T_key_map * g.CellCenter({i, j}));
      if (local.Limits().Contains(l)) {
        grid(i, j) += sign * local.at(l);
      }
    }
  }
}

const Grid2D<float>& SnapshotFusion::Update(int component, const std::vector<Placed>& key_maps,
                                            UpdateStats& stats) {
  Composite& composite = composites_[component];
  // Bounds of everything to show; a larger grid than the stored one is built from scratch.
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300);
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-1e300);
  for (const Placed& p : key_maps) {
    if (Has(p.id)) {
      Bounds(p.id, p.T_map_key, lo, hi);
    }
  }
  const MapLimits& limits = composite.grid.Limits();
  const double res = options_.resolution;
  const bool fits = limits.NumCells() > 0 && lo.x() >= limits.Origin().x() &&
                    lo.y() >= limits.Origin().y() &&
                    hi.x() <= limits.Origin().x() + limits.Width() * res &&
                    hi.y() <= limits.Origin().y() + limits.Height() * res;
  if (!fits && lo.x() <= hi.x()) {
    // Room to grow: a margin of 10 m around what is there now.
    const double margin = 10.0;
    const Eigen::Vector2d origin = (lo.array() - margin).matrix();
    const Eigen::Vector2d extent = hi - lo + Eigen::Vector2d::Constant(2 * margin);
    composite.grid =
        Grid2D<float>(MapLimits(res, origin, static_cast<int>(std::ceil(extent.x() / res)),
                                static_cast<int>(std::ceil(extent.y() / res))),
                      0.0F);
    composite.placed.clear();
  }
  long added = 0;
  long replaced = 0;
  std::map<int, Pose2> wanted;
  for (const Placed& p : key_maps) {
    if (Has(p.id)) {
      wanted[p.id] = p.T_map_key;
    }
  }
  // Out: key maps no longer wanted (another component now) or moved.
  for (auto it = composite.placed.begin(); it != composite.placed.end();) {
    const auto w = wanted.find(it->first);
    if (w == wanted.end() || Moved(it->first, it->second, w->second)) {
      Place(composite.grid, it->first, it->second, -1.0F);
      replaced += w == wanted.end() ? 0 : 1;
      it = composite.placed.erase(it);
    } else {
      ++it;
    }
  }
  for (const auto& [id, pose] : wanted) {
    if (composite.placed.count(id) == 0) {
      Place(composite.grid, id, pose, 1.0F);
      composite.placed.emplace(id, pose);
      ++added;
    }
  }
  stats.added += added - replaced;
  stats.replaced += replaced;
  return composite.grid;
}

}  // namespace gridslam::pipeline
