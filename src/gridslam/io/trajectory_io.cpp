#include "gridslam/io/trajectory_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/internal/carmen_line.hpp"
#include "gridslam/io/internal/gz_line_reader.hpp"
#include "gridslam/io/internal/number_parse.hpp"

namespace gridslam::io {
namespace {

void AppendLine(std::string& out, const char* format, auto... values) {
  char buffer[256];
  const int n = std::snprintf(buffer, sizeof(buffer), format, values...);
  out.append(buffer, static_cast<std::size_t>(n));
}

}  // namespace

StampedPose TrajectoryEntry(const Frame& frame, const Pose2& T_world_base,
                            const std::string& trajectory_frame) {
  if (trajectory_frame == "laser") {
    return {frame.time, T_world_base * frame.T_base_laser};
  }
  return {frame.time, T_world_base};
}

Status WriteTrajectory(const std::string& path, const std::vector<StampedPose>& poses) {
  std::string out;
  out.reserve(poses.size() * 72);
  for (const auto& p : poses) {
    out += FormatSeconds(p.time, 6);
    AppendLine(out, " %.17g %.17g %.17g\n", p.pose.x(), p.pose.y(), p.pose.theta());
  }
  return WriteFileAtomically(path, out);
}

Status WriteTrajectoryTum(const std::string& path, const std::vector<StampedPose>& input) {
  // Ascending timestamps, as TUM readers (evo) require; equal stamps keep their order.
  std::vector<StampedPose> poses = input;
  std::stable_sort(poses.begin(), poses.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.time < b.time; });
  std::string out;
  out.reserve(poses.size() * 120);
  for (const auto& p : poses) {
    const double half = 0.5 * p.pose.theta();
    out += FormatSeconds(p.time, 6);
    AppendLine(out, " %.17g %.17g 0 0 0 %.17g %.17g\n", p.pose.x(), p.pose.y(), std::sin(half),
               std::cos(half));
  }
  return WriteFileAtomically(path, out);
}

Status WriteTrajectoryByExtension(const std::string& path, const std::vector<StampedPose>& poses) {
  const bool tum = path.size() >= 4 && path.compare(path.size() - 4, 4, ".tum") == 0;
  return tum ? WriteTrajectoryTum(path, poses) : WriteTrajectory(path, poses);
}

Result<std::vector<StampedPose>> ReadTrajectory(const std::string& path) {
  internal::GzLineReader reader;
  GRIDSLAM_RETURN_IF_ERROR(reader.Open(path));
  std::vector<StampedPose> poses;
  std::string line;
  std::vector<std::string_view> tokens;
  Status status;
  long line_number = 0;
  while (reader.ReadLine(line, status)) {
    ++line_number;
    internal::SplitFields(line, tokens);
    if (tokens.empty() || tokens[0].front() == '#') {
      continue;
    }
    if (tokens.size() != 4 && tokens.size() != 8) {
      return InvalidInput("trajectory line has " + std::to_string(tokens.size()) +
                              " fields; expected 4 (timestamp x y theta) or 8 (TUM)",
                          path, line_number);
    }
    const auto time = ParseSeconds(tokens[0]);
    if (!time) {
      return InvalidInput("field 'timestamp': cannot read '" + std::string(tokens[0]) + "'", path,
                          line_number);
    }
    double v[7] = {0, 0, 0, 0, 0, 0, 0};
    static constexpr const char* kNames[2][7] = {{"x", "y", "theta", "", "", "", ""},
                                                 {"x", "y", "z", "qx", "qy", "qz", "qw"}};
    const bool tum = tokens.size() == 8;
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      if (!internal::ParseDouble(tokens[k], v[k - 1]) || !std::isfinite(v[k - 1])) {
        return InvalidInput(std::string("field '") + kNames[tum ? 1 : 0][k - 1] +
                                "': cannot read '" + std::string(tokens[k]) + "' as a number",
                            path, line_number);
      }
    }
    double theta = v[2];
    if (tum) {
      // Yaw of the quaternion (x, y, z, w) = (v[3], v[4], v[5], v[6]).
      theta =
          std::atan2(2.0 * (v[6] * v[5] + v[3] * v[4]), 1.0 - 2.0 * (v[4] * v[4] + v[5] * v[5]));
    }
    poses.push_back({*time, Pose2(v[0], v[1], theta)});
  }
  if (!status.ok()) {
    return status.error();
  }
  return poses;
}

}  // namespace gridslam::io
