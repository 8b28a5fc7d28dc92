#include "gridslam/io/carmen_writer.hpp"

#include <cstdio>
#include <utility>

#include "gridslam/io/atomic_file.hpp"

namespace gridslam::io {
namespace {

constexpr const char* kHeader =
    "# CARMEN Logfile\n"
    "# file format is one message per line\n"
    "# message_name [message contents] ipc_timestamp ipc_hostname logger_timestamp\n"
    "# message formats defined: PARAM SYNC ODOM TRUEPOS RAWLASER1 ROBOTLASER1 FLASER\n"
    "# PARAM param_name param_value\n"
    "# ODOM x y theta tv rv accel\n"
    "# TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta\n"
    "# RAWLASER1 laser_type start_angle field_of_view angular_resolution maximum_range "
    "accuracy remission_mode num_readings [range_readings] num_remissions [remission values]\n"
    "# ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range "
    "accuracy remission_mode num_readings [range_readings] num_remissions [remission values] "
    "laser_pose_x laser_pose_y laser_pose_theta robot_pose_x robot_pose_y robot_pose_theta "
    "laser_tv laser_rv forward_safety_dist side_safety_dist turn_axis\n"
    "# FLASER num_readings [range_readings] x y theta odom_x odom_y odom_theta\n";

/// Appends printf(format, value). %f of a huge value prints hundreds of digits: the text is
/// measured first, so it never reads past a fixed buffer (issue 17: 1e308 wrote stack bytes).
void AppendF(std::string& out, const char* format, double value) {
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof(buffer), format, value);
  if (n < 0) {
    return;
  }
  if (static_cast<std::size_t>(n) < sizeof(buffer)) {
    out.append(buffer, static_cast<std::size_t>(n));
    return;
  }
  const std::size_t size = out.size();
  out.resize(size + static_cast<std::size_t>(n) + 1);
  std::snprintf(out.data() + size, static_cast<std::size_t>(n) + 1, format, value);
  out.resize(size + static_cast<std::size_t>(n));
}

void AppendPose(std::string& out, const Pose2& pose) {
  AppendF(out, "%f ", pose.x());
  AppendF(out, "%f ", pose.y());
  AppendF(out, "%f ", pose.theta());
}

/// `ipc_timestamp host logger_timestamp\n`.
void AppendTrailer(std::string& out, Time time, const std::string& host, Time logger_start) {
  out += FormatSeconds(time, 6);
  out += ' ';
  out += host;
  out += ' ';
  out += FormatSeconds(Time(time - logger_start), 6);
  out += '\n';
}

void AppendRanges(std::string& out, const LaserScan& scan) {
  out += std::to_string(scan.ranges.size());
  out += ' ';
  for (const float r : scan.ranges) {
    AppendF(out, "%.2f ", static_cast<double>(r));
  }
}

void AppendGeometry(std::string& out, const LaserScan& scan, const CarmenWriterOptions& options) {
  out += std::to_string(options.laser_type);
  out += ' ';
  const double fov = scan.ranges.empty()
                         ? 0.0
                         : static_cast<double>(scan.ranges.size() - 1) * scan.angle_increment;
  AppendF(out, "%f ", scan.angle_min);
  AppendF(out, "%f ", fov);
  AppendF(out, "%f ", scan.angle_increment);
  AppendF(out, "%f ", scan.range_max);
  AppendF(out, "%f ", options.accuracy);
  out += "0 ";  // remission_mode OFF
  AppendRanges(out, scan);
  out += "0 ";  // num_remissions
}

}  // namespace

std::string FormatOdometryLine(const CarmenOdometry& odometry, const std::string& hostname,
                               Time logger_start) {
  std::string out = "ODOM ";
  AppendPose(out, odometry.pose);
  AppendF(out, "%f ", odometry.tv);
  AppendF(out, "%f ", odometry.rv);
  AppendF(out, "%f ", odometry.accel);
  AppendTrailer(out, odometry.time, hostname, logger_start);
  return out;
}

