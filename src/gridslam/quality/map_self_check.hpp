// The map self-check (docs/self_check.md; issue 16 part 3): how consistent a finished map is with
// the scans it was built from, without ground truth. A sample of the scans is replayed at their
// final corrected poses against the final fused occupancy map: a return agrees when an occupied
// cell lies within `agreement_distance` of it, and contradicts the map when the map holds free
// space all around it. A misaligned trajectory draws the same wall twice; the later pass clears
// the earlier copy (or both blur below the occupied threshold), so the earlier pass's returns
// stop agreeing. The score is the share of agreeing returns (1 = every return lies on a wall of
// the map). This is the grid form of the ray-consistency idea of Mazuran et al., "A Statistical
// Measure for Map Consistency in SLAM", ICRA 2014.
#pragma once

#include <array>
#include <vector>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/tiled_grid.hpp"
#include "gridslam/quality/self_check_options.hpp"

namespace gridslam::quality {

/// Counts and shares of one map (or of several, merged).
struct SelfCheckStats {
  long scans = 0;             ///< Scans replayed.
  long returns = 0;           ///< Their returns inside the map.
  long agreeing = 0;          ///< Returns within agreement_distance of an occupied cell.
  long contradicting = 0;     ///< Returns with only free cells within agreement_distance.
  long outside = 0;           ///< Returns outside the map's limits (not counted in `returns`).
  double distance_sum = 0.0;  ///< Sum of the clamped distances to the nearest occupied cell [m].
  /// Returns and agreeing returns by range band (kRangeBands: up to 5, 10, 20 m and beyond): a
  /// diagnostic of where in the scans the disagreement lies (report.json quality.by_range).
  static constexpr std::array<double, 3> kRangeBandEdges = {5.0, 10.0, 20.0};
  static constexpr int kRangeBands = static_cast<int>(kRangeBandEdges.size()) + 1;
  std::array<long, kRangeBands> band_returns{};
  std::array<long, kRangeBands> band_agreeing{};

  /// Share of agreeing returns, 1 when there is no return [-].
  [[nodiscard]] double Score() const;
  /// Share of contradicting returns [-].
  [[nodiscard]] double Contradiction() const;
  /// Mean clamped distance of a return to the nearest occupied cell [m].
  [[nodiscard]] double MeanDistance() const;
  /// Share of agreeing returns in range band `b`, 1 when it has none [-].
  [[nodiscard]] double BandScore(int b) const;
  /// The band of a return at `range` [m].
  [[nodiscard]] static int RangeBand(double range);
  /// Score() below options.suspect_below.
  [[nodiscard]] bool Suspect(const SelfCheckOptions& options) const;
  /// Adds another map's counts.
  void Merge(const SelfCheckStats& other);
};

struct SelfCheckResult {
  SelfCheckStats stats;
  TiledGrid<float> returns_per_cell;      ///< Replayed returns per cell of the map.
  TiledGrid<float> disagreeing_per_cell;  ///< Of which: not agreeing.
};

/// Replays `scans` (in trajectory order; borrowed) against the fused log-odds map `log_odds`,
/// thresholded as `fusion` does for map.pgm. Scans closer than min_motion / min_rotation to the
/// previous replayed scan are skipped. Memory: the tiles of the map the returns fall in, not the
/// map's bounding box (distances to the walls are computed block by block around the returns,
/// `threads` blocks at once: the same result for any number).
SelfCheckResult CheckMap(const TiledGrid<float>& log_odds,
                         const std::vector<fusion::PosedScan>& scans,
                         const fusion::FusionOptions& fusion, const SelfCheckOptions& options,
                         int threads = 1);
SelfCheckResult CheckMap(const Grid2D<float>& log_odds, const std::vector<fusion::PosedScan>& scans,
                         const fusion::FusionOptions& fusion, const SelfCheckOptions& options);

}  // namespace gridslam::quality
