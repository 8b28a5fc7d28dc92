// Bags in (ROS 1 .bag v2.0, MCAP, rosbag2 sqlite3 folder or .db3): loads a bag's scans,
// odometry and transforms, then assembles the Frames that the pipeline consumes.
//
// Assembly (AssembleBagFrames):
// - scans: the --scan-topic, else the only sensor_msgs/LaserScan topic; frames are ordered by
//   in storage order and keep header.stamp (the log time when it is zero) as their identity;
// - odometry: the --odom-topic (nav_msgs/Odometry), else TF odom_frame -> base_frame when the
//   frames are given, else the only Odometry topic, else TF odom -> base_link when /tf has it,
//   else none (frames with has_odometry = false and identity odometry). The pose is
//   interpolated at each scan stamp (linear in x, y, shortest arc in theta), clamped to the
//   first/last sample outside their span. TF odometry may end in an intermediate frame (e.g.
//   odom -> base_footprint): static transforms complete the chain to the base frame;
// - mounting: T_base_laser from the chain of transforms (/tf_static, and /tf transforms other
//   than the odometry) from the base frame to the scan's frame_id, through intermediate frames;
//   identity (with a warning) when there is none;
// - when the choice is ambiguous or a named topic is missing, the error lists the bag's topics
//   with their types and message counts.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/recording/bag_options.hpp"
#include "gridslam/recording/internal/bag_container.hpp"
#include "gridslam/recording/ros_messages.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::recording {

enum class BagFormat { kRos1, kMcap, kRosbag2Sqlite };

const char* BagFormatName(BagFormat format);

/// What a bag holds, decoded for the topics gridslam reads.
struct BagContents {
  BagFormat format = BagFormat::kRos1;
  std::vector<internal::BagTopic> topics;  ///< Every topic, with type and message count.
  std::int64_t first_log_ns = 0;           ///< Earliest / latest message log time [ns].
  std::int64_t last_log_ns = 0;
  std::map<std::string, std::vector<ScanMessage>> scans;         ///< By LaserScan topic.
  std::map<std::string, std::vector<OdometryMessage>> odometry;  ///< By Odometry topic.
  std::vector<TransformMessage> tf;         ///< /tf (and other TFMessage topics but /tf_static).
  std::vector<TransformMessage> tf_static;  ///< /tf_static.
  long skipped_malformed = 0;               ///< Undecodable messages skipped (lenient).
};

/// Loads a bag: a ROS 1 .bag, an .mcap, a .db3 or a rosbag2 folder. Errors name the path.
Result<BagContents> LoadBag(const std::string& path, bool lenient);

/// Loads a ROS 1 bag or an MCAP file from memory (also the fuzzing entry point: any bytes give
/// a value or an error, never a crash or unbounded allocation).
Result<BagContents> LoadBagBytes(std::span<const std::uint8_t> bytes, bool lenient);

/// What AssembleBagFrames chose, for messages and reports.
struct BagAssembly {
  std::string scan_topic;
  std::string odometry_source;  ///< "/odom", "tf odom->base_link" or "none".
  std::string base_frame;
  std::string laser_frame;
  bool mounting_from_tf = false;
  long odometry_samples = 0;
  long scans_outside_odometry = 0;  ///< Scans clamped to the first/last odometry sample.
  long repaired_timestamps = 0;     ///< Scan and odometry stamps changed by the repair.
};

/// The frames of a loaded bag (see the file comment), in the bag's storage order. Frame::time is
/// header.stamp; with repair_timestamps, Frame::corrected_time (and the odometry stamps used for
/// interpolation) go through the CARMEN timestamp repair (io/timestamp_repair.hpp), which leaves
/// correct stamps unchanged. max_usable_range caps range_max [m].
Result<std::vector<Frame>> AssembleBagFrames(const BagContents& bag, const BagOptions& options,
                                             double max_usable_range, BagAssembly* assembly,
                                             bool repair_timestamps = true);

/// "  /scan  sensor_msgs/LaserScan  13631 messages" lines, one per topic.
std::string ListTopics(const BagContents& bag);

/// Runs the whole decoder on bytes (ROS 1 or MCAP): load, then assemble with default options.
/// For fuzz harnesses; returns the number of frames or the error.
Result<std::size_t> DecodeBagForFuzzing(std::span<const std::uint8_t> bytes);

}  // namespace gridslam::recording
