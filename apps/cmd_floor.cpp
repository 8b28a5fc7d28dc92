// `gridslam floor LOG [--json]`: the floor of a mapping run's time (issue 19, docs/speed.md): read
// the recording and ray-cast every return of every scan once into one grid, at the odometry poses,
// with the fusion's ray casting (fusion::FuseScansTiled without its spacing of the scans). No
// mapper can be faster than reading its input and touching the cells its beams cross; `gridslam
// map`'s time is reported as a multiple of this (scripts/bench_speed).
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>

#include <nlohmann/json.hpp>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/recording/recording_reader.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct FloorArgs {
  std::string log;
  bool json = false;
};

double ProcessCpuSeconds() {
  return static_cast<double>(std::clock()) / static_cast<double>(CLOCKS_PER_SEC);
}

int RunFloor(const FloorArgs& args, AppContext& context) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double cpu_start = ProcessCpuSeconds();
  auto reader = recording::RecordingReader::Open(args.log, context.Recording());
  if (!reader.ok()) {
    return ReportError(reader.error());
  }
  std::vector<Frame> frames;
  long beams = 0;
  while (true) {
    auto next = reader.value().Next();
    if (!next.ok()) {
      return ReportError(next.error());
    }
    if (!next.value()) {
      break;
    }
    beams += static_cast<long>(next.value()->scan.ranges.size());
    frames.push_back(std::move(*next.value()));
  }
  if (frames.empty()) {
    return ReportError(io::NoScansError(args.log, reader.value().Stats()));
  }
  const auto read = Clock::now();
  std::vector<fusion::PosedScan> posed;
  posed.reserve(frames.size());
  for (const Frame& f : frames) {
    posed.push_back({f.T_odom_base, f.T_base_laser, &f.scan});
  }
  fusion::FusionOptions fusion = context.options.fusion;
  fusion.min_motion = 0.0;  // every scan
  fusion.min_rotation = 0.0;
  const TiledGrid<float> grid = fusion::FuseScansTiled(posed, fusion);
  const auto cast = Clock::now();
  const double read_s = std::chrono::duration<double>(read - start).count();
  const double cast_s = std::chrono::duration<double>(cast - read).count();
  const double cpu_s = ProcessCpuSeconds() - cpu_start;
  const double duration = ToSeconds(frames.back().time - frames.front().time);
  if (args.json) {
    const nlohmann::json out = {{"log", args.log},
                                {"scans", frames.size()},
                                {"beams", beams},
                                {"duration_s", duration},
                                {"read_s", read_s},
                                {"ray_cast_s", cast_s},
                                {"total_s", read_s + cast_s},
                                {"cpu_s", cpu_s},
                                {"grid_cells", grid.Limits().NumCells()},
                                {"grid_tiles", grid.NumAllocatedTiles()}};
    std::printf("%s\n", out.dump(2).c_str());
  } else {
    std::printf(
        "gridslam floor: %zu scans, %ld beams, %.0f s of data: read %.3f s + ray casting %.3f s "
        "= %.3f s (%.3f s CPU)\n",
        frames.size(), beams, duration, read_s, cast_s, read_s + cast_s, cpu_s);
  }
  return kExitOk;
}

RunFunction SetupFloor(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<FloorArgs>();
  sub.add_option("LOG", args->log,
                 "Recording: CARMEN log (optionally gzip-compressed) or bag (.bag, .mcap, rosbag2)")
      ->required();
  sub.add_flag("--json", args->json, "Print the figures as JSON");
  return [args](AppContext& ctx) { return RunFloor(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "floor",
    "Time to read a recording and ray-cast every beam once into one grid (the floor of `map`)",
    SetupFloor});

}  // namespace
}  // namespace gridslam::app
