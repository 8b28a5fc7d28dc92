#include "gridslam/recording/ros_messages.hpp"

#include <cmath>
#include <limits>

#include "gridslam/recording/internal/byte_reader.hpp"

namespace gridslam::recording {
namespace {

using internal::ByteReader;

// One message's field reader for either wire format.
class WireReader {
 public:
  WireReader(std::span<const std::uint8_t> data, MessageEncoding encoding)
      : reader_(data), encoding_(encoding) {
    if (encoding_ == MessageEncoding::kCdr) {
      // Encapsulation: 0x00 0x00 = CDR big endian, 0x00 0x01 = CDR little endian (+ options).
      const std::uint8_t e0 = reader_.U8();
      const std::uint8_t e1 = reader_.U8();
      reader_.Skip(2);
      if (!reader_.ok() || e0 != 0 || e1 > 1) {
        bad_header_ = true;
        reader_.Fail();
      }
      if (e1 == 0) {
        reader_ = ByteReader(data, /*big_endian=*/true);
        reader_.Skip(4);
      }
      origin_ = 4;
    }
  }
  [[nodiscard]] bool ok() const { return reader_.ok(); }
  [[nodiscard]] bool bad_header() const { return bad_header_; }

  template <class T>
  T Get() {
    if (encoding_ == MessageEncoding::kCdr) {
      reader_.Align(sizeof(T), origin_);
    }
    return reader_.Read<T>();
  }
  std::string String() {
    const std::uint32_t n = Get<std::uint32_t>();
    if (n > reader_.remaining()) {
      reader_.Fail();
      return {};
    }
    std::string s = reader_.String(n);
    if (encoding_ == MessageEncoding::kCdr && !s.empty() && s.back() == '\0') {
      s.pop_back();
    }
    return s;
  }
  /// Header: (ROS 1: seq) stamp frame_id; returns the stamp [ns].
  std::int64_t Header(std::string* frame_id) {
    if (encoding_ == MessageEncoding::kRos1) {
      Get<std::uint32_t>();  // seq
    }
    const std::int64_t sec = encoding_ == MessageEncoding::kRos1
                                 ? static_cast<std::int64_t>(Get<std::uint32_t>())
                                 : static_cast<std::int64_t>(Get<std::int32_t>());
    const std::uint32_t nsec = Get<std::uint32_t>();
    *frame_id = String();
    return sec * 1000000000LL + static_cast<std::int64_t>(nsec);
  }
  /// Element count of a sequence, rejected when it cannot fit in the remaining bytes.
  std::uint32_t Count(std::size_t element_size) {
    const std::uint32_t n = Get<std::uint32_t>();
    if (element_size > 0 && n > reader_.remaining() / element_size) {
      reader_.Fail();
      return 0;
    }
    return n;
  }
  /// geometry_msgs/Pose or Transform reduced to the plane.
  Pose2 PlanarPose() {
    const double x = Get<double>();
    const double y = Get<double>();
    Get<double>();  // z
    const double qx = Get<double>();
    const double qy = Get<double>();
    const double qz = Get<double>();
    const double qw = Get<double>();
    return {x, y, YawOfQuaternion(qx, qy, qz, qw)};
  }

 private:
  ByteReader reader_;
  MessageEncoding encoding_;
  std::size_t origin_ = 0;
  bool bad_header_ = false;
};

Error Bad(const char* type, const WireReader& r) {
  return InvalidInput(
      std::string(type) + " message is " +
      (r.bad_header() ? "not CDR (bad encapsulation header)" : "truncated or malformed"));
}

}  // namespace

MessageKind KindOfType(const std::string& type) {
  if (type == "sensor_msgs/LaserScan" || type == "sensor_msgs/msg/LaserScan") {
    return MessageKind::kLaserScan;
  }
  if (type == "nav_msgs/Odometry" || type == "nav_msgs/msg/Odometry") {
    return MessageKind::kOdometry;
  }
  if (type == "tf2_msgs/TFMessage" || type == "tf2_msgs/msg/TFMessage" || type == "tf/tfMessage") {
    return MessageKind::kTf;
  }
  return MessageKind::kOther;
}

double YawOfQuaternion(double x, double y, double z, double w) {
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

Result<LaserScan> MakeLaserScan(float angle_min, float angle_increment, float range_min,
                                float range_max, std::vector<float> ranges) {
  if (!std::isfinite(angle_min) || !std::isfinite(angle_increment) || !std::isfinite(range_max) ||
      angle_increment == 0.0F || ranges.empty()) {
    return InvalidInput("LaserScan message has no beams or a non-finite geometry");
  }
  LaserScan scan;
  scan.ranges = std::move(ranges);
  scan.angle_min = angle_min;
  scan.angle_increment = angle_increment;
  scan.range_min = std::isfinite(range_min) ? std::max(0.0F, range_min) : 0.0F;
  scan.range_max = range_max;
  return scan;
}

Result<ScanMessage> DecodeLaserScan(std::span<const std::uint8_t> data, MessageEncoding encoding) {
  WireReader r(data, encoding);
  ScanMessage m;
  m.stamp_ns = r.Header(&m.frame_id);
  const float angle_min = r.Get<float>();
  const float angle_max = r.Get<float>();
  const float angle_increment = r.Get<float>();
  r.Get<float>();  // time_increment
  r.Get<float>();  // scan_time
  const float range_min = r.Get<float>();
  const float range_max = r.Get<float>();
  const std::uint32_t n = r.Count(sizeof(float));
  std::vector<float> ranges(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    ranges[k] = r.Get<float>();
  }
  // intensities follow; not needed.
  if (!r.ok()) {
    return Bad("LaserScan", r);
  }
  auto scan = MakeLaserScan(angle_min, angle_increment, range_min, range_max, std::move(ranges));
  if (!scan.ok()) {
    return scan.error();
  }
  m.angle_max = angle_max;
  m.scan = std::move(scan).value();
  return m;
}

Result<OdometryMessage> DecodeOdometry(std::span<const std::uint8_t> data,
                                       MessageEncoding encoding) {
  WireReader r(data, encoding);
  OdometryMessage m;
  m.stamp_ns = r.Header(&m.frame_id);
  m.child_frame_id = r.String();
  m.T_odom_base = r.PlanarPose();
  if (!r.ok()) {  // the covariance and twist follow; only the pose is needed
    return Bad("Odometry", r);
  }
  if (!std::isfinite(m.T_odom_base.x()) || !std::isfinite(m.T_odom_base.y()) ||
      !std::isfinite(m.T_odom_base.theta())) {
    return InvalidInput("Odometry message has a non-finite pose");
  }
  return m;
}

Result<std::vector<TransformMessage>> DecodeTfMessage(std::span<const std::uint8_t> data,
                                                      MessageEncoding encoding) {
  WireReader r(data, encoding);
  // Each TransformStamped is at least 4 (seq/sec) + 8 + 4 + 4 + 56 bytes.
  const std::uint32_t n = r.Count(64);
  std::vector<TransformMessage> out;
  out.reserve(n);
  for (std::uint32_t i = 0; i < n && r.ok(); ++i) {
    TransformMessage t;
    t.stamp_ns = r.Header(&t.parent);
    t.child = r.String();
    t.T_parent_child = r.PlanarPose();
    out.push_back(std::move(t));
  }
  if (!r.ok()) {
    return Bad("TFMessage", r);
  }
  return out;
}

}  // namespace gridslam::recording
