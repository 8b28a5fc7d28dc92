// `gridslam perturb LOG -o OUT.clf [--faults FILE.yaml] [fault flags]` (issue 16;
// docs/robustness.md): a variant of a CARMEN log with seeded, documented faults: odometry glitches,
// calibration errors, clock jitter, removed odometry, fewer scans, a shorter range, a cropped field
// of view, fewer beams, range noise, dropped returns, a time cut. Every printed laser timestamp of
// the scans that remain is kept, so the log's benchmark relations still apply.
//
// OUT is written as the reader delivers the log (its frames): per scan an ODOM line and a
// ROBOTLASER1 line carrying the same (perturbed) odometry, so the ODOM lines and the odometry in
// the laser lines always agree; with --no-odometry there are no ODOM lines and the scans are
// pose-less RAWLASER1 lines, which the reader delivers with Frame::has_odometry = false. The
// first lines are comments giving the source, every fault option and every injected glitch.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/carmen_writer.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/perturb/log_perturbation.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct PerturbArgs {
  std::string log;
  std::string output;
  std::string faults;
  std::optional<int> seed;
  std::optional<double> start, duration;
  std::optional<double> glitch_period, glitch_yaw_fraction;
  std::optional<double> translation_scale, rotation_scale, yaw_drift, time_jitter;
  bool no_odometry = false;
  std::optional<int> keep_every, beam_step;
  std::optional<double> max_range, fov_deg, range_noise, beam_dropout;
};

template <class T>
void Override(T& value, const std::optional<T>& flag) {
  if (flag) {
    value = *flag;
  }
}

std::string GlitchText(const perturb::GlitchEvent& e) {
  char buffer[160];
  if (e.kind == perturb::GlitchKind::kYaw) {
    std::snprintf(buffer, sizeof(buffer), "glitch at %s: yaw jump %+.2f deg",
                  FormatSeconds(e.time).c_str(), RadToDeg(e.jump.theta()));
  } else {
    std::snprintf(buffer, sizeof(buffer), "glitch at %s: translation jump %.3f m (%+.3f, %+.3f)",
                  FormatSeconds(e.time).c_str(), e.jump.translation().norm(), e.jump.x(),
                  e.jump.y());
  }
  return buffer;
}

Status WritePerturbedLog(const std::string& path, const std::string& source,
                         const perturb::PerturbOptions& options, const perturb::PerturbedLog& log) {
  // A log read without odometry stays without (rather than gaining constant odometry).
  const bool no_odometry =
      options.remove_odometry || std::none_of(log.frames.begin(), log.frames.end(),
                                              [](const Frame& f) { return f.has_odometry; });
  io::CarmenWriterOptions writer_options;
  writer_options.hostname = "gridslam-perturb";
  writer_options.laser_message =
      no_odometry ? io::CarmenLaserMessage::kRawLaser1 : io::CarmenLaserMessage::kRobotLaser1;
  writer_options.write_truepos = true;
  const std::vector<Frame>& frames = log.frames;
  const Time start = frames.front().time;
  io::CarmenWriter writer(path, writer_options, start);
  writer.Comment("gridslam perturb: a fault variant of " + source +
                 " (printed laser timestamps kept)");
  // The options as YAML without their documentation lines (perturb --faults reads them back).
  std::string yaml;
  std::istringstream lines(io::OptionsToYaml(options));
  for (std::string line; std::getline(lines, line);) {
    const std::size_t first = line.find_first_not_of(' ');
    if (first != std::string::npos && line[first] != '#') {
      yaml += (yaml.empty() ? "" : "\n") + line;
    }
  }
  writer.Comment("fault options (perturb::PerturbOptions, YAML):\n" + yaml);
  writer.Comment(std::to_string(frames.size()) + " scans kept, " + std::to_string(log.cut) +
                 " outside the cut, " + std::to_string(log.decimated) + " dropped by keep_every, " +
                 std::to_string(log.glitches.size()) + " glitches");
  for (const perturb::GlitchEvent& e : log.glitches) {
    writer.Comment(GlitchText(e));
  }
  if (no_odometry) {
    writer.Comment("odometry removed: no ODOM lines, pose-less RAWLASER1 (has_odometry = false)");
  }
  writer.LaserOffsetParams(frames.front().T_base_laser, start);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (!no_odometry) {
      io::CarmenOdometry odometry{frames[k].time, frames[k].T_odom_base};
      if (k > 0) {
        const double dt = ToSeconds(frames[k].corrected_time - frames[k - 1].corrected_time);
        if (dt > 0.0) {
          const Pose2 delta = Between(frames[k - 1].T_odom_base, frames[k].T_odom_base);
          odometry.tv = delta.x() / dt;
          odometry.rv = delta.theta() / dt;
        }
      }
      writer.Odometry(odometry);
    }
    writer.Laser(frames[k]);
  }
  return writer.Close();
}

