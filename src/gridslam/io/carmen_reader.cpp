#include "gridslam/io/carmen_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <deque>
#include <numbers>

#include "gridslam/common/logging.hpp"
#include "gridslam/io/internal/carmen_line.hpp"
#include "gridslam/io/internal/gz_line_reader.hpp"
#include "gridslam/io/timestamp_repair.hpp"

namespace gridslam::io {
namespace internal {

namespace {
constexpr std::size_t kRepairLag = 32;          // stream entries kept for timestamp repair
constexpr std::size_t kMaxPendingScans = 4096;  // hard bound of the look-ahead buffer
constexpr std::size_t kMaxOdometrySamples = 65536;
constexpr std::size_t kMaxTruePosSamples = 256;
constexpr double kOdometryKeep = 1.0;       // odometry kept before the last scan [s]
constexpr double kTruePosTolerance = 0.25;  // TRUEPOS attached within this of a scan [s]
}  // namespace

struct TimedPose {
  Time time;
  Pose2 pose;
};

struct PendingScan {
  std::uint64_t seq = 0;
  Frame frame;
  bool needs_odometry = false;
  bool time_known = false;
};

/// A laser mounting assembled from PARAM lines (x, y, theta parts may come separately).
struct ParamMounting {
  double xyz[3] = {0.0, 0.0, 0.0};
  bool known = false;
};

struct CarmenState {
  std::string path;
  CarmenOptions options;
  GzLineReader reader;
  CarmenStats stats;
  std::string line;
  std::vector<std::string_view> tokens;
  CarmenMessage message;
  bool eof = false;
  std::uint64_t next_seq = 0;
  std::optional<Pose2> configured_mounting;
  ParamMounting front;
  ParamMounting rear;

  TimestampRepairer repair{kRepairLag};  // ODOM and laser lines, in file order
  std::deque<std::pair<std::uint64_t, TimedPose>> odom_waiting;  // ODOM awaiting repair
  std::deque<PendingScan> scans;                                 // file order
  std::deque<TimedPose> odometry;                                // sorted by corrected time
  std::deque<TimedPose> truepos;                                 // recent TRUEPOS lines
  std::optional<Time> newest_time;  // latest printed time read (look-ahead bound)
  std::optional<Time> last_emitted;
  enum class TimeSource { kUndecided, kLog, kSynthetic };
  TimeSource time_source = TimeSource::kUndecided;
  long synthetic_lasers = 0;   // laser lines given a synthesized time so far
  std::string synthetic_text;  // printed form of the latest synthesized time
  bool warned_odometry_in_laser_pose = false;

