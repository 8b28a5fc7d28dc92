// `gridslam map LOG [LOG ...] -o DIR [--config FILE]`: the whole system (DESIGN.md §1, §2). Each
// LOG is one robot with its own odometry frame and unknown start; their frames are processed
// interleaved by time, as a team would deliver them. Writes the map(s), the corrected
// trajectories, the optimized graph, the effective configuration and a report into DIR.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/pipeline/mapper.hpp"

#include "app_map_output.hpp"
#include "app_output_dir.hpp"
#include "command.hpp"
#include <unistd.h>

namespace gridslam::app {
namespace {

using Clock = std::chrono::steady_clock;

struct MapArgs {
  std::vector<std::string> logs;
  std::string output;
};

nlohmann::json StatsJson(const pipeline::MapperStats& s) {
  return {{"frames", s.frames},
          {"key_maps", s.key_maps},
          {"featureless_key_maps", s.featureless},
          {"sequential_edges_aligned", s.sequential_aligned},
          {"closures",
           {{"proposed", s.candidates + s.appearance_candidates},
            {"prior_candidates", s.candidates},
            {"appearance_queries", s.appearance_queries},
            {"appearance_candidates", s.appearance_candidates},
            {"verified", s.verified},
            {"found_by_prior_refinement", s.prior_refined},
            {"prior_searches", s.prior_searches},
            {"online_full_optimizations", s.online_full_optimizations},
            {"accepted", s.accepted},
            {"rejected_gate", s.rejected_gate},
            {"rejected_alignment", s.candidates + s.appearance_candidates - s.verified},
            {"pruned", s.pruned}}},
          {"joins", s.joins},
          {"chi2_final", s.chi2_final},
          {"time_s",
           {{"front_end", s.seconds_front_end},
            {"description", s.seconds_description},
            {"alignment", s.seconds_alignment},
            {"online_optimization", s.seconds_optimization},
            {"final_optimization", s.seconds_final},
            {"fusion", s.seconds_fusion}}}};
}

int RunMap(const MapArgs& args, AppContext& context) {
  const auto start = Clock::now();
  const int num_robots = static_cast<int>(args.logs.size());
  std::vector<io::CarmenReader> readers;
  for (const std::string& log : args.logs) {
    auto reader = io::CarmenReader::Open(log, context.options.log);
    if (!reader.ok()) {
      return ReportError(reader.error());
    }
    readers.push_back(std::move(reader).value());
  }
  auto output = OutputDir::Begin(args.output);  // staged, committed at the end (issue 17)
  if (!output.ok()) {
    return ReportError(output.error());
  }

  pipeline::Mapper mapper(context.options, num_robots);
  std::vector<RobotOutput> robots(static_cast<std::size_t>(num_robots));
  std::vector<std::optional<Frame>> next(static_cast<std::size_t>(num_robots));
  std::vector<std::optional<Time>> first_time(static_cast<std::size_t>(num_robots));
  // Reads the next frame of robot r into next[r]; false on a read error (reported).
  const auto advance = [&](std::size_t r) -> std::optional<Error> {
    auto frame = readers[r].Next();
    if (!frame.ok()) {
      return frame.error();
    }
    next[r] = std::move(frame).value();
    return std::nullopt;
  };
  for (std::size_t r = 0; r < next.size(); ++r) {
    robots[r].log = args.logs[r];
    if (auto error = advance(r)) {
      return ReportError(*error);
    }
  }
  const bool progress = isatty(fileno(stderr)) != 0;
  long processed = 0;
  while (true) {
    // The robot whose next frame comes first (by the repaired time used for ordering).
    std::optional<std::size_t> robot;
    for (std::size_t r = 0; r < next.size(); ++r) {
      if (next[r].has_value() &&
          (!robot || next[r]->corrected_time < next[*robot]->corrected_time)) {
        robot = r;
      }
    }
    if (!robot) {
      break;
    }
    const std::size_t r = *robot;
    const Frame& frame = *next[r];
    if (!first_time[r]) {
      first_time[r] = frame.time;
    }
    robots[r].duration = ToSeconds(frame.time - *first_time[r]);
    robots[r].T_base_laser.push_back(frame.T_base_laser);
    ++robots[r].scans;
    mapper.AddFrame(static_cast<int>(r), frame);
    if (auto error = advance(r)) {
      return ReportError(*error);
    }
    if (progress && ++processed % 250 == 0) {
      const pipeline::MapperStats& s = mapper.Stats();
      std::fprintf(stderr, "\rgridslam map: %ld scans, %ld key maps, %ld loop closures", s.frames,
                   s.key_maps, s.accepted);
      std::fflush(stderr);
    }
  }
  if (progress) {
    std::fprintf(stderr, "\n");
  }
  for (std::size_t r = 0; r < readers.size(); ++r) {
    if (robots[r].scans == 0) {  // nothing to map: say so, leave any earlier result alone
      return ReportError(io::NoScansError(args.logs[r], readers[r].Stats()));
    }
  }
  const auto mapped = Clock::now();
  pipeline::MapperResult result = mapper.Finish();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();

  nlohmann::json report = StatsJson(result.stats);
  double duration = 0.0;
  nlohmann::json logs = nlohmann::json::array();
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const io::CarmenStats& s = readers[r].Stats();
    logs.push_back({{"log", robots[r].log},
                    {"robot", r},
                    {"scans", robots[r].scans},
                    {"duration_s", robots[r].duration},
                    {"skipped_malformed_lines", s.skipped_malformed},
                    {"repaired_timestamps", s.repaired_timestamps}});
    duration = std::max(duration, robots[r].duration);
  }
  report["logs"] = logs;
  nlohmann::json joins = nlohmann::json::array();
  for (const pipeline::JoinRecord& j : result.joins) {
    joins.push_back({{"robots", {j.robot_a, j.robot_b}},
                     {"time", FormatSeconds(j.time)},
                     {"vertices", {j.vertex_a, j.vertex_b}},
                     {"matches", j.matches}});
  }
  report["robot_joins"] = joins;
  report["time_s"]["total"] = seconds;
  report["time_s"]["mapping"] = std::chrono::duration<double>(mapped - start).count();
  report["real_time_factor"] = seconds > 0.0 ? duration / seconds : 0.0;
  const std::string config =
      "# gridslam map: effective configuration\n" + io::OptionsToYaml(context.options);
  if (const Status s = WriteMapOutputs(output.value()->path(), result, robots,
                                       context.options.eval.trajectory_frame, config, report);
      !s.ok()) {
    return ReportError(s.error());
  }
  if (const Status s = output.value()->Commit(); !s.ok()) {
    return ReportError(s.error());
  }
  const pipeline::MapperStats& s = result.stats;
  std::fprintf(stderr,
               "gridslam map: %ld scans, %ld key maps, %ld loop closures accepted (%ld verified, "
               "%ld gated, %ld pruned), %ld joins; %.2f s, %.0fx real time; outputs in %s\n",
               s.frames, s.key_maps, s.accepted, s.verified, s.rejected_gate, s.pruned, s.joins,
               seconds, seconds > 0.0 ? duration / seconds : 0.0, args.output.c_str());
  return kExitOk;
}

RunFunction SetupMap(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<MapArgs>();
  sub.add_option("LOG", args->logs, "CARMEN log(s), one per robot (optionally gzip-compressed)")
      ->required();
  sub.add_option("-o,--output", args->output, "Output folder")->required();
  return [args](AppContext& ctx) { return RunMap(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "map", "The whole system: key maps, SURF on the distance transform, SGD graph, fused map",
    SetupMap});

}  // namespace
}  // namespace gridslam::app
