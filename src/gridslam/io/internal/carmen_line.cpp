#include "gridslam/io/internal/carmen_line.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace gridslam::io::internal {
namespace {

std::string FormatBound(double bound) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", bound);
  return buffer;
}

constexpr int kMaxBeams = 100000;

/// Sequential field reader over the tokens of one line.
class Fields {
 public:
  Fields(const std::vector<std::string_view>& tokens, const std::string& file, long line)
      : tokens_(tokens), file_(file), line_(line) {}

  Status Double(const char* name, double& value) {
    std::string_view token;
    GRIDSLAM_RETURN_IF_ERROR(Next(name, token));
    const char* end = token.data() + token.size();
    auto [ptr, ec] = std::from_chars(token.data(), end, value);
    if (ec != std::errc() || ptr != end) {
      return Bad(name, token, "a number");
    }
    return Status::Ok();
  }
  Status Int(const char* name, int& value) {
    std::string_view token;
    GRIDSLAM_RETURN_IF_ERROR(Next(name, token));
    const char* end = token.data() + token.size();
    auto [ptr, ec] = std::from_chars(token.data(), end, value);
    if (ec != std::errc() || ptr != end) {
      return Bad(name, token, "an integer");
    }
    return Status::Ok();
  }
  Status Count(const char* name, int& value) {
    GRIDSLAM_RETURN_IF_ERROR(Int(name, value));
    if (value < 0 || value > kMaxBeams) {
      return Error(std::string("field '") + name + "': count " + std::to_string(value) +
                   " out of range [0, " + std::to_string(kMaxBeams) + "]");
    }
    return Status::Ok();
  }
  /// A finite number with |value| <= bound.
  Status Bounded(const char* name, double bound, double& value) {
    GRIDSLAM_RETURN_IF_ERROR(Double(name, value));
    if (!std::isfinite(value) || std::abs(value) > bound) {
      return Error(std::string("field '") + name + "': " + std::string(tokens_[pos_ - 1]) +
                   " is not a finite number within +-" + FormatBound(bound));
    }
    return Status::Ok();
  }
  Status PoseField(const char* name, Pose2& pose) {
    double v[3];
    const std::string base(name);
    for (int i = 0; i < 3; ++i) {
      static constexpr const char* kSuffix[3] = {"_x", "_y", "_theta"};
      GRIDSLAM_RETURN_IF_ERROR(Bounded((base + kSuffix[i]).c_str(),
                                       i < 2 ? kMaxCarmenCoordinate : kMaxCarmenAngle, v[i]));
    }
    pose = Pose2(v[0], v[1], v[2]);
    return Status::Ok();
  }
  Status Ranges(const char* name, int n, std::vector<float>& out) {
    out.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      double r = 0.0;
      const std::string field = std::string(name) + "[" + std::to_string(i) + "]";
      if (pos_ >= tokens_.size()) {
        return Error("field '" + field + "' missing (line has " + std::to_string(tokens_.size()) +
                     " fields, " + std::to_string(n) + " readings announced)");
      }
      GRIDSLAM_RETURN_IF_ERROR(Double(field.c_str(), r));
      out[static_cast<std::size_t>(i)] = static_cast<float>(r);
    }
    return Status::Ok();
  }
  Status Skip(const char* name, int n) {
    for (int i = 0; i < n; ++i) {
      std::string_view token;
      GRIDSLAM_RETURN_IF_ERROR(Next(name, token));
    }
    return Status::Ok();
  }
  /// The ipc_timestamp, or out.time_missing when the line has none: no field left (laserazos),
  /// or only `host logger_timestamp` left (orebro's `... pippo 0`).
  Status Timestamp(CarmenMessage& out) {
    out.time_missing = false;
    out.time = Time();
    out.time_text = std::string_view();
    if (pos_ >= tokens_.size()) {
      out.time_missing = true;
      return Status::Ok();
    }
    GRIDSLAM_RETURN_IF_ERROR(Next("ipc_timestamp", out.time_text));
    const auto parsed = ParseSeconds(out.time_text);
    if (!parsed) {
      if (pos_ + 1 == tokens_.size()) {  // `host logger_timestamp`: no ipc_timestamp
        out.time_missing = true;
        out.time_text = std::string_view();
        return Status::Ok();
      }
      return Bad("ipc_timestamp", out.time_text, "decimal seconds within +-9e9 s");
    }
    out.time = *parsed;
    return Status::Ok();
  }
  Status Token(const char* name, std::string_view& token) { return Next(name, token); }
  [[nodiscard]] Status Error(const std::string& what) const {
    return InvalidInput(std::string(tokens_[0]) + ": " + what, file_, line_);
  }

 private:
  Status Next(const char* name, std::string_view& token) {
    if (pos_ >= tokens_.size()) {
      return Error(std::string("field '") + name + "' missing (line has " +
                   std::to_string(tokens_.size()) + " fields)");
    }
    token = tokens_[pos_++];
    return Status::Ok();
  }
  [[nodiscard]] Status Bad(const char* name, std::string_view token, const char* expected) const {
    return Error(std::string("field '") + name + "': cannot read '" + std::string(token) + "' as " +
                 expected);
  }

  const std::vector<std::string_view>& tokens_;
  const std::string& file_;
  long line_;
  std::size_t pos_ = 1;  // after the tag
};

