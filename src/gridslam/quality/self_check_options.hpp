// Options of the map self-check (docs/self_check.md): how every `gridslam map` run judges its own
// map without ground truth, by replaying a sample of its scans at their final corrected poses
// against the final fused map.
#pragma once

#include "gridslam/common/options.hpp"

namespace gridslam::quality {

struct SelfCheckOptions {
  bool enabled = true;  ///< Run the self-check after mapping (report.json "quality").
  /// Scans replayed: one after this much travel of the corrected trajectory [m] ...
  double min_motion = 0.2;
  double min_rotation = 0.2;  ///< ... or this much rotation [rad].
  double max_range = 30.0;    ///< Returns farther than this are not replayed [m].
  /// A return agrees with the map when an occupied cell lies within this distance; 0.1 m is two
  /// cells of the default 0.05 m map, the tolerance of a sharp wall drawn by noisy returns [m].
  double agreement_distance = 0.1;
  /// A return contradicts the map when every cell within agreement_distance is free (the map
  /// has carved free space where this scan, at its final pose, sees an obstacle). Distances to the
  /// nearest occupied cell are clamped here for the mean [m].
  double distance_clamp = 1.0;
  /// The local baseline: the replayed scans are cut into stretches of this much travel of the
  /// corrected trajectory, each fused alone; only the returns their own stretch's map confirms
  /// are scored (what disagrees with a map of its neighbourhood, people walking past, glass,
  /// grazing returns, says nothing of the alignment). About a key map's span, over which the
  /// front end alone aligns the scans. 0 scores every return [m].
  double local_travel = 10.0;
  /// The map is flagged suspect when the score (share of the confirmed returns that agree with
  /// the map) or the local score (share of all returns their own stretch confirms) is below
  /// this [-]. docs/self_check.md gives the validation behind the default.
  double suspect_below = 0.8;
  /// Smoothing radius of the disagreement heat layer in map_quality.png [m].
  double heat_radius = 0.3;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled, "Run the map self-check after mapping (report.json quality)");
    v("min_motion", min_motion, "Replay one scan after this much travel [m] ...");
    v("min_rotation", min_rotation, "... or this much rotation [rad]");
    v("max_range", max_range, "Returns farther than this are not replayed [m]");
    v("agreement_distance", agreement_distance,
      "A return agrees when an occupied map cell lies within this distance [m]");
    v("distance_clamp", distance_clamp, "Clamp of the return-to-wall distance in the mean [m]");
    v("local_travel", local_travel,
      "Score only returns confirmed by a map of this much travel around them (0: all) [m]");
    v("suspect_below", suspect_below,
      "Flag the map suspect when the score or the local score is below this [-]");
    v("heat_radius", heat_radius, "Smoothing radius of the map_quality.png heat layer [m]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(min_motion >= 0.0 && min_rotation >= 0.0, "quality.min_motion, min_rotation >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_range > 0.0, "quality.max_range > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(agreement_distance > 0.0, "quality.agreement_distance > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(distance_clamp >= agreement_distance,
                                     "quality.distance_clamp >= quality.agreement_distance"));
    GRIDSLAM_RETURN_IF_ERROR(Require(local_travel >= 0.0, "quality.local_travel >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(suspect_below >= 0.0 && suspect_below <= 1.0, "quality.suspect_below in [0, 1]"));
    return Require(heat_radius >= 0.0, "quality.heat_radius >= 0");
  }
};

}  // namespace gridslam::quality
