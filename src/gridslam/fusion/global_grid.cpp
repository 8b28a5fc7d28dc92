#include "gridslam/fusion/global_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <thread>

#include "gridslam/common/parallel.hpp"
#include "gridslam/grid/log_odds.hpp"
#include "gridslam/grid/ray_casting.hpp"
#include "gridslam/grid/scan_points.hpp"

namespace gridslam::fusion {

Status FusionOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(
      Require(method == "scans" || method == "nearest", "fusion.method is scans or nearest"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(resolution >= 0.005 && resolution <= 10.0, "fusion.resolution in [0.005, 10] m"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(max_range > 0.0 && max_range <= 1000.0, "fusion.max_range in (0, 1000] m"));
  GRIDSLAM_RETURN_IF_ERROR(Require(hit_probability > 0.5 && hit_probability < 1.0,
                                   "fusion.hit_probability in (0.5, 1)"));
  GRIDSLAM_RETURN_IF_ERROR(Require(miss_probability > 0.0 && miss_probability < 0.5,
                                   "fusion.miss_probability in (0, 0.5)"));
  GRIDSLAM_RETURN_IF_ERROR(Require(clamp_probability > 0.5 && clamp_probability < 1.0,
                                   "fusion.clamp_probability in (0.5, 1)"));
  GRIDSLAM_RETURN_IF_ERROR(Require(free_probability < occupied_probability,
                                   "fusion.free_probability < occupied_probability"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(min_motion >= 0.0 && min_rotation >= 0.0, "fusion.min_motion, min_rotation >= 0"));
  return Require(margin >= 0.0 && margin <= 100.0, "fusion.margin in [0, 100] m");
}

namespace {

MapLimits BoundingLimits(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double resolution,
                         double margin) {
  const Eigen::Vector2d origin = lo - Eigen::Vector2d::Constant(margin);
  const Eigen::Vector2d extent = hi - lo + Eigen::Vector2d::Constant(2.0 * margin);
  const double w = std::ceil(extent.x() / resolution);
  const double h = std::ceil(extent.y() / resolution);
  // Checked before anything is allocated: a corrupt pose must not allocate without bound.
  if (!std::isfinite(w) || !std::isfinite(h) || w * h > static_cast<double>(kMaxFusedCells)) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "the fused map would be %.3g x %.3g cells (%.3g m x %.3g m at %g m), more than "
                  "%.3g cells",
                  w, h, extent.x(), extent.y(), resolution, static_cast<double>(kMaxFusedCells));
    throw std::length_error(text);
  }
  const int width = std::max(1, static_cast<int>(w));
  const int height = std::max(1, static_cast<int>(h));
  return {resolution, origin, width, height};
}

}  // namespace

namespace {

/// The scans FuseScans inserts, in the map frame, and their bounding box.
struct PreparedScans {
  struct Scan {
    Eigen::Vector2d origin;
    std::vector<Eigen::Vector2d> points;
  };
  std::vector<Scan> scans;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
};

PreparedScans Prepare(const std::vector<PosedScan>& scans, const FusionOptions& options,
                      int threads = 1) {
  // Select the scans to insert, then their points in the map frame (`threads` at once).
  std::vector<const PosedScan*> selected;
  const Pose2* last = nullptr;
  for (const PosedScan& s : scans) {
    if (s.scan == nullptr) {
      continue;
    }
    if (last != nullptr &&
        (s.T_map_base.translation() - last->translation()).norm() < options.min_motion &&
        std::abs(NormalizeAngle(s.T_map_base.theta() - last->theta())) < options.min_rotation) {
      continue;
    }
    last = &s.T_map_base;
    selected.push_back(&s);
  }
  PreparedScans prepared;
  prepared.scans.resize(selected.size());
  const auto prepare = [&](std::size_t begin, std::size_t end, Eigen::Vector2d& lo,
                           Eigen::Vector2d& hi) {
    for (std::size_t k = begin; k < end; ++k) {
      const PosedScan& s = *selected[k];
      const ScanReturns points = ExtractScanReturns(*s.scan, s.T_base_laser, options.max_range);
      PreparedScans::Scan& p = prepared.scans[k];
      p.origin = s.T_map_base * points.origin;
      p.points.reserve(points.points.size());
      const PointTransform to_map(s.T_map_base);
      for (const auto& q : points.points) {
        p.points.push_back(to_map(q));
      }
      lo = lo.cwiseMin(p.origin);
      hi = hi.cwiseMax(p.origin);
      for (const auto& q : p.points) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
      }
    }
  };
  const std::size_t parts = PartCount(selected.size(), threads);
  std::vector<Eigen::Vector2d> lo(parts, prepared.lo);
  std::vector<Eigen::Vector2d> hi(parts, prepared.hi);
  RunParts(selected.size(), parts, [&](std::size_t part, std::size_t begin, std::size_t end) {
    prepare(begin, end, lo[part], hi[part]);
  });
  for (std::size_t t = 0; t < parts; ++t) {  // min and max: the same in any order
    prepared.lo = prepared.lo.cwiseMin(lo[t]);
    prepared.hi = prepared.hi.cwiseMax(hi[t]);
  }
  return prepared;
}

/// Inserts the prepared scans, in order; `cell(i, j)` returns the log-odds of a cell to update.
template <class Cell>
void InsertPrepared(const PreparedScans& prepared, const MapLimits& limits,
                    const FusionOptions& options, Cell&& cell) {
  const auto hit = static_cast<float>(ProbabilityToLogOdds(options.hit_probability));
  const auto miss = static_cast<float>(ProbabilityToLogOdds(options.miss_probability));
  const auto clamp = static_cast<float>(ProbabilityToLogOdds(options.clamp_probability));
  for (const PreparedScans::Scan& p : prepared.scans) {
    const Eigen::Array2i from = limits.CellIndex(p.origin);
    for (const auto& q : p.points) {
      const Eigen::Array2i to = limits.CellIndex(q);
      TraceLine(from, to, false, [&](int i, int j) {
        float& v = cell(i, j);
        v = std::max(-clamp, v + miss);
      });
      float& v = cell(to.x(), to.y());
      v = std::min(clamp, v + hit);
    }
  }
}

}  // namespace