bool StartsWith(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

Status ParseRawOrRobotLaser(Fields& f, bool robot, const CarmenOptions& options,
                            CarmenMessage& out) {
  int laser_type = 0;
  int remission_mode = 0;
  double start_angle = 0.0;
  double fov = 0.0;
  double resolution = 0.0;
  double max_range = 0.0;
  double accuracy = 0.0;
  int n = 0;
  int m = 0;
  GRIDSLAM_RETURN_IF_ERROR(f.Int("laser_type", laser_type));
  GRIDSLAM_RETURN_IF_ERROR(f.Double("start_angle", start_angle));
  GRIDSLAM_RETURN_IF_ERROR(f.Double("field_of_view", fov));
  GRIDSLAM_RETURN_IF_ERROR(f.Double("angular_resolution", resolution));
  GRIDSLAM_RETURN_IF_ERROR(f.Double("maximum_range", max_range));
  GRIDSLAM_RETURN_IF_ERROR(f.Double("accuracy", accuracy));
  GRIDSLAM_RETURN_IF_ERROR(f.Int("remission_mode", remission_mode));
  GRIDSLAM_RETURN_IF_ERROR(f.Count("num_readings", n));
  GRIDSLAM_RETURN_IF_ERROR(f.Ranges("range", n, out.scan.ranges));
  GRIDSLAM_RETURN_IF_ERROR(f.Count("num_remissions", m));
  GRIDSLAM_RETURN_IF_ERROR(f.Skip("remission", m));
  if (!std::isfinite(start_angle) || !std::isfinite(resolution) ||
      std::abs(start_angle) > kMaxCarmenAngle || std::abs(resolution) > std::numbers::pi) {
    return f.Error("field 'start_angle'/'angular_resolution': not finite, or beyond +-" +
                   FormatBound(kMaxCarmenAngle) + " rad / +-pi rad");
  }
  out.scan.angle_min = start_angle;
  out.scan.angle_increment = resolution;
  out.scan.range_min = 0.0;
  out.scan.range_max = EffectiveRangeMax(options, max_range);
  if (robot) {
    Pose2 laser_pose;
    Pose2 robot_pose;
    double ignored = 0.0;
    GRIDSLAM_RETURN_IF_ERROR(f.PoseField("laser_pose", laser_pose));
    GRIDSLAM_RETURN_IF_ERROR(f.PoseField("robot_pose", robot_pose));
    for (const char* name :
         {"laser_tv", "laser_rv", "forward_safety_dist", "side_safety_dist", "turn_axis"}) {
      GRIDSLAM_RETURN_IF_ERROR(f.Double(name, ignored));
    }
    out.laser_pose = laser_pose;
    out.robot_pose = robot_pose;
  }
  return f.Timestamp(out);
}

Status ParseOldLaser(Fields& f, const CarmenOptions& options, CarmenMessage& out) {
  int n = 0;
  GRIDSLAM_RETURN_IF_ERROR(f.Count("num_readings", n));
  GRIDSLAM_RETURN_IF_ERROR(f.Ranges("range", n, out.scan.ranges));
  Pose2 laser_pose;
  Pose2 robot_pose;
  GRIDSLAM_RETURN_IF_ERROR(f.PoseField("laser_pose", laser_pose));
  GRIDSLAM_RETURN_IF_ERROR(f.PoseField("odom", robot_pose));
  out.laser_pose = laser_pose;
  out.robot_pose = robot_pose;
  out.scan.angle_min = options.flaser_angle_min;
  out.scan.angle_increment = options.flaser_angle_increment > 0.0 ? options.flaser_angle_increment
                                                                  : GuessLaserAngleIncrement(n);
  out.scan.range_min = 0.0;
  out.scan.range_max = EffectiveRangeMax(options, 80.0);  // CARMEN's guess for FLASER
  return f.Timestamp(out);
}

}  // namespace

void SplitFields(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) {
      ++i;
    }
    const std::size_t start = i;
    while (i < n && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') {
      ++i;
    }
    if (i > start) {
      tokens.push_back(line.substr(start, i - start));
    }
  }
}