  Result<std::optional<Frame>> Next();
  Status ReadOneLine();
  Status Handle(long line_number);
  Status Dispatch(long line_number);
  Status HandleParam(long line_number);
  Status ResolveTime(long line_number);
  void Drain();
  std::optional<Frame> TryEmit();
  Pose2 Mounting(const CarmenMessage& m) const;
  Pose2 OdometryAt(Time t);
  void AddOdometry(Time t, const Pose2& pose);
};

Pose2 CarmenState::Mounting(const CarmenMessage& m) const {
  if (configured_mounting) {
    return *configured_mounting;
  }
  const ParamMounting& param = m.rear ? rear : front;
  if (param.known) {
    // A rear laser looks backwards (CARMEN's robot_rearlaser_* parameters).
    return {param.xyz[0], param.xyz[1], param.xyz[2] + (m.rear ? std::numbers::pi : 0.0)};
  }
  if (m.laser_pose && m.robot_pose) {
    return m.robot_pose->Inverse() * *m.laser_pose;  // as g2o's RobotLaser::read
  }
  return Pose2::Identity();
}

void CarmenState::AddOdometry(Time t, const Pose2& pose) {
  if (odometry.empty() || odometry.back().time <= t) {
    odometry.push_back({t, pose});
  } else {
    auto it = std::upper_bound(odometry.begin(), odometry.end(), t,
                               [](Time a, const TimedPose& b) { return a < b.time; });
    odometry.insert(it, {t, pose});
  }
  if (odometry.size() > kMaxOdometrySamples) {
    odometry.pop_front();
  }
}

Pose2 CarmenState::OdometryAt(Time t) {
  if (odometry.empty()) {
    ++stats.scans_without_odometry;
    return Pose2::Identity();
  }
  auto it = std::lower_bound(odometry.begin(), odometry.end(), t,
                             [](const TimedPose& a, Time b) { return a.time < b; });
  if (it == odometry.end()) {
    ++stats.scans_without_odometry;
    return odometry.back().pose;
  }
  if (it->time == t) {
    return it->pose;
  }
  if (it == odometry.begin()) {
    ++stats.scans_without_odometry;
    return it->pose;
  }
  const TimedPose& a = *(it - 1);
  const double alpha = ToSeconds(t - a.time) / ToSeconds(it->time - a.time);
  return Interpolate(a.pose, it->pose, alpha);
}

Status CarmenState::HandleParam(long line_number) {
  static constexpr const char* kNames[2][3] = {
      {"robot_frontlaser_offset", "robot_frontlaser_side_offset",
       "robot_frontlaser_angular_offset"},
      {"robot_rearlaser_offset", "robot_rearlaser_side_offset", "robot_rearlaser_angular_offset"}};
  ++stats.params;
  for (int side = 0; side < 2; ++side) {
    for (int k = 0; k < 3; ++k) {
      if (message.param_name != kNames[side][k]) {
        continue;
      }
      double value = 0.0;
      const std::string_view v = message.param_value;
      auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
      if (ec != std::errc() || ptr != v.data() + v.size() || !std::isfinite(value)) {
        return InvalidInput("PARAM " + std::string(message.param_name) +
                                ": field 'param_value': "
                                "cannot read '" +
                                std::string(v) + "' as a number",
                            path, line_number);
      }
      const double bound = k < 2 ? kMaxCarmenCoordinate : kMaxCarmenAngle;
      if (std::abs(value) > bound) {
        return InvalidInput("PARAM " + std::string(message.param_name) +
                                ": field 'param_value': " + std::string(v) + " is beyond +-" +
                                std::to_string(static_cast<long long>(bound)),
                            path, line_number);
      }
      ParamMounting& m = side == 0 ? front : rear;
      m.xyz[k] = value;
      m.known = true;
    }
  }
  return Status::Ok();
}

Status CarmenState::Handle(long line_number) {
  Status status;
  if (line.find('\0') != std::string::npos) {
    status = InvalidInput("a NUL byte in the line (a binary file, not a CARMEN log?)", path,
                          line_number);
  } else {
    SplitFields(line, tokens);
    status = ParseCarmenMessage(tokens, options, path, line_number, message);
  }
  if (status.ok()) {
    status = Dispatch(line_number);
  }
  if (!status.ok()) {
    if (!options.lenient) {
      return status;
    }
    if (++stats.skipped_malformed <= 5) {
      GRIDSLAM_LOG_WARN("skipping malformed line: {}", status.error().ToString());
    }
  }
  return Status::Ok();
}

Status CarmenState::ResolveTime(long line_number) {
  const bool untimed = message.time_missing || message.time == Time();
  if (time_source == TimeSource::kUndecided &&
      (message.kind == CarmenKind::kLaser || message.time_missing)) {
    time_source = untimed ? TimeSource::kSynthetic : TimeSource::kLog;
    if (time_source == TimeSource::kSynthetic) {
      GRIDSLAM_LOG_WARN(
          "{}:{}: the log has no timestamps ({}): times are synthesized from message order, one "
          "laser line every {} s (log.timestamp_rate = {} Hz; --rate sets it)",
          path, line_number, message.time_missing ? "the field is missing" : "the field is 0",
          1.0 / options.timestamp_rate, options.timestamp_rate);
    }
  }
  if (time_source == TimeSource::kSynthetic) {
    message.time =
        Time(SecondsToDuration(static_cast<double>(synthetic_lasers) / options.timestamp_rate));
    synthetic_text = FormatSeconds(message.time, 6);
    message.time_text = synthetic_text;
    message.time_missing = false;
    ++stats.synthesized_timestamps;
    if (message.kind == CarmenKind::kLaser) {
      ++synthetic_lasers;
    }
  } else if (message.time_missing) {
    return InvalidInput(std::string(message.tag) +
                            ": field 'ipc_timestamp' missing (the log's first laser line has one)",
                        path, line_number);
  }
  return Status::Ok();
}

Status CarmenState::Dispatch(long line_number) {
  if (message.kind == CarmenKind::kLaser || message.kind == CarmenKind::kOdom ||
      message.kind == CarmenKind::kTruePos) {
    GRIDSLAM_RETURN_IF_ERROR(ResolveTime(line_number));
  }
  switch (message.kind) {
    case CarmenKind::kComment:
      ++stats.comments;
      return Status::Ok();
    case CarmenKind::kUnknown:
      ++stats.skipped_unknown;
      if (stats.unknown_types.insert(std::string(message.tag)).second) {
        GRIDSLAM_LOG_WARN("{}:{}: skipping unknown message type '{}' (warned once per type)", path,
                          line_number, message.tag);
      }
      return Status::Ok();
    case CarmenKind::kSync:
      return Status::Ok();
    case CarmenKind::kParam:
      return HandleParam(line_number);
    case CarmenKind::kTruePos:
      ++stats.truepos;
      truepos.push_back({message.time, message.pose});
      if (truepos.size() > kMaxTruePosSamples) {
        truepos.pop_front();
      }
      return Status::Ok();
    case CarmenKind::kOdom: {
      if (message.time <= Time{}) {
        ++stats.skipped_bad_odometry;
        return Status::Ok();
      }
      ++stats.odometry;
      newest_time = newest_time ? std::max(*newest_time, message.time) : message.time;
      const std::uint64_t seq = next_seq++;
      if (options.repair_timestamps) {
        odom_waiting.emplace_back(seq, TimedPose{message.time, message.pose});
        repair.Push(seq, message.time_text, message.time);
      } else {
        AddOdometry(message.time, message.pose);
      }
      return Status::Ok();
    }
    case CarmenKind::kLaser: {
      if (time_source == TimeSource::kSynthetic && message.robot_pose && message.laser_pose &&
          message.robot_pose->x() == 0.0 && message.robot_pose->y() == 0.0 &&
          message.robot_pose->theta() == 0.0) {
        // An old untimed FLASER whose odometry triple is all zero: the laser triple is the
        // odometry (orebro), the laser at the robot centre.
        if (!warned_odometry_in_laser_pose && !IsApprox(*message.laser_pose, Pose2())) {
          warned_odometry_in_laser_pose = true;
          GRIDSLAM_LOG_WARN(
              "{}:{}: the laser line's odometry fields are 0: its laser pose is "
              "read as the odometry",
              path, line_number);
        }
        message.robot_pose = message.laser_pose;
      }
      newest_time = newest_time ? std::max(*newest_time, message.time) : message.time;
      PendingScan scan;
      scan.seq = next_seq++;
      scan.frame.time = message.time;
      scan.frame.corrected_time = message.time;
      scan.frame.scan = std::move(message.scan);
      scan.frame.T_base_laser = Mounting(message);
      scan.frame.source_line = line_number;
      scan.needs_odometry = !message.robot_pose.has_value();
      if (message.robot_pose) {
        scan.frame.T_odom_base = *message.robot_pose;
      }
      scan.time_known = !options.repair_timestamps;
      if (options.repair_timestamps) {
        repair.Push(scan.seq, message.time_text, message.time);
      }
      scans.push_back(std::move(scan));
      return Status::Ok();
    }
  }
  return Status::Ok();
}

void CarmenState::Drain() {
  while (auto r = repair.Pop()) {
    if (!odom_waiting.empty() && odom_waiting.front().first == r->first) {
      if (r->second != odom_waiting.front().second.time) {
        ++stats.repaired_timestamps;
      }
      AddOdometry(r->second, odom_waiting.front().second.pose);
      odom_waiting.pop_front();
      continue;
    }
    auto it = std::lower_bound(scans.begin(), scans.end(), r->first,
                               [](const PendingScan& s, std::uint64_t seq) { return s.seq < seq; });
    GRIDSLAM_CHECK(it != scans.end() && it->seq == r->first) << "timestamp repair out of sync";
    it->frame.corrected_time = r->second;
    it->time_known = true;
    if (r->second != it->frame.time) {
      ++stats.repaired_timestamps;
    }
  }
}

std::optional<Frame> CarmenState::TryEmit() {
  if (scans.empty() || !scans.front().time_known) {
    return std::nullopt;
  }
  PendingScan& s = scans.front();
  const Time t = s.frame.corrected_time;
  if (s.needs_odometry) {
    const bool covered = !odometry.empty() && odometry.back().time >= t;
    const bool waited_enough =
        newest_time && ToSeconds(*newest_time - t) > options.max_lookahead && odom_waiting.empty();
    if (!covered && !eof && !waited_enough && scans.size() < kMaxPendingScans) {
      return std::nullopt;
    }
    // A log without any odometry (no ODOM line so far, pose-less laser lines): scan matching
    // alone; the identity is a placeholder.
    s.frame.has_odometry = stats.odometry > 0;
    s.frame.T_odom_base = OdometryAt(t);
  }
  if (!truepos.empty()) {
    const auto nearest = std::min_element(truepos.begin(), truepos.end(), [&](auto& a, auto& b) {
      return std::abs(ToSeconds(a.time - s.frame.time)) <
             std::abs(ToSeconds(b.time - s.frame.time));
    });
    if (std::abs(ToSeconds(nearest->time - s.frame.time)) <= kTruePosTolerance) {
      s.frame.T_world_base_true = nearest->pose;
    }
  }
  Frame frame = std::move(s.frame);
  scans.pop_front();
  last_emitted = t;
  while (odometry.size() >= 2 && ToSeconds(t - odometry[1].time) > kOdometryKeep) {
    odometry.pop_front();
  }
  ++stats.scans;
  return frame;
}

Status CarmenState::ReadOneLine() {
  Status status;
  if (!reader.ReadLine(line, status)) {
    if (!status.ok()) {
      return status;
    }
    eof = true;
    repair.Flush();
    return Status::Ok();
  }
  ++stats.lines;
  return Handle(stats.lines);
}

Result<std::optional<Frame>> CarmenState::Next() {
  while (true) {
    Drain();
    if (auto frame = TryEmit()) {
      return std::optional<Frame>(std::move(*frame));
    }
    if (eof) {
      GRIDSLAM_CHECK(scans.empty()) << "scans left after the end of the log";
      return std::optional<Frame>();
    }
    GRIDSLAM_RETURN_IF_ERROR(ReadOneLine());
  }
}

}  // namespace internal

CarmenReader::CarmenReader() : state_(std::make_unique<internal::CarmenState>()) {}
CarmenReader::CarmenReader(CarmenReader&&) noexcept = default;
CarmenReader& CarmenReader::operator=(CarmenReader&&) noexcept = default;
CarmenReader::~CarmenReader() = default;

Result<CarmenReader> CarmenReader::Open(const std::string& path, const CarmenOptions& options) {
  GRIDSLAM_RETURN_IF_ERROR(options.Validate());
  CarmenReader reader;
  auto& s = *reader.state_;
  s.path = path;
  s.options = options;
  if (options.laser_offset.size() == 3) {
    s.configured_mounting =
        Pose2(options.laser_offset[0], options.laser_offset[1], options.laser_offset[2]);
  }
  GRIDSLAM_RETURN_IF_ERROR(s.reader.Open(path));
  return reader;
}

Result<std::optional<Frame>> CarmenReader::Next() { return state_->Next(); }

const CarmenStats& CarmenReader::Stats() const { return state_->stats; }

long CarmenReader::BytesRead() const { return state_->reader.FileOffset(); }

Error NoScansError(const std::string& path, const CarmenStats& stats) {
  std::string held = std::to_string(stats.lines) + " lines";
  if (stats.lines > 0) {
    held += ": " + std::to_string(stats.comments) + " comments or empty, " +
            std::to_string(stats.odometry + stats.skipped_bad_odometry) + " ODOM, " +
            std::to_string(stats.params) + " PARAM, " + std::to_string(stats.skipped_unknown) +
            " of unknown types";
    for (const std::string& type : stats.unknown_types) {
      held += (type == *stats.unknown_types.begin() ? " (" : ", ") + type;
    }
    held += stats.unknown_types.empty() ? "" : ")";
    if (stats.skipped_malformed > 0) {
      held += ", " + std::to_string(stats.skipped_malformed) + " malformed (skipped)";
    }
  }
  return InvalidInput("no laser scan in the log (" + held +
                          "); expected FLASER, RLASER, RAWLASER1..4 or ROBOTLASER1/2 lines; "
                          "nothing written",
                      path);
}

Result<std::vector<Frame>> ReadCarmenLog(const std::string& path, const CarmenOptions& options,
                                         CarmenStats* stats) {
  auto reader = CarmenReader::Open(path, options);
  if (!reader.ok()) {
    return reader.error();
  }
  return ReadAllFrames(reader.value(), stats);
}

Result<std::vector<Frame>> ReadCarmenLog(const std::string& path, const CarmenOptions& options) {
  return ReadCarmenLog(path, options, nullptr);
}

}  // namespace gridslam::io
