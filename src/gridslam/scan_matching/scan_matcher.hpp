// Scan-to-local-map matcher of the front end (docs/design.md §1.2). The paper uses Censi's PL-ICP
// (docs/method.md §6) against a key-frame scan; here each scan is matched against the
// rolling local map built from the previous scans, by Gauss-Newton on the map's own exact distance
// transform (matching_field.hpp): the residual of a point is the bilinearly interpolated distance
// to the nearest obstacle cell, its gradient restricted to the point's scan normal on clean
// surfaces. A "point_to_line" residual (to the nearest obstacle cell's mean hit point, along its
// mean normal, correspondences in O(1) from the transform's labels) is available; it is more
// precise per scan but lets the map follow the robot's errors (docs/front_end.md). The iterations
// are robust (Cauchy weights, shrinking scale over stages, i.e. coarse to fine; damped when they
// oscillate across the field's kinks), start from the odometry prediction and keep a motion-model
// prior, which matters only where the scan leaves a direction unconstrained (long corridors). When
// the refined prior explains the scan poorly, a correlative search (Olson 2009, brute force over a
// coarse x-y-yaw lattice on a Gaussian score of the distance field) proposes another start, and the
// better of the two refinements wins. The covariance is the inverse of the Gauss-Newton Hessian
// (points with standard deviation point_sigma, plus the prior).
#pragma once

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/rolling_window.hpp"
#include "gridslam/grid/scan_points.hpp"
#include "gridslam/scan_matching/degeneracy.hpp"
#include "gridslam/scan_matching/matching_field.hpp"
#include "gridslam/scan_matching/scan_matcher_options.hpp"

namespace gridslam::scan_matching {

struct MatchResult {
  Pose2 T_odom_base;  ///< Estimated robot pose in the local map's (odometry) frame.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  ///< Of (x, y, theta) [m^2, rad^2].
  double score = 0.0;       ///< Fraction of the points in observed cells that lie on the map.
  int iterations = 0;       ///< Gauss-Newton iterations, all stages and starts.
  int correspondences = 0;  ///< Points matched at the final pose.
  bool converged = false;   ///< The last stage converged before max_iterations.
  bool searched = false;    ///< The correlative search ran.
  bool ok = false;          ///< Enough correspondences; otherwise the pose is the prior.
  /// Matched against the front end's larger matching window (set by FrontEnd, not the matcher).
  bool far_window = false;
  /// The translation directions the scan left to the prior at the last iteration (degeneracy.hpp).
  DegeneracyResult degeneracy;
};

/// Where the prior comes from: a measurement of the motion (odometry), which carries the estimate
/// along the directions the scan leaves degenerate, or a motion model (constant velocity), which
/// does not: there the scan's few points are better than a guess.
enum class PriorKind { kMeasured, kMotionModel };

class ScanMatcher {
 public:
  /// `options` must be valid (Validate()).
  explicit ScanMatcher(const ScanMatcherOptions& options);

  /// Matches `scan` (points in the base frame) against `map`, whose `field` is up to date, from
  /// the prior pose `T_odom_base_prior` with information `prior_information` on (x, y, theta)
  /// deviations in the odometry frame (may be zero). Thread-compatible (const, no state).
  [[nodiscard]] MatchResult Match(const RollingWindow& map, const MatchingField& field,
                                  const ScanPoints& scan, const Pose2& T_odom_base_prior,
                                  const Eigen::Matrix3d& prior_information,
                                  PriorKind prior_kind = PriorKind::kMeasured) const;

  /// Gauss-Newton refinement alone, from `start`, with the prior centred on `prior`.
  [[nodiscard]] MatchResult Refine(const RollingWindow& map, const MatchingField& field,
                                   const ScanPoints& scan, const Pose2& start, const Pose2& prior,
                                   const Eigen::Matrix3d& prior_information,
                                   PriorKind prior_kind = PriorKind::kMeasured) const;

  /// The score (see MatchResult::score) of `scan` at `pose`, and the number of matched points.
  [[nodiscard]] double Score(const RollingWindow& map, const MatchingField& field,
                             const ScanPoints& scan, const Pose2& pose,
                             int* correspondences = nullptr) const;

  [[nodiscard]] const ScanMatcherOptions& Options() const { return options_; }

 private:
  ScanMatcherOptions options_;
  bool point_to_line_ = true;
};

}  // namespace gridslam::scan_matching
