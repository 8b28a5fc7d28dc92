// Writes CARMEN logs (docs/formats.md §1) the way CARMEN's logger does (`carmen/src/logger/
// writelog.c`): the logger's header comments, one message per line, every message followed by
// `ipc_timestamp ipc_hostname logger_timestamp` (timestamps with 6 decimals, the logger time
// relative to the log's start), ranges with %.2f and every other number with %f. Laser frames
// become RAWLASER1 lines (geometry, no pose: readers interpolate the ODOM lines, as in the
// project's reconstructed logs), ROBOTLASER1 (geometry and poses) or FLASER (poses, no
// geometry); optionally each scan also gets a TRUEPOS line with its ground truth. The log is
// built in memory and written all at once through a temporary file.
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::io {

enum class CarmenLaserMessage { kRawLaser1, kRobotLaser1, kFlaser };

struct CarmenWriterOptions {
  std::string hostname = "gridslam";  ///< ipc_hostname of every line (one token).
  CarmenLaserMessage laser_message = CarmenLaserMessage::kRawLaser1;
  int laser_type = 0;          ///< 0 SICK_LMS, 1 SICK_PLS, 2 HOKUYO_URG.
  double accuracy = 0.01;      ///< The `accuracy` field (range sigma) [m].
  bool write_truepos = false;  ///< A TRUEPOS line before each scan that has ground truth.
};

/// One ODOM line's contents.
struct CarmenOdometry {
  Time time;
  Pose2 pose;       ///< T_odom_base.
  double tv = 0.0;  ///< [m/s]
  double rv = 0.0;  ///< [rad/s]
  double accel = 0.0;
};

/// `ODOM x y theta tv rv accel ipc_timestamp host logger_timestamp`.
std::string FormatOdometryLine(const CarmenOdometry& odometry, const std::string& hostname,
                               Time logger_start);

/// The laser line of a frame (and its TRUEPOS line first, if asked and available), each ending
/// in a newline. Field of view = (beams - 1) * angle_increment; maximum_range = range_max.
std::string FormatLaserLines(const Frame& frame, const CarmenWriterOptions& options,
                             Time logger_start);

class CarmenWriter {
 public:
  /// A writer for `path`; `logger_start` is the time the logger timestamps count from.
  CarmenWriter(std::string path, CarmenWriterOptions options, Time logger_start);

  /// A '# ' comment line (one per line of `text`).
  void Comment(const std::string& text);
  /// `PARAM name value` (PARAM lines carry the absolute time in both timestamp fields).
  void Param(const std::string& name, const std::string& value, Time time);
  /// The laser-offset PARAMs CARMEN's reader understands (robot_frontlaser_offset,
  /// _side_offset, _angular_offset).
  void LaserOffsetParams(const Pose2& T_base_laser, Time time);
  void Odometry(const CarmenOdometry& odometry);
  void Laser(const Frame& frame);
  /// Writes the log file; RuntimeError if it cannot be written.
  [[nodiscard]] Status Close();

 private:
  std::string path_;
  CarmenWriterOptions options_;
  Time logger_start_;
  std::string text_;
};

/// Writes frames as a log: the header, `comment` as '# ' lines (none if empty), laser-offset
/// PARAMs from the first frame, then for each frame an ODOM line with its odometry (tv, rv from
/// the previous frame, over the repaired times) and its laser line.
Status WriteCarmenLog(const std::string& path, const std::vector<Frame>& frames,
                      const CarmenWriterOptions& options, const std::string& comment = {});

}  // namespace gridslam::io
