#include "app_align_map.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace gridslam::app {

namespace {

/// Sharpness of the projections of `points` on the axes rotated by -angle: the sum of squared
/// counts of `bin`-wide bins along x and along y. Walls along the axes pile their cells into few
/// bins, so the sharpness peaks where the dominant walls are axis-aligned.
double ProjectionSharpness(const std::vector<Eigen::Vector2d>& points, double angle, double bin) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  std::unordered_map<long, int> xs;
  std::unordered_map<long, int> ys;
  for (const Eigen::Vector2d& p : points) {
    ++xs[std::lround(std::floor((c * p.x() + s * p.y()) / bin))];
    ++ys[std::lround(std::floor((-s * p.x() + c * p.y()) / bin))];
  }
  double sum = 0.0;
  for (const auto* counts : {&xs, &ys}) {
    for (const auto& [key, n] : *counts) {
      sum += static_cast<double>(n) * n;
    }
  }
  return sum;
}

}  // namespace

double DominantWallAngle(const TiledGrid<float>& log_odds, float occupied_log_odds) {
  std::vector<Eigen::Vector2d> points;
  const MapLimits& limits = log_odds.Limits();
  for (int j = 0; j < log_odds.Height(); ++j) {
    for (int i = 0; i < log_odds.Width(); ++i) {
      if (log_odds.Get(i, j) > occupied_log_odds) {
        points.push_back(limits.CellCenter(Eigen::Array2i(i, j)));
      }
    }
  }
  if (points.size() < 10) {
    return 0.0;
  }
  const double bin = limits.Resolution();
  // Coarse search over [-45, 45) degrees in 1-degree steps, then 0.05 degrees around the best.
  const double degree = M_PI / 180.0;
  double best_angle = 0.0;
  double best = -1.0;
  for (int k = -45; k < 45; ++k) {
    if (const double v = ProjectionSharpness(points, k * degree, bin); v > best) {
      best = v;
      best_angle = k * degree;
    }
  }
  const double coarse = best_angle;
  for (int k = -20; k <= 20; ++k) {
    const double angle = coarse + k * 0.05 * degree;
    if (const double v = ProjectionSharpness(points, angle, bin); v > best) {
      best = v;
      best_angle = angle;
    }
  }
  // Folded into [-pi/4, pi/4): walls at angle and angle + 90 degrees are the same directions.
  double angle = std::remainder(best_angle, M_PI / 2.0);
  if (angle >= M_PI / 4.0) {
    angle -= M_PI / 2.0;
  }
  return angle;
}

