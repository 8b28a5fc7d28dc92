// Correlative scan matching (E. Olson, "Real-time correlative scan matching", ICRA 2009), in its
// brute-force form: every pose of a coarse x-y-yaw lattice around a centre is scored by the sum of
// a Gaussian of each point's distance to the nearest obstacle (read from the matching field's
// exact distance transform, a table lookup per point). The scan matcher uses a small lattice when
// the refined odometry prior explains the scan poorly, to find a start inside Gauss-Newton's
// basin; the front end uses a wide one (metres, a right angle) when the odometry is doubtful or
// missing, keeping the best few distinct lattice poses as starts.
#pragma once

#include <vector>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/scan_points.hpp"
#include "gridslam/scan_matching/matching_field.hpp"
#include "gridslam/scan_matching/scan_matcher_options.hpp"

namespace gridslam::scan_matching {

struct SearchResult {
  Pose2 T_odom_base;   ///< Best lattice pose.
  double score = 0.0;  ///< Its mean Gaussian score per point, in [0, 1].
  long evaluated = 0;  ///< Poses scored.
};

/// A lattice of poses around a centre.
struct SearchLattice {
  double linear_window = 0.3;    ///< Half-width in x and y [m].
  int linear_step = 2;           ///< Translation step [cells].
  double angular_window = 0.25;  ///< Half-width in yaw [rad].
  double angular_step = 0.0175;  ///< Yaw step [rad].
  double sigma = 0.1;            ///< Width of a point's Gaussian score [m].
  std::size_t max_points = 180;  ///< Points used (evenly subsampled).
};

/// Searches x, y in centre +- search_linear_window (step search_linear_step cells) and yaw in
/// centre +- search_angular_window (step search_angular_step) with at most `max_points` points.
SearchResult CorrelativeSearch(const MatchingField& field, const ScanPoints& scan,
                               const Pose2& centre, const ScanMatcherOptions& options,
                               std::size_t max_points = 180);

/// The best `count` lattice poses around `centre`, best first, each a local maximum at least
/// `separation_xy` [m] or `separation_theta` [rad] away from every better one kept.
std::vector<SearchResult> CorrelativeSearchTop(const MatchingField& field, const ScanPoints& scan,
                                               const Pose2& centre, const SearchLattice& lattice,
                                               int count, double separation_xy,
                                               double separation_theta);

}  // namespace gridslam::scan_matching
