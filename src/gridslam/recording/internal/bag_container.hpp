// Readers of the three bag containers: ROS 1 bag v2.0, MCAP and rosbag2 sqlite3. Each walks the
// file in storage order and hands every message to a sink, with the topic table it has built
// so far (topics are appended as their connection/channel records appear; counts grow as
// messages are delivered). Structural damage (truncation, bad magic, corrupt chunk, a record
// that overruns its container) is an InvalidInput error naming the byte offset.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/recording/ros_messages.hpp"

namespace gridslam::recording::internal {

struct BagTopic {
  std::string topic;
  std::string type;  ///< ROS type name as stored ("sensor_msgs/LaserScan", ".../msg/...").
  MessageEncoding encoding = MessageEncoding::kRos1;
  long count = 0;  ///< Messages delivered so far.
};

/// Called per message: index into the topic table, log (receive) time [ns], serialized bytes.
using MessageSink = std::function<Status(std::size_t topic, std::int64_t log_time_ns,
                                         std::span<const std::uint8_t>)>;

inline constexpr std::string_view kRos1Magic = "#ROSBAG V2.0\n";
inline constexpr std::string_view kMcapMagic = "\x89MCAP0\r\n";

Status ReadRos1Bag(std::span<const std::uint8_t> file, std::vector<BagTopic>* topics,
                   const MessageSink& sink);
Status ReadMcap(std::span<const std::uint8_t> file, std::vector<BagTopic>* topics,
                const MessageSink& sink);
/// One or more .db3 files of a rosbag2 (in split order), messages in timestamp order per file.
Status ReadRosbag2Sqlite(const std::vector<std::string>& db3_files, std::vector<BagTopic>* topics,
                         const MessageSink& sink);

}  // namespace gridslam::recording::internal
