// `gridslam info RECORDING`: what a CARMEN log or a bag holds — its format, topics (bags) or
// message counts (logs), duration, and the laser's geometry (beams, field of view, range) and
// mounting, plus the odometry source that `map` would use.
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <tuple>

#include "gridslam/recording/bag_reader.hpp"
#include "gridslam/recording/content_sniffer.hpp"
#include "gridslam/recording/recording_reader.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct InfoArgs {
  std::string path;
};

double Deg(double rad) { return rad * 180.0 / M_PI; }

// Beam count, first angle, step, range limits of a scan, for grouping distinct geometries.
using Geometry = std::tuple<std::size_t, float, float, float, float>;

void PrintGeometries(const std::map<Geometry, long>& geometries) {
  for (const auto& [g, count] : geometries) {
    const auto& [beams, angle_min, step, range_min, range_max] = g;
    std::printf(
        "  laser: %zu beams, %.2f deg field of view (%.2f..%.2f deg, step %.4f deg), "
        "range %.3g..%.3g m: %ld scans\n",
        beams, Deg(static_cast<double>(step) * static_cast<double>(beams - 1)), Deg(angle_min),
        Deg(angle_min + static_cast<double>(step) * static_cast<double>(beams - 1)), Deg(step),
        static_cast<double>(range_min), static_cast<double>(range_max), count);
  }
}

int RunInfo(const InfoArgs& args, AppContext& context) {
  auto reader = recording::RecordingReader::Open(args.path, context.Recording());
  if (!reader.ok()) {
    return ReportError(reader.error());
  }
  std::map<Geometry, long> geometries;
  long scans = 0;
  long without_odometry = 0;
  Time first{};
  Time last{};
  Pose2 mounting;
  while (true) {
    auto next = reader.value().Next();
    if (!next.ok()) {
      return ReportError(next.error());
    }
    if (!next.value()) {
      break;
    }
    const Frame& f = *next.value();
    if (scans == 0) {
      first = last = f.time;
      mounting = f.T_base_laser;
    }
    first = std::min(first, f.time);
    last = std::max(last, f.time);
    ++scans;
    without_odometry += f.has_odometry ? 0 : 1;
    ++geometries[{f.scan.size(), static_cast<float>(f.scan.angle_min),
                  static_cast<float>(f.scan.angle_increment), static_cast<float>(f.scan.range_min),
                  static_cast<float>(f.scan.range_max)}];
  }
  const recording::RecordingFormat format = reader.value().Format();
  const io::CarmenStats& stats = reader.value().Stats();
  std::printf("%s: %s\n", args.path.c_str(), recording::RecordingFormatName(format));
  if (format != recording::RecordingFormat::kCarmen) {
    auto bag = recording::LoadBag(args.path, context.options.log.lenient);
    if (!bag.ok()) {
      return ReportError(bag.error());
    }
    const double span = static_cast<double>(bag.value().last_log_ns - bag.value().first_log_ns);
    std::printf("  duration: %.3f s (message log times)\n  topics:\n%s", span * 1e-9,
                recording::ListTopics(bag.value()).c_str());
    const recording::BagAssembly* a = reader.value().Assembly();
    std::printf("  scans: %s, frame %s; odometry: %s (%ld samples); base frame %s\n",
                a->scan_topic.c_str(), a->laser_frame.c_str(), a->odometry_source.c_str(),
                a->odometry_samples, a->base_frame.c_str());
  } else {
    std::printf(
        "  lines: %ld (ODOM %ld, PARAM %ld, TRUEPOS %ld, comments %ld, unknown %ld, "
        "malformed skipped %ld)\n",
        stats.lines, stats.odometry, stats.params, stats.truepos, stats.comments,
        stats.skipped_unknown, stats.skipped_malformed);
  }
  std::printf(
      "  scans: %ld over %.3f s (%.2f Hz)%s\n", scans, ToSeconds(last - first),
      scans > 1 && last > first ? static_cast<double>(scans - 1) / ToSeconds(last - first) : 0.0,
      without_odometry > 0 ? " WITHOUT odometry (scan matching alone)" : "");
  PrintGeometries(geometries);
  std::printf("  laser mounting T_base_laser: x %.4f m, y %.4f m, theta %.4f rad\n", mounting.x(),
              mounting.y(), mounting.theta());
  return kExitOk;
}

RunFunction SetupInfo(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<InfoArgs>();
  sub.add_option("RECORDING", args->path,
                 "CARMEN log, ROS 1 .bag, MCAP .mcap, rosbag2 folder or .db3")
      ->required();
  return [args](AppContext& ctx) { return RunInfo(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "info", "What a log or bag holds: topics, counts, duration, laser geometry and mounting",
    SetupInfo});

}  // namespace
}  // namespace gridslam::app
