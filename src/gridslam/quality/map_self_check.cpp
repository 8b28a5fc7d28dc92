#include "gridslam/quality/map_self_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gridslam/common/check.hpp"
#include "gridslam/common/parallel.hpp"
#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/grid/log_odds.hpp"
#include "gridslam/grid/scan_points.hpp"
#include "gridslam/quality/local_confirmation.hpp"

namespace gridslam::quality {

double SelfCheckStats::Score() const {
  return confirmed > 0 ? static_cast<double>(confirmed_agreeing) / static_cast<double>(confirmed)
                       : 1.0;
}

double SelfCheckStats::RawScore() const {
  return returns > 0 ? static_cast<double>(agreeing) / static_cast<double>(returns) : 1.0;
}

double SelfCheckStats::LocalScore() const {
  return returns > 0 ? static_cast<double>(confirmed) / static_cast<double>(returns) : 1.0;
}

double SelfCheckStats::Contradiction() const {
  return returns > 0 ? static_cast<double>(contradicting) / static_cast<double>(returns) : 0.0;
}

double SelfCheckStats::MeanDistance() const {
  return returns > 0 ? distance_sum / static_cast<double>(returns) : 0.0;
}

double SelfCheckStats::BandScore(int b) const {
  const auto n = band_returns[static_cast<std::size_t>(b)];
  return n > 0 ? static_cast<double>(band_agreeing[static_cast<std::size_t>(b)]) /
                     static_cast<double>(n)
               : 1.0;
}

int SelfCheckStats::RangeBand(double range) {
  return static_cast<int>(std::upper_bound(kRangeBandEdges.begin(), kRangeBandEdges.end(), range) -
                          kRangeBandEdges.begin());
}

std::string_view ToString(SelfCheckVerdict verdict) {
  switch (verdict) {
    case SelfCheckVerdict::kConsistent:
      return "consistent";
    case SelfCheckVerdict::kContradicted:
      return "contradicted";
    case SelfCheckVerdict::kUnconfirmed:
      return "unconfirmed";
  }
  return "unknown";
}

SelfCheckVerdict SelfCheckStats::Verdict(const SelfCheckOptions& options) const {
  if (Score() < options.suspect_below) {
    return SelfCheckVerdict::kContradicted;
  }
  if (LocalScore() < options.suspect_below) {
    return SelfCheckVerdict::kUnconfirmed;
  }
  return SelfCheckVerdict::kConsistent;
}

bool SelfCheckStats::Suspect(const SelfCheckOptions& options) const {
  return Verdict(options) != SelfCheckVerdict::kConsistent;
}

void SelfCheckStats::Merge(const SelfCheckStats& other) {
  scans += other.scans;
  returns += other.returns;
  agreeing += other.agreeing;
  confirmed += other.confirmed;
  confirmed_agreeing += other.confirmed_agreeing;
  contradicting += other.contradicting;
  outside += other.outside;
  distance_sum += other.distance_sum;
  for (std::size_t b = 0; b < band_returns.size(); ++b) {
    band_returns[b] += other.band_returns[b];
    band_agreeing[b] += other.band_agreeing[b];
  }
}

namespace {

constexpr int kTile = TiledGrid<float>::kTileSize;
constexpr int kTileBits = TiledGrid<float>::kTileBits;
constexpr int kBlockTiles = 4;  ///< Distances are computed in blocks of 4 x 4 tiles.

/// A replayed return inside the map: its cell and what the map says there.
struct Return {
  int i = 0;
  int j = 0;
  int band = 0;              ///< SelfCheckStats::RangeBand of its range.
  bool confirmed = true;     ///< Confirmed by its own stretch of trajectory.
  float to_occupied = 0.0F;  ///< Distance to the nearest occupied cell [m], +inf beyond the clamp.
  float to_not_free = 0.0F;  ///< Distance to the nearest cell that is not free [m], idem.
};

/// Distances [m] from the cells of `block` (a rectangle of cells) to the nearest cell of the map
/// where `source(occupancy)` holds, exact up to `max_cells`, +inf beyond: the distance transform
/// of the block grown by that many cells (no source farther away can be nearer), which is what a
/// transform of the whole map truncated at `max_cells` gives on these cells.
template <class Source>
void BlockDistances(const TiledGrid<float>& log_odds, const fusion::FusionOptions& fusion,
                    Source source, float max_cells, int i0, int j0, int i1, int j1,
                    std::vector<std::uint8_t>& is_source,
                    distance_transform::SquaredDistanceField& field, int* region) {
  const MapLimits& limits = log_odds.Limits();
  const int halo = static_cast<int>(std::ceil(max_cells)) + 1;
  const int ri0 = std::max(0, i0 - halo);
  const int rj0 = std::max(0, j0 - halo);
  const int ri1 = std::min(limits.Width(), i1 + halo);
  const int rj1 = std::min(limits.Height(), j1 + halo);
  const int w = ri1 - ri0;
  const int h = rj1 - rj0;
  const auto occupied = static_cast<float>(ProbabilityToLogOdds(fusion.occupied_probability));
  const auto free = static_cast<float>(ProbabilityToLogOdds(fusion.free_probability));
  is_source.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int j = rj0; j < rj1; ++j) {
    std::uint8_t* row = is_source.data() + static_cast<std::size_t>(j - rj0) * w;
    for (int i = ri0; i < ri1; ++i) {
      const float l = log_odds.Get(i, j);
      const signed char v = l > occupied ? kOccupiedCell : (l < free ? kFreeCell : kUnknownCell);
      row[i - ri0] = source(v) ? 1 : 0;
    }
  }
  distance_transform::SquaredEuclideanDistanceTransform(is_source.data(), w, h, field, false,
                                                        max_cells);
  region[0] = ri0;
  region[1] = rj0;
  region[2] = w;
}

}  // namespace