std::string FormatLaserLines(const Frame& frame, const CarmenWriterOptions& options,
                             Time logger_start) {
  std::string out;
  if (options.write_truepos && frame.T_world_base_true.has_value()) {
    out += "TRUEPOS ";
    AppendPose(out, *frame.T_world_base_true);
    AppendPose(out, frame.T_odom_base);
    AppendTrailer(out, frame.time, options.hostname, logger_start);
  }
  const Pose2 T_odom_laser = frame.T_odom_laser();
  switch (options.laser_message) {
    case CarmenLaserMessage::kRawLaser1:
      out += "RAWLASER1 ";
      AppendGeometry(out, frame.scan, options);
      break;
    case CarmenLaserMessage::kRobotLaser1:
      out += "ROBOTLASER1 ";
      AppendGeometry(out, frame.scan, options);
      AppendPose(out, T_odom_laser);
      AppendPose(out, frame.T_odom_base);
      out += "0.000000 0.000000 0.000000 0.000000 0.000000 ";  // tv rv safety distances turn_axis
      break;
    case CarmenLaserMessage::kFlaser:
      out += "FLASER ";
      AppendRanges(out, frame.scan);
      AppendPose(out, T_odom_laser);
      AppendPose(out, frame.T_odom_base);
      break;
  }
  AppendTrailer(out, frame.time, options.hostname, logger_start);
  return out;
}

CarmenWriter::CarmenWriter(std::string path, CarmenWriterOptions options, Time logger_start)
    : path_(std::move(path)), options_(std::move(options)), logger_start_(logger_start) {
  text_ = kHeader;
}

void CarmenWriter::Comment(const std::string& text) {
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    text_ += "# " + text.substr(start, end - start) + "\n";
    start = end + 1;
  }
}

void CarmenWriter::Param(const std::string& name, const std::string& value, Time time) {
  text_ += "PARAM " + name + " " + value + " ";
  // PARAM lines carry absolute time in both fields (logger.c).
  text_ += FormatSeconds(time, 6) + " " + options_.hostname + " " + FormatSeconds(time, 6) + "\n";
}

void CarmenWriter::LaserOffsetParams(const Pose2& T_base_laser, Time time) {
  const auto text = [](double value) {
    std::string out;
    AppendF(out, "%f", value);
    return out;
  };
  Param("robot_frontlaser_offset", text(T_base_laser.x()), time);
  Param("robot_frontlaser_side_offset", text(T_base_laser.y()), time);
  Param("robot_frontlaser_angular_offset", text(T_base_laser.theta()), time);
}

void CarmenWriter::Odometry(const CarmenOdometry& odometry) {
  text_ += FormatOdometryLine(odometry, options_.hostname, logger_start_);
}

void CarmenWriter::Laser(const Frame& frame) {
  text_ += FormatLaserLines(frame, options_, logger_start_);
}

Status CarmenWriter::Close() { return WriteFileAtomically(path_, text_); }

Status WriteCarmenLog(const std::string& path, const std::vector<Frame>& frames,
                      const CarmenWriterOptions& options, const std::string& comment) {
  const Time start = frames.empty() ? Time() : frames.front().time;
  CarmenWriter writer(path, options, start);
  if (!comment.empty()) {
    writer.Comment(comment);
  }
  if (!frames.empty()) {
    writer.LaserOffsetParams(frames.front().T_base_laser, start);
  }
  for (std::size_t k = 0; k < frames.size(); ++k) {
    CarmenOdometry odometry{frames[k].time, frames[k].T_odom_base};
    if (k > 0) {
      // Speeds from the previous scan, over the repaired times (what CARMEN's ODOM carries; no
      // reader relies on them).
      const double dt = ToSeconds(frames[k].corrected_time - frames[k - 1].corrected_time);
      if (dt > 0.0) {
        const Pose2 delta = Between(frames[k - 1].T_odom_base, frames[k].T_odom_base);
        odometry.tv = delta.x() / dt;
        odometry.rv = delta.theta() / dt;
      }
    }
    writer.Odometry(odometry);
    writer.Laser(frames[k]);
  }
  return writer.Close();
}

}  // namespace gridslam::io