Grid2D<float> FuseScans(const std::vector<PosedScan>& scans, const FusionOptions& options) {
  const PreparedScans prepared = Prepare(scans, options);
  if (prepared.scans.empty()) {
    return Grid2D<float>(MapLimits(options.resolution, Eigen::Vector2d::Zero(), 1, 1),
                         kUnknownLogOdds);
  }
  Grid2D<float> grid(BoundingLimits(prepared.lo, prepared.hi, options.resolution, options.margin),
                     kUnknownLogOdds);
  InsertPrepared(prepared, grid.Limits(), options,
                 [&](int i, int j) -> float& { return grid(i, j); });
  return grid;
}

namespace {

/// Inserts the prepared scans into the rows [j0, j1) of the grid only, in the order FuseScans
/// inserts them (the same updates of every cell in the same order: the same values); `cell(i, j)`
/// returns the log-odds of a cell to update. Bands of rows inserted at once must not share
/// storage (whole tile rows for a tiled grid).
template <class Cell>
void InsertBand(const PreparedScans& prepared, const MapLimits& limits,
                const FusionOptions& options, int j0, int j1, Cell&& cell) {
  if (j0 <= 0 && j1 >= limits.Height()) {
    InsertPrepared(prepared, limits, options, cell);
    return;
  }
  const auto hit = static_cast<float>(ProbabilityToLogOdds(options.hit_probability));
  const auto miss = static_cast<float>(ProbabilityToLogOdds(options.miss_probability));
  const auto clamp = static_cast<float>(ProbabilityToLogOdds(options.clamp_probability));
  for (const PreparedScans::Scan& p : prepared.scans) {
    const Eigen::Array2i from = limits.CellIndex(p.origin);
    for (const auto& q : p.points) {
      const Eigen::Array2i to = limits.CellIndex(q);
      if (std::max(from.y(), to.y()) < j0 || std::min(from.y(), to.y()) >= j1) {
        continue;  // the ray stays out of the band
      }
      // TraceLine(from, to, false, ...) restricted to the band: the same cells in the same order.
      int x = from.x();
      int y = from.y();
      const int dx = std::abs(to.x() - x);
      const int dy = -std::abs(to.y() - y);
      const int sx = x < to.x() ? 1 : -1;
      const int sy = y < to.y() ? 1 : -1;
      int err = dx + dy;
      while (x != to.x() || y != to.y()) {
        if (y >= j0 && y < j1) {
          float& v = cell(x, y);
          v = std::max(-clamp, v + miss);
        } else if ((sy > 0 && y >= j1) || (sy < 0 && y < j0)) {
          break;  // past the band, and moving away
        }
        const int e2 = 2 * err;
        if (e2 >= dy) {
          err += dy;
          x += sx;
        }
        if (e2 <= dx) {
          err += dx;
          y += sy;
        }
      }
      if (to.y() >= j0 && to.y() < j1) {
        float& v = cell(to.x(), to.y());
        v = std::min(clamp, v + hit);
      }
    }
  }
}

/// Row bands of about as many returns each, at multiples of `granule` rows; `bands` + 1 edges.
std::vector<int> BandEdges(const PreparedScans& prepared, const MapLimits& limits, int bands,
                           int granule) {
  const int granules = (limits.Height() + granule - 1) / granule;
  std::vector<long> per_granule(static_cast<std::size_t>(granules), 0);
  long returns = 0;
  for (const PreparedScans::Scan& p : prepared.scans) {
    for (const auto& q : p.points) {
      ++per_granule[static_cast<std::size_t>(limits.CellIndex(q).y() / granule)];
      ++returns;
    }
  }
  std::vector<int> edges = {0};
  long seen = 0;
  for (int g = 0; g < granules && static_cast<int>(edges.size()) < bands; ++g) {
    seen += per_granule[static_cast<std::size_t>(g)];
    if (seen * bands >= returns * static_cast<long>(edges.size())) {
      edges.push_back(std::min(limits.Height(), (g + 1) * granule));
    }
  }
  edges.push_back(limits.Height());
  return edges;
}

/// Runs band(j0, j1) for the bands between consecutive `edges`, the first on this thread.
template <class Band>
void RunBands(const std::vector<int>& edges, Band&& band) {
  std::vector<std::thread> workers;
  for (std::size_t b = 1; b + 1 < edges.size(); ++b) {
    if (edges[b] < edges[b + 1]) {
      workers.emplace_back([&, b] { band(edges[b], edges[b + 1]); });
    }
  }
  band(edges[0], edges[1]);
  for (std::thread& w : workers) {
    w.join();
  }
}

}  // namespace

