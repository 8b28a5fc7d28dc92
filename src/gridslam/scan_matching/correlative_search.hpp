// Correlative scan matching (E. Olson, "Real-time correlative scan matching", ICRA 2009), in its
// brute-force form: every pose of a coarse x-y-yaw lattice around a centre is scored by the sum of
// a Gaussian of each point's distance to the nearest obstacle (read from the matching field's
// exact distance transform, a table lookup per point). Used by the scan matcher only when the
// refined odometry prior explains the scan poorly, to find a start inside Gauss-Newton's basin.
#pragma once

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

/// Searches x, y in centre +- search_linear_window (step search_linear_step cells) and yaw in
/// centre +- search_angular_window (step search_angular_step) with at most `max_points` points.
SearchResult CorrelativeSearch(const MatchingField& field, const ScanPoints& scan,
                               const Pose2& centre, const ScanMatcherOptions& options,
                               std::size_t max_points = 180);

}  // namespace gridslam::scan_matching
