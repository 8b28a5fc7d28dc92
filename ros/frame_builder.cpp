#include "frame_builder.hpp"

#include <algorithm>
#include <utility>

#include "gridslam/recording/ros_messages.hpp"

namespace gridslam::live {
namespace {

// Samples older than this before the latest scan are dropped (a scan never waits that long).
constexpr std::int64_t kKeepOdometryNs = 10'000'000'000;  // 10 s

}  // namespace

Pose2 PlanarOf(const Transform3D& T_parent_child) {
  const Transform3D& t = T_parent_child;
  return {t.x, t.y, recording::YawOfQuaternion(t.qx, t.qy, t.qz, t.qw)};
}

PlanarPose ToPlanar(const Pose2& pose) { return {pose.x(), pose.y(), pose.theta()}; }

FrameBuilder::FrameBuilder(io::CarmenOptions log, OdometrySource source)
    : log_(std::move(log)), source_(source) {}

void FrameBuilder::AddOdometry(const OdometryInput& odometry) {
  Pose2 T_odom_base = PlanarOf(odometry.T_odom_child);
  if (odometry.T_child_base) {
    T_odom_base = T_odom_base * PlanarOf(*odometry.T_child_base);
  }
  const recording::OdometrySample sample{odometry.stamp_ns, T_odom_base, 0};
  const auto at = std::upper_bound(
      samples_.begin(), samples_.end(), sample.stamp_ns,
      [](std::int64_t t, const recording::OdometrySample& s) { return t < s.stamp_ns; });
  samples_.insert(at, sample);
}

bool FrameBuilder::Covers(std::int64_t stamp_ns) const {
  return source_ == OdometrySource::kNone ||
         (!samples_.empty() && samples_.back().stamp_ns >= stamp_ns);
}

Result<Frame> FrameBuilder::Build(const ScanInput& scan, bool* clamped) {
  *clamped = false;
  auto laser = recording::MakeLaserScan(scan.angle_min, scan.angle_increment, scan.range_min,
                                        scan.range_max, scan.ranges);
  if (!laser.ok()) {
    return laser.error();
  }
  Frame frame;
  frame.time = Time(Duration(scan.stamp_ns));
  frame.corrected_time = frame.time;
  frame.scan = std::move(laser).value();
  frame.scan.range_max = std::min(frame.scan.range_max, log_.max_usable_range);
  frame.T_base_laser = log_.laser_offset.size() == 3
                           ? Pose2(log_.laser_offset[0], log_.laser_offset[1], log_.laser_offset[2])
                           : PlanarOf(scan.T_base_laser);
  frame.source_line = ++built_;
  if (source_ == OdometrySource::kNone) {
    frame.has_odometry = false;
  } else if (samples_.empty()) {  // not a frame without odometry: the odometry is on its way
    return InvalidInput("scan before the first odometry sample");
  } else {
    frame.T_odom_base = recording::InterpolateOdometry(samples_, scan.stamp_ns, clamped);
  }
  // Keep one sample before the oldest stamp a later scan can have (scans come in order).
  const auto old = std::lower_bound(
      samples_.begin(), samples_.end(), scan.stamp_ns - kKeepOdometryNs,
      [](const recording::OdometrySample& s, std::int64_t t) { return s.stamp_ns < t; });
  if (old - samples_.begin() > 1) {
    samples_.erase(samples_.begin(), old - 1);
  }
  return frame;
}

}  // namespace gridslam::live
