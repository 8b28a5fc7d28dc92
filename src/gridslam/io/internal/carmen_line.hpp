// Parses one CARMEN log line (docs/formats.md §1.2–1.3) into a message: the field layouts of ODOM,
// TRUEPOS, PARAM, SYNC, FLASER/RLASER, RAWLASER1..4 and ROBOTLASER1/2. FLASER/RLASER beam
// geometry is guessed as CARMEN's carmen_laser_guess_fov()/..._angle_increment() do. A malformed
// line gives an InvalidInput error naming file, line, message type and field. Internal to io/.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/io/carmen_options.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::io::internal {

/// The largest |x|, |y| a CARMEN pose or laser offset may have [m] (100 km: anything farther is
/// a corrupt number, and would make the fused map allocate without bound).
constexpr double kMaxCarmenCoordinate = 1e5;
/// The largest |theta| a CARMEN pose or beam angle may have [rad] (logs print unwrapped angles).
constexpr double kMaxCarmenAngle = 1e4;

enum class CarmenKind { kComment, kOdom, kTruePos, kParam, kSync, kLaser, kUnknown };

struct CarmenMessage {
  CarmenKind kind = CarmenKind::kComment;
  std::string_view tag;        ///< First token (message type).
  std::string_view time_text;  ///< The ipc_timestamp token as printed.
  Time time;                   ///< ipc_timestamp.
  /// The line has no ipc_timestamp (none left, or only `host logger_timestamp`); time is 0.
  bool time_missing = false;
  // ODOM: pose. TRUEPOS: pose = true pose, odom_pose = odometry.
  Pose2 pose;
  Pose2 odom_pose;
  // PARAM
  std::string_view param_name;
  std::string_view param_value;
  // Laser lines
  bool rear = false;  ///< RLASER, RAWLASER2/4, ROBOTLASER2 (the CARMEN rear/second laser).
  LaserScan scan;
  std::optional<Pose2> laser_pose;  ///< FLASER/RLASER first triple, ROBOTLASER laser pose.
  std::optional<Pose2> robot_pose;  ///< FLASER/RLASER odom triple, ROBOTLASER robot pose.
};

/// Splits `line` at whitespace into `tokens` (views into `line`).
void SplitFields(std::string_view line, std::vector<std::string_view>& tokens);

/// Classifies the first token; kUnknown for tags the reader does not know.
CarmenKind ClassifyTag(std::string_view tag);

/// Parses a tokenized line of a known kind. `file` and `line` name it in errors.
Status ParseCarmenMessage(const std::vector<std::string_view>& tokens, const CarmenOptions& options,
                          const std::string& file, long line, CarmenMessage& out);

/// CARMEN's field-of-view guess for FLASER/RLASER lines by beam count [rad].
double GuessLaserFov(int num_beams);
/// CARMEN's angular-resolution guess for FLASER/RLASER lines by beam count [rad].
double GuessLaserAngleIncrement(int num_beams);

/// The largest range that still counts as a hit for a line whose own maximum_range field is
/// `line_max_range` (<= 0 if none): the smallest of it, options.max_usable_range and the
/// configured no-return sentinels (less half a centimetre, the logs' precision).
double EffectiveRangeMax(const CarmenOptions& options, double line_max_range);

}  // namespace gridslam::io::internal
