// The SLAM benchmark's relation metric (Kümmerle et al. 2009; docs/design.md §3.1, docs/formats.md
// §4). For each relation (t1, t2, δ*) the estimate's poses X_t1, X_t2 are the trajectory poses with
// the nearest timestamps (within EvalOptions::tolerance) or, failing that and if
// EvalOptions::interpolate, interpolated between the poses before and after (at most
// max_interpolation_gap apart; counted in `interpolated`), δ = X_t1⁻¹ X_t2, and the error is
// ε = δ* ⊖ δ = δ⁻¹ δ*. Its translational part |t(ε)| = |t(δ*) - t(δ)| is the distance between
// the true and estimated positions of the pose at t2, both expressed in the frame of the pose at
// t1: unlike Cartographer's (δ δ*⁻¹), it does not depend on which of the two is called the
// estimate. Its rotational part is |θ* - θ| wrapped to [0, π]. Reported: mean and sample (N-1)
// standard deviation of the absolute and squared errors; relations whose timestamps the
// trajectory lacks are counted, never silently dropped.
#pragma once

#include <vector>

#include "gridslam/eval/eval_options.hpp"
#include "gridslam/eval/relation.hpp"
#include "gridslam/eval/stamped_pose.hpp"

namespace gridslam::eval {

/// Mean and sample standard deviation (0 for fewer than 2 values).
struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};
MeanStd ComputeMeanStd(const std::vector<double>& values);

/// The error of one relation.
struct RelationError {
  Relation relation;
  double translation = 0.0;  ///< |t(δ*) - t(δ)| [m], in the frame of the pose at t1.
  double rotation = 0.0;     ///< |θ* - θ| wrapped [rad].
};

/// ε = δ⁻¹ δ* for an estimated relative pose δ and the true one δ*.
Pose2 RelationErrorPose(const Pose2& estimate, const Pose2& truth);

struct RelationMetrics {
  long total = 0;          ///< Relations given.
  long filtered = 0;       ///< Excluded by min_dt / max_dt.
  long missing = 0;        ///< Not scored: a timestamp has no trajectory pose within the tolerance.
  long interpolated = 0;   ///< Scored with at least one interpolated pose (included in `used`).
  long used = 0;           ///< Scored (= errors.size()).
  MeanStd translation;     ///< [m]
  MeanStd translation_sq;  ///< [m²]
  MeanStd rotation_deg;    ///< [deg]
  MeanStd rotation_sq_deg2;           ///< [deg²]
  std::vector<RelationError> errors;  ///< One per scored relation, in input order.
};

/// Scores `trajectory` (any order; duplicate times use the first) against `relations`.
RelationMetrics EvaluateRelations(const std::vector<Relation>& relations,
                                  const std::vector<StampedPose>& trajectory,
                                  const EvalOptions& options);

}  // namespace gridslam::eval