SelfCheckResult CheckMap(const Grid2D<float>& log_odds, const std::vector<fusion::PosedScan>& scans,
                         const fusion::FusionOptions& fusion, const SelfCheckOptions& options,
                         const std::vector<std::vector<std::uint8_t>>* confirmed) {
  return CheckMap(TiledGrid<float>::FromDense(log_odds, kUnknownLogOdds), scans, fusion, options, 1,
                  confirmed);
}

SelfCheckResult CheckMap(const TiledGrid<float>& log_odds,
                         const std::vector<fusion::PosedScan>& scans,
                         const fusion::FusionOptions& fusion, const SelfCheckOptions& options,
                         int threads, const std::vector<std::vector<std::uint8_t>>* confirmed) {
  SelfCheckResult result;
  const MapLimits& limits = log_odds.Limits();
  result.returns_per_cell = TiledGrid<float>(limits, 0.0F);
  result.disagreeing_per_cell = TiledGrid<float>(limits, 0.0F);
  SelfCheckStats& stats = result.stats;
  // The returns inside the map, in replay order.
  std::vector<Return> returns;
  for (const std::size_t n : ReplayedScans(scans, options)) {
    const fusion::PosedScan& s = scans[n];
    ++stats.scans;
    const ScanReturns points = ExtractScanReturns(*s.scan, s.T_base_laser, options.max_range);
    const std::vector<std::uint8_t>* flags = confirmed != nullptr ? &(*confirmed)[n] : nullptr;
    GRIDSLAM_CHECK(flags == nullptr || flags->size() == points.points.size());
    const PointTransform to_map(s.T_map_base);
    for (std::size_t p = 0; p < points.points.size(); ++p) {
      const Eigen::Vector2d& q = points.points[p];
      const Eigen::Array2i cell = limits.CellIndex(to_map(q));
      if (!limits.Contains(cell)) {
        ++stats.outside;
        continue;
      }
      const bool is_confirmed = flags == nullptr || (*flags)[p] != 0;
      returns.push_back({cell.x(), cell.y(), SelfCheckStats::RangeBand((q - points.origin).norm()),
                         is_confirmed});
      if (is_confirmed) {
        result.returns_per_cell.Mutable(cell) += 1.0F;
      }
    }
  }
  // Distances to the walls, block by block: the returns grouped by block (counting sort).
  const int blocks_x = (limits.Width() + kBlockTiles * kTile - 1) / (kBlockTiles * kTile);
  const int blocks_y = (limits.Height() + kBlockTiles * kTile - 1) / (kBlockTiles * kTile);
  const auto block_of = [&](const Return& r) {
    return static_cast<std::size_t>(r.j >> kTileBits) / kBlockTiles *
               static_cast<std::size_t>(blocks_x) +
           static_cast<std::size_t>(r.i >> kTileBits) / kBlockTiles;
  };
  std::vector<std::size_t> first(static_cast<std::size_t>(blocks_x) * blocks_y + 1, 0);
  for (const Return& r : returns) {
    ++first[block_of(r) + 1];
  }
  for (std::size_t b = 1; b < first.size(); ++b) {
    first[b] += first[b - 1];
  }
  std::vector<std::size_t> order(returns.size());
  {
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t k = 0; k < returns.size(); ++k) {
      order[next[block_of(returns[k])]++] = k;
    }
  }
  const auto resolution = static_cast<float>(limits.Resolution());
  const auto occupied_cells =
      static_cast<float>(options.distance_clamp / limits.Resolution() + 2.0);
  const auto not_free_cells =
      static_cast<float>(options.agreement_distance / limits.Resolution() + 2.0);
  // Blocks with returns, each on its own (`threads` at once): every return gets its distances.
  std::vector<std::size_t> blocks;
  for (std::size_t b = 0; b + 1 < first.size(); ++b) {
    if (first[b] != first[b + 1]) {
      blocks.push_back(b);
    }
  }
  const auto distances = [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint8_t> is_source;
    distance_transform::SquaredDistanceField field;
    for (std::size_t n = begin; n < end; ++n) {
      const std::size_t b = blocks[n];
      const int bx = static_cast<int>(b % static_cast<std::size_t>(blocks_x));
      const int by = static_cast<int>(b / static_cast<std::size_t>(blocks_x));
      const int i0 = bx * kBlockTiles * kTile;
      const int j0 = by * kBlockTiles * kTile;
      const int i1 = std::min(limits.Width(), i0 + kBlockTiles * kTile);
      const int j1 = std::min(limits.Height(), j0 + kBlockTiles * kTile);
      int region[3];
      const auto lookup = [&](float Return::*member) {
        for (std::size_t k = first[b]; k < first[b + 1]; ++k) {
          Return& r = returns[order[k]];
          const float sq = field.squared[static_cast<std::size_t>(r.j - region[1]) * region[2] +
                                         static_cast<std::size_t>(r.i - region[0])];
          r.*member = std::sqrt(sq) * resolution;
        }
      };
      BlockDistances(
          log_odds, fusion, [](signed char v) { return v == kOccupiedCell; }, occupied_cells, i0,
          j0, i1, j1, is_source, field, region);
      lookup(&Return::to_occupied);
      BlockDistances(
          log_odds, fusion, [](signed char v) { return v != kFreeCell; }, not_free_cells, i0, j0,
          i1, j1, is_source, field, region);
      lookup(&Return::to_not_free);
    }
  };
  RunParts(
      blocks.size(), PartCount(blocks.size(), threads),
      [&](std::size_t /*part*/, std::size_t begin, std::size_t end) { distances(begin, end); });
  // Cell-centre distances are multiples of the resolution: a small slack keeps "within 2 cells"
  // exact at agreement_distance = 2 * resolution.
  const double agree = options.agreement_distance + 1e-6;
  for (const Return& r : returns) {
    ++stats.returns;
    ++stats.band_returns[static_cast<std::size_t>(r.band)];
    const double d = r.to_occupied;
    stats.distance_sum += std::min(d, options.distance_clamp);
    stats.confirmed += r.confirmed ? 1 : 0;
    if (d <= agree) {
      ++stats.agreeing;
      ++stats.band_agreeing[static_cast<std::size_t>(r.band)];
      stats.confirmed_agreeing += r.confirmed ? 1 : 0;
    } else if (r.confirmed) {
      result.disagreeing_per_cell.Mutable(r.i, r.j) += 1.0F;
    }
    if (r.to_not_free > agree) {
      ++stats.contradicting;
    }
  }
  return result;
}

}  // namespace gridslam::quality
