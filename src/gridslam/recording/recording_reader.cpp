#include "gridslam/recording/recording_reader.hpp"

#include <filesystem>

#include <spdlog/spdlog.h>

#include "gridslam/recording/content_sniffer.hpp"

namespace gridslam::recording {

struct RecordingReader::State {
  std::string path;
  RecordingFormat format = RecordingFormat::kCarmen;
  std::optional<io::CarmenReader> carmen;
  std::vector<Frame> frames;
  std::size_t next = 0;
  io::CarmenStats bag_stats;
  BagAssembly assembly;
  long delivered = 0;
  long total_bytes = 0;
};

namespace {

long SizeOf(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    long total = 0;
    for (const auto& entry : fs::directory_iterator(path, ec)) {
      const auto size = entry.is_regular_file(ec) ? entry.file_size(ec) : 0;
      total += ec ? 0 : static_cast<long>(size);
    }
    return total;
  }
  const auto size = fs::file_size(path, ec);
  return ec ? 0 : static_cast<long>(size);
}

}  // namespace

const char* RecordingFormatName(RecordingFormat format) {
  switch (format) {
    case RecordingFormat::kCarmen:
      return "CARMEN log";
    case RecordingFormat::kRos1Bag:
      return "ROS 1 bag";
    case RecordingFormat::kMcap:
      return "MCAP";
    case RecordingFormat::kRosbag2:
      return "rosbag2 sqlite3";
  }
  return "?";
}

RecordingReader::RecordingReader(std::unique_ptr<State> state) : state_(std::move(state)) {}
RecordingReader::RecordingReader(RecordingReader&&) noexcept = default;
RecordingReader& RecordingReader::operator=(RecordingReader&&) noexcept = default;
RecordingReader::~RecordingReader() = default;

Result<RecordingReader> RecordingReader::Open(const std::string& path,
                                              const RecordingOptions& options) {
  const SniffResult sniff = SniffPath(path);
  auto state = std::make_unique<State>();
  state->path = path;
  state->total_bytes = SizeOf(path);
  switch (sniff.kind) {
    case ContentKind::kNotRecording:
      if (sniff.description == "a file that cannot be opened") {
        return NotFound("cannot open", path);
      }
      return InvalidInput(
          "not a recording (CARMEN log or ROS bag): it looks like " + sniff.description, path);
    case ContentKind::kCarmenLog: {
      auto reader = io::CarmenReader::Open(path, options.log);
      if (!reader.ok()) {
        return reader.error();
      }
      state->carmen.emplace(std::move(reader).value());
      state->format = RecordingFormat::kCarmen;
      return RecordingReader(std::move(state));
    }
    case ContentKind::kRos1Bag:
    case ContentKind::kMcap:
    case ContentKind::kRosbag2:
      break;
  }
  auto bag = LoadBag(path, options.log.lenient);
  if (!bag.ok()) {
    return bag.error();
  }
  state->format = bag.value().format == BagFormat::kRos1   ? RecordingFormat::kRos1Bag
                  : bag.value().format == BagFormat::kMcap ? RecordingFormat::kMcap
                                                           : RecordingFormat::kRosbag2;
  auto frames = AssembleBagFrames(bag.value(), options.bag, options.log.max_usable_range,
                                  &state->assembly, options.log.repair_timestamps);
  if (!frames.ok()) {
    Error e = frames.error();
    e.file = path;
    return e;
  }
  state->frames = std::move(frames).value();
  if (options.log.laser_offset.size() == 3) {  // an explicit mounting wins over the bag's TF
    const Pose2 T_base_laser(options.log.laser_offset[0], options.log.laser_offset[1],
                             options.log.laser_offset[2]);
    for (Frame& f : state->frames) {
      f.T_base_laser = T_base_laser;
    }
  }
  io::CarmenStats& s = state->bag_stats;
  for (const internal::BagTopic& t : bag.value().topics) {
    s.lines += t.count;
  }
  s.odometry = state->assembly.odometry_samples;
  s.scans_without_odometry = state->assembly.scans_outside_odometry;
  s.skipped_malformed = bag.value().skipped_malformed;
  s.repaired_timestamps = state->assembly.repaired_timestamps;
  const BagAssembly& a = state->assembly;
  spdlog::info("{}: {} scans on {} ({}), odometry {} ({} samples), base {}, laser {}", path,
               state->frames.size(), a.scan_topic, RecordingFormatName(state->format),
               a.odometry_source, a.odometry_samples, a.base_frame, a.laser_frame);
  return RecordingReader(std::move(state));
}

Result<std::optional<Frame>> RecordingReader::Next() {
  std::optional<Frame> frame;
  if (state_->carmen) {
    auto next = state_->carmen->Next();
    if (!next.ok()) {
      return next.error();
    }
    frame = std::move(next).value();
  } else if (state_->next < state_->frames.size()) {
    frame = std::move(state_->frames[state_->next++]);
    ++state_->bag_stats.scans;
  }
  if (!frame && state_->delivered == 0 && state_->carmen) {
    return io::NoScansError(state_->path, state_->carmen->Stats());  // what the log held
  }
  if (!frame && state_->delivered == 0) {
    return InvalidInput(
        std::string("the ") + RecordingFormatName(state_->format) + " has no laser scans",
        state_->path);
  }
  state_->delivered += frame ? 1 : 0;
  return frame;
}

RecordingFormat RecordingReader::Format() const { return state_->format; }

const io::CarmenStats& RecordingReader::Stats() const {
  return state_->carmen ? state_->carmen->Stats() : state_->bag_stats;
}

long RecordingReader::TotalBytes() const { return state_->total_bytes; }

long RecordingReader::BytesRead() const {
  if (state_->carmen) {
    return state_->carmen->BytesRead();
  }
  if (state_->frames.empty()) {
    return state_->total_bytes;
  }
  return static_cast<long>(static_cast<double>(state_->total_bytes) *
                           static_cast<double>(state_->next) /
                           static_cast<double>(state_->frames.size()));
}

const BagAssembly* RecordingReader::Assembly() const {
  return state_->carmen ? nullptr : &state_->assembly;
}

Result<std::vector<Frame>> ReadRecording(const std::string& path, const RecordingOptions& options,
                                         io::CarmenStats* stats) {
  auto reader = RecordingReader::Open(path, options);
  if (!reader.ok()) {
    return reader.error();
  }
  return io::ReadAllFrames(reader.value(), stats);
}

}  // namespace gridslam::recording
