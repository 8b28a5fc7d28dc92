// Trajectory files (docs/formats.md §7): one stamped pose per line, either the project's plain
// "timestamp x y theta" or TUM's "timestamp x y z qx qy qz qw" (z = 0, yaw-only quaternion). The
// timestamp is printed with 6 decimals exactly as parsed (common/time.hpp), poses at full
// precision (%.17g) so a write/read round trip is lossless. Which frame a trajectory is in is
// the writer's business (docs/frames.md); these functions only move numbers.
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/eval/stamped_pose.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::io {

/// { Time time; Pose2 pose; } (defined in eval, which io builds on).
using StampedPose = eval::StampedPose;

/// The trajectory entry of a frame: its printed timestamp and its pose in `trajectory_frame`
/// ("base": T_odom_base; "laser": T_odom_base * T_base_laser), given the robot's pose
/// `T_world_base` (e.g. the frame's odometry or a SLAM estimate).
StampedPose TrajectoryEntry(const Frame& frame, const Pose2& T_world_base,
                            const std::string& trajectory_frame);

/// Writes "timestamp x y theta" lines (timestamp with 6 decimals, poses at full precision).
/// Writes to a temporary file beside `path` and renames it, so no half file is left on failure.
Status WriteTrajectory(const std::string& path, const std::vector<StampedPose>& poses);

/// Writes TUM lines "timestamp x y z qx qy qz qw" with z = 0 and the yaw quaternion, sorted by
/// timestamp (stable), as TUM readers such as evo require; the plain format keeps the given order
/// (a log's own stamps may go backwards, and the benchmark relations are keyed on them).
Status WriteTrajectoryTum(const std::string& path, const std::vector<StampedPose>& poses);

/// Writes TUM if `path` ends in ".tum", else the plain format.
Status WriteTrajectoryByExtension(const std::string& path, const std::vector<StampedPose>& poses);

/// Reads either format, detected per line by its column count (4 = plain, 8 = TUM). Blank lines
/// and lines starting with '#' are skipped; any other line is an error naming file and line.
Result<std::vector<StampedPose>> ReadTrajectory(const std::string& path);

}  // namespace gridslam::io
