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
#include <cstdint>
#include <string_view>
#include <vector>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/tiled_grid.hpp"
#include "gridslam/quality/self_check_options.hpp"

namespace gridslam::quality {

/// The self-check's verdict on a map (report.json quality.verdict, ToString).
enum class SelfCheckVerdict {
  kConsistent,    ///< Both shares at or above suspect_below.
  kContradicted,  ///< Score() below suspect_below: the map contradicts what the scans confirm.
  /// LocalScore() below suspect_below (and Score() not): too few returns are confirmed by their
  /// own stretch of trajectory for the score to mean anything; the scans disagree with their
  /// neighbours (a front end that failed at every step, or a laser that sees little but noise).
  kUnconfirmed,
};
[[nodiscard]] std::string_view ToString(SelfCheckVerdict verdict);

/// Counts and shares of one map (or of several, merged).
struct SelfCheckStats {
  long scans = 0;     ///< Scans replayed.
  long returns = 0;   ///< Their returns inside the map.
  long agreeing = 0;  ///< Returns within agreement_distance of an occupied cell.
  /// Returns confirmed by the map of their own stretch of trajectory (LocalConfirmation; all of
  /// them when the check was given no confirmation).
  long confirmed = 0;
  long confirmed_agreeing = 0;  ///< Of which: agreeing with the map checked.
  long contradicting = 0;       ///< Returns with only free cells within agreement_distance.
  long outside = 0;             ///< Returns outside the map's limits (not counted in `returns`).
  double distance_sum = 0.0;    ///< Sum of the clamped distances to the nearest occupied cell [m].
  /// Returns and agreeing returns by range band (kRangeBands: up to 5, 10, 20 m and beyond): a
  /// diagnostic of where in the scans the disagreement lies (report.json quality.by_range).
  static constexpr std::array<double, 3> kRangeBandEdges = {5.0, 10.0, 20.0};
  static constexpr int kRangeBands = static_cast<int>(kRangeBandEdges.size()) + 1;
  std::array<long, kRangeBands> band_returns{};
  std::array<long, kRangeBands> band_agreeing{};

  /// The verdict's score: the share of the confirmed returns that agree with the map, 1 when
  /// there is none [-]. A misaligned trajectory lowers it; what disagrees with any map (moving
  /// people, glass, grazing returns) does not.
  [[nodiscard]] double Score() const;
  /// Share of all returns that agree with the map, 1 when there is no return [-].
  [[nodiscard]] double RawScore() const;
  /// Share of the returns their own stretch of trajectory confirms, 1 when there is none [-]:
  /// how much of what the laser sees is stable structure.
  [[nodiscard]] double LocalScore() const;
  /// Share of contradicting returns [-].
  [[nodiscard]] double Contradiction() const;
  /// Mean clamped distance of a return to the nearest occupied cell [m].
  [[nodiscard]] double MeanDistance() const;
  /// Share of agreeing returns in range band `b`, 1 when it has none [-].
  [[nodiscard]] double BandScore(int b) const;
  /// The band of a return at `range` [m].
  [[nodiscard]] static int RangeBand(double range);
  /// The verdict at options.suspect_below: the score is judged first.
  [[nodiscard]] SelfCheckVerdict Verdict(const SelfCheckOptions& options) const;
  /// Verdict() is not kConsistent.
  [[nodiscard]] bool Suspect(const SelfCheckOptions& options) const;
  /// Adds another map's counts.
  void Merge(const SelfCheckStats& other);
};

struct SelfCheckResult {
  SelfCheckStats stats;
  TiledGrid<float> returns_per_cell;      ///< Confirmed replayed returns per cell of the map.
  TiledGrid<float> disagreeing_per_cell;  ///< Of which: not agreeing.
};

/// Replays `scans` (in trajectory order; borrowed) against the fused log-odds map `log_odds`,
/// thresholded as `fusion` does for map.pgm. Scans closer than min_motion / min_rotation to the
/// previous replayed scan are skipped (ReplayedScans). `confirmed`: LocalConfirmation of the
/// same scans; null counts every return as confirmed (then Score() == RawScore()). Memory: the
/// tiles of the map the returns fall in, not the map's bounding box (distances to the walls are
/// computed block by block around the returns, `threads` blocks at once: the same result for any
/// number).
SelfCheckResult CheckMap(const TiledGrid<float>& log_odds,
                         const std::vector<fusion::PosedScan>& scans,
                         const fusion::FusionOptions& fusion, const SelfCheckOptions& options,
                         int threads = 1,
                         const std::vector<std::vector<std::uint8_t>>* confirmed = nullptr);
SelfCheckResult CheckMap(const Grid2D<float>& log_odds, const std::vector<fusion::PosedScan>& scans,
                         const fusion::FusionOptions& fusion, const SelfCheckOptions& options,
                         const std::vector<std::vector<std::uint8_t>>* confirmed = nullptr);

}  // namespace gridslam::quality