namespace {

/// FuseScansTiled of scans already prepared (Prepare does not depend on the resolution).
TiledGrid<float> FusePrepared(const PreparedScans& prepared, const FusionOptions& options,
                              int threads, long dense_cells) {
  if (prepared.scans.empty()) {
    return TiledGrid<float>(MapLimits(options.resolution, Eigen::Vector2d::Zero(), 1, 1),
                            kUnknownLogOdds);
  }
  const MapLimits limits =
      BoundingLimits(prepared.lo, prepared.hi, options.resolution, options.margin);
  constexpr int kTile = TiledGrid<float>::kTileSize;
  if (limits.NumCells() <= dense_cells) {
    // Small enough to fuse densely (faster per cell), then keep the written tiles.
    Grid2D<float> dense(limits, kUnknownLogOdds);
    const int w = limits.Width();
    float* cells = dense.data();
    RunBands(BandEdges(prepared, limits, std::max(1, threads), 1), [&](int j0, int j1) {
      InsertBand(prepared, limits, options, j0, j1, [&](int i, int j) -> float& {
        return cells[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
                     static_cast<std::size_t>(i)];
      });
    });
    TiledGrid<float> grid(limits, kUnknownLogOdds);
    for (int tj = 0; tj < grid.TilesY(); ++tj) {
      for (int ti = 0; ti < grid.TilesX(); ++ti) {
        const int i0 = ti * kTile;
        const int j0 = tj * kTile;
        const int i1 = std::min(limits.Width(), i0 + kTile);
        const int j1 = std::min(limits.Height(), j0 + kTile);
        bool written = false;
        for (int j = j0; j < j1 && !written; ++j) {
          written = std::any_of(&dense(i0, j), &dense(i0, j) + (i1 - i0),
                                [](float v) { return v != kUnknownLogOdds; });
        }
        if (written) {
          float* tile = grid.MutableTile(ti, tj);
          for (int j = j0; j < j1; ++j) {
            std::copy(&dense(i0, j), &dense(i0, j) + (i1 - i0), tile + (j - j0) * kTile);
          }
        }
      }
    }
    return grid;
  }
  TiledGrid<float> grid(limits, kUnknownLogOdds);
  RunBands(BandEdges(prepared, limits, std::clamp(threads, 1, grid.TilesY()), kTile),
           [&](int j0, int j1) {
             // The tile of the last cell: consecutive cells of a ray mostly share one.
             constexpr int kBits = TiledGrid<float>::kTileBits;
             int tile_i = -1;
             int tile_j = -1;
             float* tile = nullptr;
             InsertBand(prepared, limits, options, j0, j1, [&](int i, int j) -> float& {
               if ((i >> kBits) != tile_i || (j >> kBits) != tile_j) {
                 tile_i = i >> kBits;
                 tile_j = j >> kBits;
                 tile = grid.MutableTile(tile_i, tile_j);
               }
               return tile[TiledGrid<float>::InTile(i, j)];
             });
           });
  return grid;
}

}  // namespace

TiledGrid<float> FuseScansTiled(const std::vector<PosedScan>& scans, const FusionOptions& options,
                                int threads, long dense_cells) {
  return FusePrepared(Prepare(scans, options, threads), options, threads, dense_cells);
}

