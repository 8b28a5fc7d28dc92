#include "gridslam/io/simulation_io.hpp"

#include <cmath>
#include <sstream>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/options_yaml.hpp"

namespace gridslam::io {
namespace {

/// Splits `text` into lines and calls `parse(tokens, line_number)` for each non-comment line.
template <typename Parse>
Status ForEachLine(const std::string& text, Parse parse) {
  std::istringstream in(text);
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) {
      tokens.push_back(token);
    }
    if (tokens.empty() || tokens.front().front() == '#') {
      continue;
    }
    GRIDSLAM_RETURN_IF_ERROR(parse(tokens, number));
  }
  return Status::Ok();
}

bool ParseDouble(const std::string& token, double& value) {
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return *end == '\0' && std::isfinite(value);
}

}  // namespace

Status WriteScanIndex(const std::string& path, const std::vector<ScanIndexEntry>& entries) {
  std::string text;
  text.reserve(entries.size() * 22);
  for (const ScanIndexEntry& e : entries) {
    text += FormatSeconds(e.time, 6) + " " + std::to_string(e.robot) + "\n";
  }
  return WriteFileAtomically(path, text);
}

Result<std::vector<ScanIndexEntry>> ReadScanIndex(const std::string& path) {
  auto text = ReadTextFile(path);
  if (!text.ok()) {
    return text.error();
  }
  std::vector<ScanIndexEntry> entries;
  const Status s = ForEachLine(text.value(), [&](const std::vector<std::string>& t, long line) {
    const auto time = ParseSeconds(t[0]);
    char* end = nullptr;
    const long robot = t.size() == 2 ? std::strtol(t[1].c_str(), &end, 10) : -1;
    if (t.size() != 2 || !time || *end != '\0' || robot < 0 || robot > 1000) {
      return Status(InvalidInput("expected 'timestamp robot'", path, line));
    }
    entries.push_back({*time, static_cast<int>(robot)});
    return Status::Ok();
  });
  if (!s.ok()) {
    return s.error();
  }
  return entries;
}

Result<std::vector<Eigen::Vector2d>> ReadWaypoints(const std::string& path) {
  auto text = ReadTextFile(path);
  if (!text.ok()) {
    return text.error();
  }
  std::vector<Eigen::Vector2d> points;
  const Status s = ForEachLine(text.value(), [&](const std::vector<std::string>& t, long line) {
    double x = 0.0;
    double y = 0.0;
    if (t.size() != 2 || !ParseDouble(t[0], x) || !ParseDouble(t[1], y)) {
      return Status(InvalidInput("expected a waypoint 'x y' in metres", path, line));
    }
    if (!std::isfinite(x) || !std::isfinite(y) || std::abs(x) > 1e5 || std::abs(y) > 1e5) {
      return Status(
          InvalidInput("waypoint coordinates must be finite, within +-1e5 m", path, line));
    }
    points.emplace_back(x, y);
    return Status::Ok();
  });
  if (!s.ok()) {
    return s.error();
  }
  return points;
}

}  // namespace gridslam::io
