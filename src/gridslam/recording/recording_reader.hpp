// One streaming interface over every recording gridslam reads: CARMEN logs (plain or gzip) and
// bags (ROS 1 .bag, MCAP, rosbag2 sqlite3 folder or .db3). OpenRecording sniffs the content
// (content_sniffer.hpp), not the extension, and refuses anything else with InvalidInput saying
// what the file looks like. CARMEN logs are streamed line by line; a bag is decoded when it is
// opened (odometry interpolation needs the samples after each scan) and its frames are then
// handed out one by one. A recording that yields no laser scan is an error, not an empty map.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/io/carmen_options.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/recording/bag_options.hpp"
#include "gridslam/recording/bag_reader.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::recording {

enum class RecordingFormat { kCarmen, kRos1Bag, kMcap, kRosbag2 };

const char* RecordingFormatName(RecordingFormat format);

struct RecordingOptions {
  io::CarmenOptions log;  ///< CARMEN reading (max_usable_range and lenient apply to bags too).
  BagOptions bag;
};

class RecordingReader {
 public:
  static Result<RecordingReader> Open(const std::string& path, const RecordingOptions& options);

  RecordingReader(RecordingReader&&) noexcept;
  RecordingReader& operator=(RecordingReader&&) noexcept;
  ~RecordingReader();

  /// The next frame, nullopt at the end, or an error (also when the recording has no scan).
  Result<std::optional<Frame>> Next();

  [[nodiscard]] RecordingFormat Format() const;
  /// Counts in the CARMEN reader's terms; for bags: lines = messages, odometry = odometry
  /// samples, scans_without_odometry = scans clamped outside the odometry's time span.
  [[nodiscard]] const io::CarmenStats& Stats() const;
  /// Size of the recording [bytes] (a rosbag2 folder: its .db3 files) and how much of it has
  /// been delivered (CARMEN: bytes read; bags: the share of frames handed out), for progress.
  [[nodiscard]] long TotalBytes() const;
  [[nodiscard]] long BytesRead() const;
  /// What the bag assembly chose (nullptr for CARMEN logs).
  [[nodiscard]] const BagAssembly* Assembly() const;

 private:
  struct State;
  explicit RecordingReader(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

/// Reads a whole recording into memory.
Result<std::vector<Frame>> ReadRecording(const std::string& path, const RecordingOptions& options,
                                         io::CarmenStats* stats = nullptr);

}  // namespace gridslam::recording
