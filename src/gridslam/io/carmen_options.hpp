// Options of the CARMEN log reader (docs/formats.md §1).
#pragma once

#include <vector>

#include "gridslam/common/options.hpp"

namespace gridslam::io {

struct CarmenOptions {
  /// Range values that mean "no return" in the project's logs (docs/formats.md §1.5).
  std::vector<double> no_return_values = {81.83, 81.91};
  /// Readings at or beyond this are no-returns, whatever the line's maximum_range says [m].
  double max_usable_range = 80.0;
  /// Laser mounting on the robot (x, y, theta) [m, m, rad]; empty = from PARAM lines,
  /// ROBOTLASER1 poses or FLASER's two poses, else identity.
  std::vector<double> laser_offset = {};
  /// Repair intel-style unpadded microseconds and late stamps for ordering and odometry
  /// interpolation (scans keep their printed timestamps as identity).
  bool repair_timestamps = true;
  /// Skip and count malformed lines of known types instead of stopping with an error.
  bool lenient = false;
  /// FLASER/RLASER lines carry no beam geometry: first beam angle [rad] (CARMEN: -pi/2) and
  /// beam step [rad]; 0 = CARMEN's guess from the beam count (carmen_laser_guess_angle_increment).
  double flaser_angle_min = -1.5707963267948966;
  double flaser_angle_increment = 0.0;
  /// A pose-less scan (RAWLASER*) waits at most this long in log time for an ODOM line at or
  /// after its timestamp before its odometry is clamped to the latest ODOM line [s].
  double max_lookahead = 10.0;
  /// A log whose first laser line has no timestamp (0 or missing, as orebro and laserazos) gets
  /// times synthesized from message order: laser line k at k / timestamp_rate seconds (ODOM and
  /// TRUEPOS lines at the time of the next laser line) [Hz].
  double timestamp_rate = 10.0;

  template <class V>
  void Visit(V& v) {
    v("no_return_values", no_return_values, "Range values meaning 'no return' [m]");
    v("max_usable_range", max_usable_range, "Readings at or beyond this are no-returns [m]");
    v("laser_offset", laser_offset,
      "Laser pose on the robot [x m, y m, theta rad]; [] = from the log (PARAM/ROBOTLASER1)");
    v("repair_timestamps", repair_timestamps,
      "Repair out-of-order/unpadded timestamps for odometry interpolation");
    v("lenient", lenient, "Skip and count malformed lines instead of failing");
    v("flaser_angle_min", flaser_angle_min, "First beam angle of FLASER/RLASER lines [rad]");
    v("flaser_angle_increment", flaser_angle_increment,
      "Beam step of FLASER/RLASER lines [rad]; 0 = CARMEN's guess from the beam count");
    v("max_lookahead", max_lookahead,
      "Longest wait in log time for the ODOM line after a pose-less scan [s]");
    v("timestamp_rate", timestamp_rate,
      "Scan rate used to synthesize times when the log has none (0 or missing) [Hz]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(max_usable_range > 0.0, "log.max_usable_range > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(laser_offset.empty() || laser_offset.size() == 3,
                                     "log.laser_offset has 0 or 3 values"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(flaser_angle_increment >= 0.0, "log.flaser_angle_increment >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_lookahead > 0.0, "log.max_lookahead > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(timestamp_rate > 0.0, "log.timestamp_rate > 0"));
    return Status::Ok();
  }
};

}  // namespace gridslam::io
