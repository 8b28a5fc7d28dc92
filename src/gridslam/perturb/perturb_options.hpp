// Options of `gridslam perturb` (issue 16; docs/robustness.md): the seeded faults written into a
// variant of a log. Every fault is off by default, so the default options copy the log (as
// re-encoded by the CARMEN writer). Each fault draws from its own random stream of `seed`, so
// turning one fault on or off never changes the draws of another.
#pragma once

#include "gridslam/common/options.hpp"

namespace gridslam::perturb {

struct PerturbOptions {
  /// Seed of every random draw (glitch times and sizes, noise, dropouts, jitter).
  int seed = 1;

  // --- Cut (applied first; times relative to the first scan's corrected time) ---
  double start = 0.0;     ///< Keep scans from this time on [s].
  double duration = 0.0;  ///< Keep scans up to start + duration; 0 = to the end [s].

  // --- Odometry glitches (a Poisson process in log time) ---
  /// Mean time between glitches [s]; 0 = no glitches. At the first scan after each glitch time
  /// the odometry increment gets a spurious jump, and the odometry carries on from the jumped
  /// pose.
  double glitch_period = 0.0;
  /// Share of glitches that are yaw jumps; the others are translation jumps.
  double glitch_yaw_fraction = 0.5;
  double glitch_yaw_min_deg = 25.0;     ///< Smallest yaw jump [deg] (random sign).
  double glitch_yaw_max_deg = 85.0;     ///< Largest yaw jump [deg].
  double glitch_translation_min = 0.3;  ///< Smallest translation jump [m] (random direction).
  double glitch_translation_max = 1.0;  ///< Largest translation jump [m].

  // --- Odometry calibration errors (applied to every increment) ---
  double translation_scale = 1.0;  ///< Factor on the translation of each increment.
  double rotation_scale = 1.0;     ///< Factor on the rotation of each increment.
  double yaw_drift = 0.0;          ///< Yaw added per second of log time [rad/s].

  /// Standard deviation of the offset between the laser's and the odometry's clocks [s]: each
  /// scan gets the odometry at its timestamp plus N(0, sigma). The printed laser timestamps stay
  /// (the relations still apply); the odometry is what is taken at the wrong time.
  double time_jitter = 0.0;

  /// Remove the odometry: the log gets no ODOM lines and pose-less RAWLASER1 laser lines, which
  /// the reader delivers as Frame::has_odometry = false (scan matching alone).
  bool remove_odometry = false;

  // --- Sensor changes ---
  int keep_every = 1;      ///< Keep every k-th scan (the first, k+1-th, ...).
  double max_range = 0.0;  ///< Readings at or beyond this become no-returns; 0 = unchanged [m].
  double fov_deg = 0.0;    ///< Keep the beams within +-fov/2 of the laser's x axis; 0 = all [deg].
  int beam_step = 1;       ///< Keep every k-th beam (after the crop).
  double range_noise = 0.0;   ///< Standard deviation of Gaussian noise on every return [m].
  double beam_dropout = 0.0;  ///< Probability that a return is replaced by 0 (no return).

  template <class V>
  void Visit(V& v) {
    v("seed", seed, "Seed of every random draw");
    v("start", start, "Keep scans from this time after the first scan on [s]");
    v("duration", duration, "Keep scans up to start + duration; 0 = to the end [s]");
    v("glitch_period", glitch_period, "Mean time between odometry glitches; 0 = none [s]");
    v("glitch_yaw_fraction", glitch_yaw_fraction,
      "Share of glitches that are yaw jumps (the others translation jumps)");
    v("glitch_yaw_min_deg", glitch_yaw_min_deg, "Smallest glitch yaw jump [deg]");
    v("glitch_yaw_max_deg", glitch_yaw_max_deg, "Largest glitch yaw jump [deg]");
    v("glitch_translation_min", glitch_translation_min, "Smallest glitch translation jump [m]");
    v("glitch_translation_max", glitch_translation_max, "Largest glitch translation jump [m]");
    v("translation_scale", translation_scale, "Factor on the translation of each increment");
    v("rotation_scale", rotation_scale, "Factor on the rotation of each increment");
    v("yaw_drift", yaw_drift, "Yaw added per second of log time [rad/s]");
    v("time_jitter", time_jitter,
      "Std. dev. of the laser/odometry clock offset: each scan gets the odometry at t + N(0, s) "
      "[s]");
    v("remove_odometry", remove_odometry, "No odometry at all (scan matching alone)");
    v("keep_every", keep_every, "Keep every k-th scan");
    v("max_range", max_range, "Readings at or beyond this become no-returns; 0 = unchanged [m]");
    v("fov_deg", fov_deg, "Keep the beams within +-fov/2 of the laser axis; 0 = all [deg]");
    v("beam_step", beam_step, "Keep every k-th beam (after the crop)");
    v("range_noise", range_noise, "Std. dev. of Gaussian noise on every return [m]");
    v("beam_dropout", beam_dropout, "Probability that a return becomes 0 (no return)");
  }

  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(start >= 0.0, "perturb.start >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(duration >= 0.0, "perturb.duration >= 0 (0 = to the end)"));
    GRIDSLAM_RETURN_IF_ERROR(Require(glitch_period >= 0.0, "perturb.glitch_period >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(glitch_yaw_fraction >= 0.0 && glitch_yaw_fraction <= 1.0,
                                     "perturb.glitch_yaw_fraction in [0, 1]"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(0.0 <= glitch_yaw_min_deg && glitch_yaw_min_deg <= glitch_yaw_max_deg &&
                    glitch_yaw_max_deg <= 180.0,
                "0 <= perturb.glitch_yaw_min_deg <= glitch_yaw_max_deg <= 180"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(0.0 <= glitch_translation_min && glitch_translation_min <= glitch_translation_max,
                "0 <= perturb.glitch_translation_min <= glitch_translation_max"));
    GRIDSLAM_RETURN_IF_ERROR(Require(translation_scale > 0.0, "perturb.translation_scale > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(rotation_scale > 0.0, "perturb.rotation_scale > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(time_jitter >= 0.0, "perturb.time_jitter >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(keep_every >= 1, "perturb.keep_every >= 1"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_range >= 0.0, "perturb.max_range >= 0 (0 = unchanged)"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(fov_deg >= 0.0 && fov_deg <= 360.0, "perturb.fov_deg in [0, 360] (0 = all)"));
    GRIDSLAM_RETURN_IF_ERROR(Require(beam_step >= 1, "perturb.beam_step >= 1"));
    GRIDSLAM_RETURN_IF_ERROR(Require(range_noise >= 0.0, "perturb.range_noise >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(beam_dropout >= 0.0 && beam_dropout <= 1.0, "perturb.beam_dropout in [0, 1]"));
    return Status::Ok();
  }

  /// True when some odometry fault is on (glitches, calibration, drift, jitter).
  [[nodiscard]] bool PerturbsOdometry() const {
    return glitch_period > 0.0 || translation_scale != 1.0 || rotation_scale != 1.0 ||
           yaw_drift != 0.0 || time_jitter > 0.0;
  }
};

}  // namespace gridslam::perturb