int RunPerturb(const PerturbArgs& args, AppContext& context) {
  perturb::PerturbOptions options;
  if (!args.faults.empty()) {
    auto text = io::ReadTextFile(args.faults);
    if (!text.ok()) {
      return ReportError(text.error());
    }
    if (const Status s = io::LoadOptionsFromString(text.value(), args.faults, options); !s.ok()) {
      return ReportError(s.error());
    }
  }
  Override(options.seed, args.seed);
  Override(options.start, args.start);
  Override(options.duration, args.duration);
  Override(options.glitch_period, args.glitch_period);
  Override(options.glitch_yaw_fraction, args.glitch_yaw_fraction);
  Override(options.translation_scale, args.translation_scale);
  Override(options.rotation_scale, args.rotation_scale);
  Override(options.yaw_drift, args.yaw_drift);
  Override(options.time_jitter, args.time_jitter);
  options.remove_odometry = options.remove_odometry || args.no_odometry;
  Override(options.keep_every, args.keep_every);
  Override(options.beam_step, args.beam_step);
  Override(options.max_range, args.max_range);
  Override(options.fov_deg, args.fov_deg);
  Override(options.range_noise, args.range_noise);
  Override(options.beam_dropout, args.beam_dropout);
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  auto frames = io::ReadCarmenLog(args.log, context.options.log);
  if (!frames.ok()) {
    return ReportError(frames.error());
  }
  if (frames.value().empty()) {
    return ReportError(InvalidInput("the log has no laser scans", args.log));
  }
  auto perturbed = perturb::PerturbLog(frames.value(), options);
  if (!perturbed.ok()) {
    Error error = perturbed.error();
    error.file = args.log;
    return ReportError(error);
  }
  if (const Status s = WritePerturbedLog(args.output, args.log, options, perturbed.value());
      !s.ok()) {
    return ReportError(s.error());
  }
  const perturb::PerturbedLog& log = perturbed.value();
  std::printf(
      "gridslam perturb: %zu of %zu scans of %s written to %s (seed %d; %ld outside the cut, "
      "%ld dropped by keep_every; %zu glitches%s)\n",
      log.frames.size(), frames.value().size(), args.log.c_str(), args.output.c_str(), options.seed,
      log.cut, log.decimated, log.glitches.size(),
      options.remove_odometry ? "; odometry removed" : "");
  return kExitOk;
}

RunFunction SetupPerturb(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<PerturbArgs>();
  sub.add_option("LOG", args->log, "CARMEN log (optionally gzip-compressed)")->required();
  sub.add_option("-o,--output", args->output, "Perturbed log (CARMEN)")->required();
  sub.add_option(
      "--faults", args->faults,
      "YAML file of fault options (the keys of perturb::PerturbOptions; flags override)");
  sub.add_option("--seed", args->seed, "Seed of every random draw (default 1)");
  sub.add_option("--start", args->start, "Keep scans from S seconds after the first on");
  sub.add_option("--duration", args->duration, "Keep S seconds of scans (0 = to the end)");
  sub.add_option("--glitch-period", args->glitch_period,
                 "Odometry glitches, one every S seconds on average (yaw 25-85 deg or 0.3-1 m)");
  sub.add_option("--glitch-yaw-fraction", args->glitch_yaw_fraction,
                 "Share of glitches that are yaw jumps (default 0.5; the rest translation)");
  sub.add_option("--translation-scale", args->translation_scale,
                 "Odometry calibration: factor on every translation increment");
  sub.add_option("--rotation-scale", args->rotation_scale,
                 "Odometry calibration: factor on every rotation increment");
  sub.add_option("--yaw-drift", args->yaw_drift, "Odometry yaw drift [rad/s]");
  sub.add_option("--time-jitter", args->time_jitter,
                 "Laser/odometry clock jitter: odometry taken at t + N(0, S) [s]");
  sub.add_flag("--no-odometry", args->no_odometry, "Remove the odometry (scan matching alone)");
  sub.add_option("--keep-every", args->keep_every, "Keep every k-th scan");
  sub.add_option("--max-range", args->max_range,
                 "Readings at or beyond M metres become no-returns");
  sub.add_option("--fov", args->fov_deg, "Keep the beams within +-D/2 degrees of the laser axis");
  sub.add_option("--beam-step", args->beam_step, "Keep every k-th beam");
  sub.add_option("--range-noise", args->range_noise, "Gaussian range noise, sigma [m]");
  sub.add_option("--beam-dropout", args->beam_dropout,
                 "Probability that a return becomes 0 (no return)");
  return [args](AppContext& ctx) { return RunPerturb(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "perturb", "Write a fault variant of a CARMEN log (glitches, calibration, sensor changes)",
    SetupPerturb});

}  // namespace
}  // namespace gridslam::app
