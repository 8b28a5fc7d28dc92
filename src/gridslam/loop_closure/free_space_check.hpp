// The free-space check of a join (docs/multi_robot.md, "Round 16: a join checked against free
// space"). Aligning key maps compares walls with walls; a symmetric building's look-alike (a
// corridor turned by 180°) passes that test as well as the truth. What differs is the space
// between the walls: under a wrong frame, the walls one key map saw fall where the other saw
// free space. The returns of one key map (KeyMapNode::scan_points) placed in another by the
// alignment are replayed against its cells (description::KeyMapCells): a return agrees when an
// obstacle cell lies within `agreement_distance`, contradicts when every cell that close was
// observed and none is an obstacle, and tells nothing where the other key map did not look
// (the ray-consistency idea of Mazuran et al., ICRA 2014, which the map self-check also uses).
//
// How much a right alignment contradicts depends on the laser and the building: a noise-free
// simulated office contradicts at 0.1-0.5 %, fr-clinic, whose long grazing returns carve free
// space through near walls, at 0-30 %. So the contradiction of a join's alignments is compared
// with the robots' own: each key map of the join against the same robot's key map
// `baseline_travel` behind it, under their estimates (one front end, no alignment). The join is
// refused when the median contradiction of its alignments exceeds `max_ratio` times the median
// of the baselines plus `min_excess`.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/options.hpp"
#include "gridslam/description/key_map_cells.hpp"
#include "gridslam/geometry/pose2.hpp"

namespace gridslam::loop_closure {

struct FreeSpaceCheckOptions {
  bool enabled = true;
  /// A return agrees when an obstacle cell lies within this distance [m].
  double agreement_distance = 0.15;
  /// Each key map's baseline: against its robot's key maps this far behind along the path [m].
  std::vector<double> baseline_travel = {5.0, 10.0};
  /// Refused when median(alignments) > max_ratio * median(baselines) + min_excess [-], [-].
  double max_ratio = 4.0;
  double min_excess = 0.01;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled,
      "Refuse a join whose alignments put walls in free space far more often than each robot "
      "contradicts itself");
    v("agreement_distance", agreement_distance,
      "A return agrees when an obstacle cell lies within this distance [m]");
    v("baseline_travel", baseline_travel,
      "A robot's own contradiction: each key map against its key maps this far behind [m]");
    v("max_ratio", max_ratio,
      "Refused when the alignments' median contradiction exceeds this times the baseline "
      "median ... [-]");
    v("min_excess", min_excess, "... plus this [-]");
  }
  [[nodiscard]] Status Validate() const;
};

/// Returns replayed against a key map's cells.
struct FreeSpaceCounts {
  long returns = 0;        ///< Returns replayed.
  long observed = 0;       ///< Of which on an observed cell.
  long agreeing = 0;       ///< An obstacle cell within agreement_distance.
  long contradicting = 0;  ///< Every cell within agreement_distance observed, none an obstacle.

  /// contradicting / observed; 0 when nothing was observed [-].
  [[nodiscard]] double Contradiction() const;
  void Merge(const FreeSpaceCounts& other);
};

/// Replays `points` (in frame p) placed by `T_cells_p` against `cells` (in frame cells).
FreeSpaceCounts ReplayReturns(std::span<const Eigen::Vector2d> points, const Pose2& T_cells_p,
                              const description::KeyMapCells& cells, double agreement_distance);

/// The two key maps against each other: b's returns in a's cells and a's in b's.
FreeSpaceCounts ReplayPair(std::span<const Eigen::Vector2d> points_a,
                           const description::KeyMapCells& cells_a,
                           std::span<const Eigen::Vector2d> points_b,
                           const description::KeyMapCells& cells_b, const Pose2& T_a_b,
                           double agreement_distance);

struct FreeSpaceVerdict {
  double alignments = 0.0;  ///< Median contradiction of the alignments [-].
  double baseline = 0.0;    ///< Median contradiction of the baselines [-].
  bool refused = false;
};

/// The decision above from the contradictions of the alignments and of the baselines (a join
/// without baselines is judged against a baseline of 0).
FreeSpaceVerdict JudgeContradictions(std::vector<double> alignments, std::vector<double> baselines,
                                     const FreeSpaceCheckOptions& options);

}  // namespace gridslam::loop_closure
