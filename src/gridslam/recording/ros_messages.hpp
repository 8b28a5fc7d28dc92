// The three ROS message types gridslam reads from bags (sensor_msgs/LaserScan, nav_msgs/Odometry,
// tf2_msgs/TFMessage), decoded from either wire format: ROS 1 serialization (packed little
// endian, strings without terminator, header with seq) or ROS 2 CDR (4-byte encapsulation
// header, aligned primitives, NUL-terminated strings, no seq). Poses are reduced to the plane
// (x, y, yaw). Decoding never reads past the buffer: a short or inconsistent message is an error.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::recording {

/// How a bag's message bytes are serialized.
enum class MessageEncoding { kRos1, kCdr };

/// What a topic carries, as far as gridslam is concerned.
enum class MessageKind { kLaserScan, kOdometry, kTf, kOther };

/// Kind of a ROS type name ("sensor_msgs/LaserScan" or "sensor_msgs/msg/LaserScan").
MessageKind KindOfType(const std::string& type);

struct ScanMessage {
  std::uint64_t sequence = 0;  ///< Position in the bag's storage order (set by the bag reader).
  std::int64_t stamp_ns = 0;   ///< header.stamp [ns].
  std::string frame_id;
  double angle_max = 0.0;  ///< [rad] (LaserScan keeps angle_min and the increment).
  LaserScan scan;
};

struct OdometryMessage {
  std::uint64_t sequence = 0;
  std::int64_t stamp_ns = 0;
  std::string frame_id;        ///< Odometry frame (e.g. odom).
  std::string child_frame_id;  ///< Robot frame (e.g. base_link).
  Pose2 T_odom_base;
};

struct TransformMessage {
  std::uint64_t sequence = 0;
  std::int64_t stamp_ns = 0;
  std::string parent;  ///< header.frame_id.
  std::string child;   ///< child_frame_id.
  Pose2 T_parent_child;
};

Result<ScanMessage> DecodeLaserScan(std::span<const std::uint8_t> data, MessageEncoding encoding);
Result<OdometryMessage> DecodeOdometry(std::span<const std::uint8_t> data,
                                       MessageEncoding encoding);
Result<std::vector<TransformMessage>> DecodeTfMessage(std::span<const std::uint8_t> data,
                                                      MessageEncoding encoding);

/// gridslam's LaserScan from the fields of a sensor_msgs/LaserScan, as every reader builds it (bags
/// and the ROS node): InvalidInput without beams or with a non-finite geometry; a non-finite or
/// negative range_min becomes 0. NaN, inf and out-of-range readings stay and are no-returns.
Result<LaserScan> MakeLaserScan(float angle_min, float angle_increment, float range_min,
                                float range_max, std::vector<float> ranges);

/// Planar yaw of a unit quaternion (x, y, z, w) [rad].
double YawOfQuaternion(double x, double y, double z, double w);

}  // namespace gridslam::recording