void RotateMapFrame(pipeline::MapperResult& result, int component, double angle, double margin) {
  const Pose2 T_new_old(0.0, 0.0, -angle);
  for (std::size_t r = 0; r < result.trajectories.size(); ++r) {
    if (result.component_of_robot[r] != component) {
      continue;
    }
    for (pipeline::TrajectoryPose& p : result.trajectories[r]) {
      p.T_map_base = T_new_old * p.T_map_base;
    }
  }
  for (int k = 0; k < static_cast<int>(result.graph.vertices().size()); ++k) {
    const auto& v = result.graph.vertex(k);
    const int robot = result.vertex_robot[static_cast<std::size_t>(v.id)];
    if (result.component_of_robot[static_cast<std::size_t>(robot)] == component) {
      result.graph.SetPose(k, T_new_old * v.T_map_v);
    }
  }
  TiledGrid<float>& old_map = result.maps[static_cast<std::size_t>(component)];
  const MapLimits& old_limits = old_map.Limits();
  const double res = old_limits.Resolution();
  // Bounding box of the rotated map.
  Eigen::Vector2d lo(1e300, 1e300);
  Eigen::Vector2d hi(-1e300, -1e300);
  for (const int i : {0, old_limits.Width()}) {
    for (const int j : {0, old_limits.Height()}) {
      const Eigen::Vector2d corner =
          T_new_old * (old_limits.Origin() + res * Eigen::Vector2d(i, j));
      lo = lo.cwiseMin(corner);
      hi = hi.cwiseMax(corner);
    }
  }
  const MapLimits limits(res, lo, static_cast<int>(std::ceil((hi.x() - lo.x()) / res)),
                         static_cast<int>(std::ceil((hi.y() - lo.y()) / res)));
  TiledGrid<float> map(limits, 0.0F);  // log-odds 0: unknown
  const Pose2 T_old_new = T_new_old.Inverse();
  constexpr int kSize = TiledGrid<float>::kTileSize;
  // Whether the old map has any written tile under the rotated footprint of a new tile (its
  // corners' bounding box, one tile of slack): the others read unknown cells only.
  const auto footprint_written = [&](int i0, int j0, int i1, int j1) {
    int ti0 = old_map.TilesX();
    int tj0 = old_map.TilesY();
    int ti1 = -1;
    int tj1 = -1;
    for (const int i : {i0, i1}) {
      for (const int j : {j0, j1}) {
        const Eigen::Array2i c =
            old_limits.CellIndex(T_old_new * limits.CellCenter(Eigen::Array2i(i, j)));
        ti0 = std::min(ti0, (c.x() >> TiledGrid<float>::kTileBits) - 1);
        tj0 = std::min(tj0, (c.y() >> TiledGrid<float>::kTileBits) - 1);
        ti1 = std::max(ti1, (c.x() >> TiledGrid<float>::kTileBits) + 1);
        tj1 = std::max(tj1, (c.y() >> TiledGrid<float>::kTileBits) + 1);
      }
    }
    for (int tj = std::max(0, tj0); tj <= std::min(old_map.TilesY() - 1, tj1); ++tj) {
      for (int ti = std::max(0, ti0); ti <= std::min(old_map.TilesX() - 1, ti1); ++ti) {
        if (old_map.Tile(ti, tj) != nullptr) {
          return true;
        }
      }
    }
    return false;
  };
  for (int tj = 0; tj < map.TilesY(); ++tj) {
    for (int ti = 0; ti < map.TilesX(); ++ti) {
      const int i0 = ti * kSize;
      const int j0 = tj * kSize;
      const int i1 = std::min(limits.Width(), i0 + kSize);
      const int j1 = std::min(limits.Height(), j0 + kSize);
      if (!footprint_written(i0, j0, i1 - 1, j1 - 1)) {
        continue;
      }
      for (int j = j0; j < j1; ++j) {
        for (int i = i0; i < i1; ++i) {
          const Eigen::Array2i cell =
              old_limits.CellIndex(T_old_new * limits.CellCenter(Eigen::Array2i(i, j)));
          if (old_limits.Contains(cell)) {
            if (const float v = old_map.Get(cell); v != 0.0F) {
              map.Mutable(i, j) = v;
            }
          }
        }
      }
    }
  }
  // Crop to the observed cells plus the fusion margin's worth of cells (a rotated rectangle's
  // bounding box is mostly unknown).
  int i0 = limits.Width();
  int j0 = limits.Height();
  int i1 = -1;
  int j1 = -1;
  for (int tj = 0; tj < map.TilesY(); ++tj) {
    for (int ti = 0; ti < map.TilesX(); ++ti) {
      const float* tile = map.Tile(ti, tj);
      if (tile == nullptr) {
        continue;
      }
      for (int k = 0; k < TiledGrid<float>::kTileCells; ++k) {
        if (tile[k] != 0.0F) {
          const int i = ti * kSize + (k & (kSize - 1));
          const int j = tj * kSize + (k >> TiledGrid<float>::kTileBits);
          i0 = std::min(i0, i);
          i1 = std::max(i1, i);
          j0 = std::min(j0, j);
          j1 = std::max(j1, j);
        }
      }
    }
  }
  if (i1 < 0) {
    old_map = std::move(map);
    return;
  }
  const int pad = static_cast<int>(std::lround(margin / res));
  i0 = std::max(0, i0 - pad);
  j0 = std::max(0, j0 - pad);
  i1 = std::min(limits.Width() - 1, i1 + pad);
  j1 = std::min(limits.Height() - 1, j1 + pad);
  const MapLimits cropped(res, limits.Origin() + res * Eigen::Vector2d(i0, j0), i1 - i0 + 1,
                          j1 - j0 + 1);
  TiledGrid<float> out(cropped, 0.0F);
  for (int tj = 0; tj < map.TilesY(); ++tj) {
    for (int ti = 0; ti < map.TilesX(); ++ti) {
      const float* tile = map.Tile(ti, tj);
      if (tile == nullptr) {
        continue;
      }
      for (int k = 0; k < TiledGrid<float>::kTileCells; ++k) {
        const int i = ti * kSize + (k & (kSize - 1));
        const int j = tj * kSize + (k >> TiledGrid<float>::kTileBits);
        if (tile[k] != 0.0F && i >= i0 && i <= i1 && j >= j0 && j <= j1) {
          out.Mutable(i - i0, j - j0) = tile[k];
        }
      }
    }
  }
  old_map = std::move(out);
}

}  // namespace gridslam::app
