// Tells what a file is from its content (magic bytes and structure, not its extension), so that
// a recording reader is chosen by what the file holds and anything else is refused with a
// message saying what it looks like ("looks like a g2o graph", "a PNG image", ...).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace gridslam::recording {

enum class ContentKind {
  kCarmenLog,    ///< CARMEN text log (plain or gzip).
  kRos1Bag,      ///< ROS 1 bag v2.0.
  kMcap,         ///< MCAP.
  kRosbag2,      ///< rosbag2 folder or sqlite3 .db3.
  kNotRecording  ///< Anything else; `description` says what it looks like.
};

struct SniffResult {
  ContentKind kind = ContentKind::kNotRecording;
  std::string description;  ///< E.g. "a g2o pose graph", "an empty file", "a PNG image".
};

/// Classifies the first bytes of a file (decompressed when `head` is gzip's inner stream).
SniffResult SniffBytes(std::span<const std::uint8_t> head);

/// Classifies a path: a folder (rosbag2), or a file by its first 64 KiB (gzip looked into).
SniffResult SniffPath(const std::string& path);

}  // namespace gridslam::recording
