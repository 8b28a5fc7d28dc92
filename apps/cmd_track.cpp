// `gridslam track LOG -o DIR`: the front end alone (docs/design.md §1.2-1.3, §2). Every scan of a
// CARMEN log is matched against the rolling local map; DIR receives trajectory.txt and
// trajectory.tum (one pose per scan, printed timestamps, in the front end's odometry frame),
// report.json (scans, key maps, fallbacks, time per stage, real-time factor) and config.yaml.
// A progress bar goes to stderr when it is a terminal.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/io/trajectory_io.hpp"
#include "gridslam/recording/recording_reader.hpp"
#include "gridslam/scan_matching/front_end.hpp"

#include "app_mounting_report.hpp"
#include "app_output_dir.hpp"
#include "command.hpp"
#include <unistd.h>

namespace gridslam::app {
namespace {

using Clock = std::chrono::steady_clock;

struct TrackArgs {
  std::string log;
  std::string output;
  bool no_match = false;
};

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

void DrawProgress(std::size_t done, std::size_t total) {
  constexpr int kWidth = 40;
  const double fraction = total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total);
  const auto filled = static_cast<int>(fraction * kWidth);
  std::fprintf(stderr, "\r[%.*s%*s] %3d%% %zu/%zu scans", filled,
               "########################################", kWidth - filled, "",
               static_cast<int>(fraction * 100.0), done, total);
  std::fflush(stderr);
}

nlohmann::json StatsJson(const scan_matching::FrontEndStats& s) {
  return {
      {"frames", s.frames},
      {"matched", s.matched},
      {"fallbacks",
       {{"few_points", s.fallback_few_points},
        {"empty_map", s.fallback_empty_map},
        {"rejected", s.fallback_rejected},
        {"total", s.fallback_few_points + s.fallback_empty_map + s.fallback_rejected}}},
      {"correlative_searches", s.searches},
      {"degenerate_matches", {{"one_direction", s.degenerate_one}, {"both", s.degenerate_both}}},
      {"far_window_matches", s.far_matches},
      {"wall_normal_frames", s.wall_normal_frames},
      {"odometry",
       {{"doubtful", s.odometry_doubtful},
        {"missing", s.odometry_missing},
        {"wide_searches", s.wide_searches},
        {"overruled", s.odometry_overruled},
        {"poor_matches", s.poor_matches},
        {"poor_rescued", s.poor_rescued},
        {"poor_ambiguous", s.poor_ambiguous}}},
      {"insertions", s.insertions},
      {"key_maps", s.key_maps},
      {"distance_field", {{"rebuilds", s.field_rebuilds}, {"tile_updates", s.field_tile_updates}}}};
}

int RunTrack(const TrackArgs& args, AppContext& context) {
  scan_matching::FrontEndOptions options = context.options.front_end;
  options.match = options.match && !args.no_match;
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  const auto start = Clock::now();
  io::CarmenStats log_stats;
  auto frames = recording::ReadRecording(args.log, context.Recording(), &log_stats);
  if (!frames.ok()) {
    return ReportError(frames.error());
  }
  auto output = OutputDir::Begin(args.output);  // staged, committed at the end (issue 17)
  if (!output.ok()) {
    return ReportError(output.error());
  }
  if (frames.value().empty()) {
    return ReportError(io::NoScansError(args.log, log_stats));
  }
  const auto read_done = Clock::now();

  const bool progress = isatty(fileno(stderr)) != 0;
  const std::string& frame_name = context.options.eval.trajectory_frame;
  scan_matching::FrontEnd front_end(options);
  std::vector<io::StampedPose> poses;
  poses.reserve(frames.value().size());
  Time first_time = frames.value().front().time;
  Time last_time = first_time;
  std::size_t done = 0;
  for (const Frame& frame : frames.value()) {
    const scan_matching::FrontEndStep step = front_end.AddFrame(frame);
    poses.push_back(io::TrajectoryEntry(frame, step.T_odom_base, frame_name));
    first_time = std::min(first_time, frame.time);
    last_time = std::max(last_time, frame.time);
    if (progress && (++done % 200 == 0 || done == frames.value().size())) {
      DrawProgress(done, frames.value().size());
    }
  }
  front_end.Finish();
  const auto track_done = Clock::now();
  if (progress) {
    std::fprintf(stderr, "\n");
  }

  const std::filesystem::path dir(output.value()->path());
  for (const Status& s : {io::WriteTrajectory((dir / "trajectory.txt").string(), poses),
                          io::WriteTrajectoryTum((dir / "trajectory.tum").string(), poses)}) {
    if (!s.ok()) {
      return ReportError(s.error());
    }
  }
  if (const Status s = io::WriteFileAtomically(
          (dir / "config.yaml").string(),
          "# gridslam track: effective configuration\n" + io::OptionsToYaml(context.options));
      !s.ok()) {
    return ReportError(s.error());
  }
  const auto write_done = Clock::now();

  const scan_matching::FrontEndStats& stats = front_end.Stats();
  const double duration = ToSeconds(last_time - first_time);
  const double front_end_seconds = Seconds(track_done - read_done);
  const double total_seconds = Seconds(write_done - start);
  nlohmann::json report = StatsJson(stats);
  report["log"] = args.log;
  report["scans"] = poses.size();
  report["matching"] = options.match;
  report["log_duration_s"] = duration;
  report["time_s"] = {{"read", Seconds(read_done - start)},
                      {"front_end", front_end_seconds},
                      {"preprocess", stats.seconds_preprocess},
                      {"distance_field", stats.seconds_field},
                      {"match", stats.seconds_match},
                      {"insert", stats.seconds_insert},
                      {"keymap", stats.seconds_keymap},
                      {"write", Seconds(write_done - track_done)},
                      {"total", total_seconds}};
  report["real_time_factor"] = {{"front_end", duration / front_end_seconds},
                                {"total", duration / total_seconds}};
  report["reader"] = {{"lines", log_stats.lines},
                      {"repaired_timestamps", log_stats.repaired_timestamps},
                      {"scans_without_odometry", log_stats.scans_without_odometry},
                      {"skipped_malformed", log_stats.skipped_malformed}};
  const scan_matching::MountingResult mounting = front_end.Mounting();
  report["laser_mounting"] = MountingJson(mounting);
  if (const Status s =
          io::WriteFileAtomically((dir / "report.json").string(), report.dump(2) + "\n");
      !s.ok()) {
    return ReportError(s.error());
  }
  if (const Status s = output.value()->Commit(); !s.ok()) {
    return ReportError(s.error());
  }

  PrintMountingNote("gridslam track", args.log, mounting, options.local_map.resolution);
  std::fprintf(stderr,
               "gridslam track: %zu scans, %ld key maps, %ld fallbacks, %ld searches; "
               "%.2f s (read %.2f s, front end %.2f s), %.0fx real time\n",
               poses.size(), stats.key_maps,
               stats.fallback_few_points + stats.fallback_empty_map + stats.fallback_rejected,
               stats.searches, total_seconds, Seconds(read_done - start), front_end_seconds,
               duration / total_seconds);
  return kExitOk;
}

RunFunction SetupTrack(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<TrackArgs>();
  sub.add_option("LOG", args->log,
                 "Recording: CARMEN log (optionally gzip-compressed) or bag (.bag, .mcap, rosbag2)")
      ->required();
  sub.add_option("-o,--output", args->output, "Output folder")->required()->check(OutputFolder());
  sub.add_flag("--no-match", args->no_match,
               "Do not match scans: the trajectory is the raw odometry (baseline)");
  return [args](AppContext& ctx) { return RunTrack(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "track", "Front end alone: scan matching against a rolling local map", SetupTrack});

}  // namespace
}  // namespace gridslam::app
