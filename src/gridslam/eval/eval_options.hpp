// Options of the benchmark relation metric (docs/design.md §3.1; docs/formats.md §4).
#pragma once

#include <string>

#include "gridslam/common/options.hpp"

namespace gridslam::eval {

struct EvalOptions {
  /// A relation timestamp matches the trajectory pose with the nearest timestamp when they
  /// differ by at most this (relation files round timestamps differently) [s].
  double tolerance = 0.001;
  /// Only relations with min_dt <= |t2 - t1| are scored [s].
  double min_dt = 0.0;
  /// Only relations with |t2 - t1| < max_dt are scored; 0 = no upper limit [s].
  double max_dt = 0.0;
  /// Frame whose poses trajectories hold (what `odometry` and `map` write, and what the
  /// relations describe): "base" (robot centre, T_odom_base) or "laser" (T_odom_base *
  /// T_base_laser). docs/frames.md gives the evidence for the default.
  std::string trajectory_frame = "base";
  /// A relation timestamp without a trajectory pose within `tolerance` gets the pose
  /// interpolated between the trajectory poses just before and after it (linear in x, y,
  /// shortest arc in theta, as Cartographer's relations tool), so decimated logs are scored on
  /// every relation. False = such relations are missing.
  bool interpolate = true;
  /// Interpolate only between poses at most this far apart; 0 = any gap [s].
  double max_interpolation_gap = 1.0;

  template <class V>
  void Visit(V& v) {
    v("tolerance", tolerance, "Largest |relation time - trajectory time| that still matches [s]");
    v("min_dt", min_dt, "Score only relations with |t2 - t1| >= min_dt [s]");
    v("max_dt", max_dt, "Score only relations with |t2 - t1| < max_dt; 0 = no limit [s]");
    v("trajectory_frame", trajectory_frame,
      "Frame of written trajectories and of the relations: base (robot centre) or laser");
    v("interpolate", interpolate,
      "Interpolate the trajectory at relation timestamps between two poses (else missing)");
    v("max_interpolation_gap", max_interpolation_gap,
      "Interpolate only between poses at most this far apart; 0 = any gap [s]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(tolerance >= 0.0, "eval.tolerance >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(min_dt >= 0.0, "eval.min_dt >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_dt >= 0.0, "eval.max_dt >= 0 (0 = no limit)"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(max_dt == 0.0 || max_dt > min_dt, "eval.max_dt > eval.min_dt (or 0)"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(max_interpolation_gap >= 0.0, "eval.max_interpolation_gap >= 0 (0 = any gap)"));
    GRIDSLAM_RETURN_IF_ERROR(Require(trajectory_frame == "base" || trajectory_frame == "laser",
                                     "eval.trajectory_frame is 'base' or 'laser'"));
    return Status::Ok();
  }
};

}  // namespace gridslam::eval
