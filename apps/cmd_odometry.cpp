// `gridslam odometry LOG -o FILE`: the raw odometry pose of every laser scan of a CARMEN log,
// in the frame the benchmark relations use (eval.trajectory_frame), so a log's odometry
// baseline is one `gridslam eval` away (docs/design.md §2). FILE ending in .tum is written as TUM.
#include <cstdio>
#include <memory>

#include "gridslam/io/trajectory_io.hpp"
#include "gridslam/recording/recording_reader.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct OdometryArgs {
  std::string log;
  std::string output;
  std::vector<double> laser_offset;
  std::string frame;
};

int RunOdometry(const OdometryArgs& args, AppContext& context) {
  io::CarmenOptions options = context.options.log;
  if (!args.laser_offset.empty()) {
    options.laser_offset = args.laser_offset;
  }
  std::string frame = args.frame.empty() ? context.options.eval.trajectory_frame : args.frame;
  if (frame != "base" && frame != "laser") {
    return ReportError(InvalidInput("--frame must be 'base' or 'laser', not '" + frame + "'"));
  }
  auto reader = recording::RecordingReader::Open(args.log, {options, context.bag});
  if (!reader.ok()) {
    return ReportError(reader.error());
  }
  std::vector<io::StampedPose> poses;
  while (true) {
    auto next = reader.value().Next();
    if (!next.ok()) {
      return ReportError(next.error());
    }
    if (!next.value()) {
      break;
    }
    const Frame& f = *next.value();
    poses.push_back(io::TrajectoryEntry(f, f.T_odom_base, frame));
  }
  const io::CarmenStats& stats = reader.value().Stats();
  if (poses.empty()) {
    return ReportError(io::NoScansError(args.log, stats));
  }
  if (const Status s = io::WriteTrajectoryByExtension(args.output, poses); !s.ok()) {
    return ReportError(s.error());
  }
  std::fprintf(stderr,
               "gridslam odometry: %zu scans (%s frame) written to %s; %ld lines, %ld ODOM, "
               "%ld repaired timestamps, %ld scans outside the odometry, %ld ODOM with time <= 0, "
               "%ld unknown-type lines skipped, %ld malformed lines skipped\n",
               poses.size(), frame.c_str(), args.output.c_str(), stats.lines, stats.odometry,
               stats.repaired_timestamps, stats.scans_without_odometry, stats.skipped_bad_odometry,
               stats.skipped_unknown, stats.skipped_malformed);
  return kExitOk;
}

RunFunction SetupOdometry(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<OdometryArgs>();
  sub.add_option("LOG", args->log,
                 "Recording: CARMEN log (optionally gzip-compressed) or bag (.bag, .mcap, rosbag2)")
      ->required();
  sub.add_option("-o,--output", args->output,
                 "Trajectory file (.tum = TUM, else timestamp x y "
                 "theta)")
      ->required();
  sub.add_option("--laser-offset", args->laser_offset,
                 "Laser mounting x y theta [m m rad] (overrides log.laser_offset and PARAM lines)")
      ->expected(3);
  sub.add_option("--frame", args->frame, "base or laser (default: eval.trajectory_frame)");
  return [args](AppContext& ctx) { return RunOdometry(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "odometry", "Write the raw odometry pose of every laser scan of a CARMEN log", SetupOdometry});

}  // namespace
}  // namespace gridslam::app