TiledGrid<float> FuseScansFitting(const std::vector<PosedScan>& scans, FusionOptions options,
                                  int threads) {
  constexpr double kCoarsest = 10.0;  // FusionOptions::Validate's bound [m]
  const PreparedScans prepared = Prepare(scans, options, threads);
  for (;;) {
    try {
      return FusePrepared(prepared, options, threads, kDenseFusionCells);
    } catch (const std::length_error&) {
      if (options.resolution * 2.0 > kCoarsest) {
        throw;
      }
      options.resolution *= 2.0;
    }
  }
}

Grid2D<float> FuseNearestKeyMap(const std::vector<PosedKeyMap>& key_maps,
                                const FusionOptions& options) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for (const PosedKeyMap& k : key_maps) {
    const MapLimits& l = k.key_map->log_odds.Limits();
    const Eigen::Vector2d size(l.Width() * l.Resolution(), l.Height() * l.Resolution());
    const std::array<Eigen::Vector2d, 4> corners = {
        l.Origin(), l.Origin() + Eigen::Vector2d(size.x(), 0.0),
        l.Origin() + Eigen::Vector2d(0.0, size.y()), l.Origin() + size};
    for (const Eigen::Vector2d& corner : corners) {
      const Eigen::Vector2d c = k.T_map_key * corner;
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
  }
  if (key_maps.empty()) {
    return Grid2D<float>(MapLimits(options.resolution, Eigen::Vector2d::Zero(), 1, 1),
                         kUnknownLogOdds);
  }
  Grid2D<float> grid(BoundingLimits(lo, hi, options.resolution, 0.0), kUnknownLogOdds);
  const MapLimits& limits = grid.Limits();
  std::vector<Pose2> T_key_map;
  for (const PosedKeyMap& k : key_maps) {
    T_key_map.push_back(k.T_map_key.Inverse());
  }
  for (int j = 0; j < limits.Height(); ++j) {
    for (int i = 0; i < limits.Width(); ++i) {
      const Eigen::Vector2d p = limits.CellCenter({i, j});
      double best = std::numeric_limits<double>::max();
      float value = kUnknownLogOdds;
      for (std::size_t k = 0; k < key_maps.size(); ++k) {
        const double d = (key_maps[k].T_map_key.translation() - p).squaredNorm();
        if (d >= best) {
          continue;
        }
        const Grid2D<float>& local = key_maps[k].key_map->log_odds;
        const Eigen::Array2i cell = local.Limits().CellIndex(T_key_map[k] * p);
        if (local.Limits().Contains(cell) && local.at(cell) != kUnknownLogOdds) {
          best = d;
          value = local.at(cell);
        }
      }
      grid(i, j) = value;
    }
  }
  return grid;
}

OccupancyImage ToOccupancy(const TiledGrid<float>& log_odds, const FusionOptions& options) {
  const auto occupied = static_cast<float>(ProbabilityToLogOdds(options.occupied_probability));
  const auto free = static_cast<float>(ProbabilityToLogOdds(options.free_probability));
  const auto value = [&](float l) {
    return l > occupied ? kOccupiedCell : (l < free ? kFreeCell : kUnknownCell);
  };
  const MapLimits& limits = log_odds.Limits();
  OccupancyImage image(limits, value(log_odds.Fill()));
  constexpr int kSize = TiledGrid<float>::kTileSize;
  for (int tj = 0; tj < log_odds.TilesY(); ++tj) {
    for (int ti = 0; ti < log_odds.TilesX(); ++ti) {
      const float* tile = log_odds.Tile(ti, tj);
      if (tile == nullptr) {
        continue;
      }
      const int i0 = ti * kSize;
      const int j0 = tj * kSize;
      const int i1 = std::min(limits.Width(), i0 + kSize);
      const int j1 = std::min(limits.Height(), j0 + kSize);
      for (int j = j0; j < j1; ++j) {
        const float* row = tile + (j - j0) * kSize;
        for (int i = i0; i < i1; ++i) {
          image(i, j) = value(row[i - i0]);
        }
      }
    }
  }
  return image;
}

OccupancyImage ToOccupancy(const Grid2D<float>& log_odds, const FusionOptions& options) {
  OccupancyImage image(log_odds.Limits(), kUnknownCell);
  const auto occupied = static_cast<float>(ProbabilityToLogOdds(options.occupied_probability));
  const auto free = static_cast<float>(ProbabilityToLogOdds(options.free_probability));
  for (std::size_t k = 0; k < log_odds.size(); ++k) {
    const float l = log_odds.data()[k];
    image.data()[k] = l > occupied ? kOccupiedCell : (l < free ? kFreeCell : kUnknownCell);
  }
  return image;
}

}  // namespace gridslam::fusion