CarmenKind ClassifyTag(std::string_view tag) {
  if (tag.empty() || tag.front() == '#') {
    return CarmenKind::kComment;
  }
  if (tag == "ODOM") return CarmenKind::kOdom;
  if (tag == "TRUEPOS") return CarmenKind::kTruePos;
  if (tag == "PARAM") return CarmenKind::kParam;
  if (tag == "SYNC") return CarmenKind::kSync;
  if (tag == "FLASER" || tag == "RLASER" || tag == "ROBOTLASER1" || tag == "ROBOTLASER2") {
    return CarmenKind::kLaser;
  }
  if (tag.size() == 9 && StartsWith(tag, "RAWLASER") && tag[8] >= '1' && tag[8] <= '4') {
    return CarmenKind::kLaser;
  }
  return CarmenKind::kUnknown;
}

Status ParseCarmenMessage(const std::vector<std::string_view>& tokens, const CarmenOptions& options,
                          const std::string& file, long line, CarmenMessage& out) {
  out.kind = tokens.empty() ? CarmenKind::kComment : ClassifyTag(tokens[0]);
  out.tag = tokens.empty() ? std::string_view() : tokens[0];
  out.laser_pose.reset();
  out.robot_pose.reset();
  out.rear = false;
  if (out.kind == CarmenKind::kComment || out.kind == CarmenKind::kUnknown) {
    return Status::Ok();
  }
  Fields f(tokens, file, line);
  switch (out.kind) {
    case CarmenKind::kOdom: {
      double ignored = 0.0;
      GRIDSLAM_RETURN_IF_ERROR(f.PoseField("odom", out.pose));
      GRIDSLAM_RETURN_IF_ERROR(f.Double("tv", ignored));
      GRIDSLAM_RETURN_IF_ERROR(f.Double("rv", ignored));
      GRIDSLAM_RETURN_IF_ERROR(f.Double("accel", ignored));
      return f.Timestamp(out);
    }
    case CarmenKind::kTruePos:
      GRIDSLAM_RETURN_IF_ERROR(f.PoseField("true", out.pose));
      GRIDSLAM_RETURN_IF_ERROR(f.PoseField("odom", out.odom_pose));
      return f.Timestamp(out);
    case CarmenKind::kParam:
      GRIDSLAM_RETURN_IF_ERROR(f.Token("param_name", out.param_name));
      GRIDSLAM_RETURN_IF_ERROR(f.Token("param_value", out.param_value));
      return Status::Ok();  // PARAM trailers vary between logs ("nohost 0"); not needed
    case CarmenKind::kSync:
      return Status::Ok();
    case CarmenKind::kLaser: {
      const std::string_view tag = tokens[0];
      if (tag == "FLASER" || tag == "RLASER") {
        out.rear = tag == "RLASER";
        return ParseOldLaser(f, options, out);
      }
      if (StartsWith(tag, "ROBOTLASER")) {
        out.rear = tag == "ROBOTLASER2";
        return ParseRawOrRobotLaser(f, /*robot=*/true, options, out);
      }
      out.rear = tag == "RAWLASER2" || tag == "RAWLASER4";
      return ParseRawOrRobotLaser(f, /*robot=*/false, options, out);
    }
    default:
      return Status::Ok();
  }
}

double GuessLaserFov(int num_beams) {
  constexpr double kPi = std::numbers::pi;
  switch (num_beams) {
    case 181:
      return kPi;
    case 180:
      return kPi / 180.0 * 179.0;
    case 361:
      return kPi;
    case 360:
      return kPi / 180.0 * 179.5;
    case 401:
      return kPi / 180.0 * 100.0;
    case 400:
      return kPi / 100.0 * 99.75;  // sic: CARMEN's formula (not 99.75 degrees)
    default:
      return kPi;
  }
}

double GuessLaserAngleIncrement(int num_beams) {
  constexpr double kPi = std::numbers::pi;
  if (num_beams == 181 || num_beams == 180) return kPi / 180.0;
  if (num_beams == 361 || num_beams == 360) return kPi / 360.0;
  if (num_beams == 401 || num_beams == 400) return kPi / 720.0;
  if (num_beams <= 1) return 0.0;  // CARMEN would divide by zero
  return GuessLaserFov(num_beams) / static_cast<double>(num_beams - 1);
}

double EffectiveRangeMax(const CarmenOptions& options, double line_max_range) {
  double limit = options.max_usable_range;
  if (line_max_range > 0.0 && std::isfinite(line_max_range)) {
    limit = std::min(limit, line_max_range);
  }
  for (double sentinel : options.no_return_values) {
    if (sentinel > 0.0) {
      limit = std::min(limit, sentinel - 0.005);
    }
  }
  return limit;
}

}  // namespace gridslam::io::internal
