#include "app_map_session.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <regex>
#include <set>

#include "gridslam/io/options_yaml.hpp"

#include "app_map_report.hpp"
#include "app_memory.hpp"

namespace gridslam::app {

MapSession::MapSession(const SlamOptions& options, const std::vector<std::string>& logs)
    : options_(options),
      quality_scans_(options.quality, static_cast<int>(logs.size())),
      robots_(logs.size()),
      first_time_(logs.size()) {
  for (std::size_t r = 0; r < logs.size(); ++r) {
    robots_[r].log = logs[r];
  }
}

void MapSession::Record(int robot, const Frame& frame) {
  const auto r = static_cast<std::size_t>(robot);
  if (!first_time_[r]) {
    first_time_[r] = frame.time;
  }
  robots_[r].duration = ToSeconds(frame.time - *first_time_[r]);
  robots_[r].T_base_laser.push_back(frame.T_base_laser);
  quality_scans_.Add(robot, robots_[r].scans, frame);
  ++robots_[r].scans;
}

double MapSession::Duration() const {
  double duration = 0.0;
  for (const RobotOutput& r : robots_) {
    duration = std::max(duration, r.duration);
  }
  return duration;
}

nlohmann::json MapSession::Report(const pipeline::MapperResult& result) const {
  return MapReport(result, robots_);
}

Result<std::string> MapSession::Write(const std::string& dir, const pipeline::MapperResult& result,
                                      nlohmann::json report, const std::string& producer) const {
  const auto checked = std::chrono::steady_clock::now();
  // One buffer for the pictures of the self-check and of the outputs, drawn one after another.
  ImageBuffer pictures;
  auto quality = RunSelfCheck(dir, result, quality_scans_, options_.quality, options_.fusion,
                              options_.compute.Threads(), &pictures);
  report["time_s"]["self_check"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - checked).count();
  report["threads"] = options_.compute.Threads();
  if (!quality.ok()) {
    return quality.error();
  }
  report["quality"] = quality.value().report;
  ReleaseFreedMemory();
  const std::string config =
      "# " + producer + ": effective configuration\n" + io::OptionsToYaml(options_);
  GRIDSLAM_RETURN_IF_ERROR(WriteMapOutputs(dir, result, robots_, options_.eval.trajectory_frame,
                                           config, report, &pictures, options_.compute.Threads()));
  return quality.value().summary;
}

int RemoveStaleMapOutputs(const std::string& dir, std::size_t num_robots, std::size_t num_maps) {
  std::set<std::string> written;
  for (std::size_t r = 0; r < num_robots; ++r) {
    const std::string stem = num_robots > 1 ? "trajectory_" + std::to_string(r) : "trajectory";
    written.insert(stem + ".txt");
    written.insert(stem + ".tum");
  }
  for (std::size_t c = 0; c < num_maps; ++c) {
    const std::string stem = num_maps == 1 ? "map" : "map_" + std::to_string(c);
    for (const char* suffix : {".yaml", ".pgm", ".png", "_graph.png"}) {
      written.insert(stem + suffix);
    }
  }
  static const std::regex kOutput(
      "trajectory(_[0-9]+)?\\.(txt|tum)|map(_[0-9]+)?(\\.yaml|\\.pgm|\\.png|_graph\\.png)");
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file(ec) && std::regex_match(name, kOutput) && written.count(name) == 0 &&
        std::filesystem::remove(entry.path(), ec)) {
      ++removed;
    }
  }
  return removed;
}

}  // namespace gridslam::app
