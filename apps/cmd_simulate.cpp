// `gridslam simulate --world NAME|FILE.png|FILE.yaml [--resolution R] [--robots N] [--seed S]
// [--duration S] [--route FILE] -o DIR` (issue 3; docs/design.md §2): simulated CARMEN logs with
// exact ground truth. DIR receives, for each robot i: robot_<i>.clf (ODOM + RAWLASER1, in the
// robot's own odometry frame), robot_<i>.gt.txt (`timestamp x y theta` per scan, world frame),
// robot_<i>.relations (benchmark relations); with several robots also between.relations,
// within.relations (all robots' own relations) and index.txt; and world.png + world.yaml (the
// true map, map_server), overview.png (the map with the true paths) and config.yaml.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/carmen_writer.hpp"
#include "gridslam/io/map_io.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/io/simulation_io.hpp"
#include "gridslam/io/trajectory_io.hpp"
#include "gridslam/simulation/simulator.hpp"

#include "app_output_dir.hpp"
#include "command.hpp"

namespace gridslam::app {
namespace {

namespace fs = std::filesystem;

struct SimulateArgs {
  std::optional<std::string> world;
  std::optional<double> resolution;
  std::optional<int> robots;
  std::optional<int> seed;
  std::optional<double> duration;
  std::optional<std::string> route;
  std::string output;
};

bool IsBuiltin(const std::string& name) {
  const auto names = simulation::BuiltinWorldNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Result<simulation::World> LoadWorld(const simulation::SimulationOptions& options) {
  const std::string& world = options.world;
  if (IsBuiltin(world)) {
    return simulation::MakeBuiltinWorld(world, options.resolution, options.layout);
  }
  const std::string name = fs::path(world).stem().string();
  const std::string ext = fs::path(world).extension().string();
  if (ext == ".yaml" || ext == ".yml") {
    auto map = io::ReadMap(world);
    if (!map.ok()) {
      return map.error();
    }
    return simulation::WorldFromOccupancy(name, map.value());
  }
  if (!fs::exists(world)) {
    return InvalidInput(
        "--world: '" + world +
        "' is neither a built-in world (office, ambiguous, campus, corridors, courts) nor a file");
  }
  auto image = io::ReadGrayImage(world, options.resolution);
  if (!image.ok()) {
    return image.error();
  }
  return simulation::WorldFromGrayImage(name, image.value());
}

Status WriteRobot(const fs::path& dir, int index, const simulation::RobotRun& run,
                  const simulation::SimulationOptions& options) {
  const std::string stem = "robot_" + std::to_string(index);
  io::CarmenWriterOptions writer_options;
  writer_options.hostname = "gridslam-sim";
  writer_options.accuracy = options.laser.range_noise;
  const Time start = run.odometry.front().time;
  io::CarmenWriter writer((dir / (stem + ".clf")).string(), writer_options, start);
  writer.Comment("gridslam simulate: world " + options.world + ", robot " + std::to_string(index) +
                 " of " + std::to_string(options.robots) + ", seed " +
                 std::to_string(options.seed) + "; ground truth in " + stem + ".gt.txt");
  writer.LaserOffsetParams(run.frames.front().T_base_laser, start);
  std::size_t f = 0;
  for (const simulation::OdometryReading& o : run.odometry) {
    writer.Odometry({o.time, o.pose, o.tv, o.rv, 0.0});
    if (f < run.frames.size() && run.frames[f].time == o.time) {
      writer.Laser(run.frames[f++]);
    }
  }
  GRIDSLAM_CHECK(f == run.frames.size()) << "every scan has an ODOM line at its time";
  GRIDSLAM_RETURN_IF_ERROR(writer.Close());
  std::vector<io::StampedPose> truth;
  truth.reserve(run.frames.size());
  for (const Frame& frame : run.frames) {
    truth.push_back({frame.time, *frame.T_world_base_true});
  }
  GRIDSLAM_RETURN_IF_ERROR(io::WriteTrajectory((dir / (stem + ".gt.txt")).string(), truth));
  return io::WriteRelations((dir / (stem + ".relations")).string(), run.relations);
}

Status WriteMultiRobotFiles(const fs::path& dir, const simulation::SimulationResult& result) {
  std::vector<io::ScanIndexEntry> index;
  std::vector<eval::Relation> within;
  for (std::size_t i = 0; i < result.robots.size(); ++i) {
    for (const Frame& frame : result.robots[i].frames) {
      index.push_back({frame.time, static_cast<int>(i)});
    }
    within.insert(within.end(), result.robots[i].relations.begin(),
                  result.robots[i].relations.end());
  }
  std::sort(index.begin(), index.end(),
            [](const auto& a, const auto& b) { return a.time < b.time; });
  std::sort(within.begin(), within.end(),
            [](const auto& a, const auto& b) { return a.t1 != b.t1 ? a.t1 < b.t1 : a.t2 < b.t2; });
  GRIDSLAM_RETURN_IF_ERROR(io::WriteScanIndex((dir / "index.txt").string(), index));
  GRIDSLAM_RETURN_IF_ERROR(io::WriteRelations((dir / "within.relations").string(), within));
  return io::WriteRelations((dir / "between.relations").string(), result.between);
}

int RunSimulate(const SimulateArgs& args, AppContext& context) {
  simulation::SimulationOptions& options = context.options.simulation;
  options.world = args.world.value_or(options.world);
  options.resolution = args.resolution.value_or(options.resolution);
  options.robots = args.robots.value_or(options.robots);
  options.seed = args.seed.value_or(options.seed);
  options.duration = args.duration.value_or(options.duration);
  options.route = args.route.value_or(options.route);
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  auto world = LoadWorld(options);
  if (!world.ok()) {
    return ReportError(world.error());
  }
  std::vector<Eigen::Vector2d> route;
  if (!options.route.empty()) {
    auto points = io::ReadWaypoints(options.route);
    if (!points.ok()) {
      return ReportError(points.error());
    }
    route = std::move(points).value();
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto result = simulation::Simulate(world.value(), route, options);
  if (!result.ok()) {
    Error error = result.error();
    if (error.file.empty() && !options.route.empty() &&
        error.message.find("route") != std::string::npos) {
      error.file = options.route;  // name the route file in route errors
    }
    return ReportError(error);
  }
  const double sim_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  auto output = OutputDir::Begin(args.output);  // staged, committed at the end (issue 17)
  if (!output.ok()) {
    return ReportError(output.error());
  }
  const fs::path dir(output.value()->path());
  std::vector<std::vector<Eigen::Vector2d>> paths;
  for (std::size_t i = 0; i < result.value().robots.size(); ++i) {
    const simulation::RobotRun& run = result.value().robots[i];
    if (const Status s = WriteRobot(dir, static_cast<int>(i), run, options); !s.ok()) {
      return ReportError(s.error());
    }
    paths.emplace_back();
    for (const Frame& frame : run.frames) {
      paths.back().push_back(frame.T_world_base_true->translation());
    }
  }
  const OccupancyImage truth = simulation::TrueMap(world.value());
  for (const Status& s :
       {options.robots > 1 ? WriteMultiRobotFiles(dir, result.value()) : Status::Ok(),
        io::WriteMap((dir / "world.yaml").string(), "world.png", truth),
        io::WriteMapPicture((dir / "overview.png").string(), truth, paths),
        io::WriteFileAtomically(
            (dir / "config.yaml").string(),
            "# gridslam effective configuration\n" + io::OptionsToYaml(context.options))}) {
    if (!s.ok()) {
      return ReportError(s.error());
    }
  }
  if (const Status s = output.value()->Commit(); !s.ok()) {
    return ReportError(s.error());
  }

  const MapLimits& limits = world.value().walls.Limits();
  std::printf("gridslam simulate: world %s (%.1f x %.1f m, %.3f m cells), %d robot%s, seed %d\n",
              world.value().name.c_str(), limits.Width() * limits.Resolution(),
              limits.Height() * limits.Resolution(), limits.Resolution(), options.robots,
              options.robots > 1 ? "s" : "", options.seed);
  for (std::size_t i = 0; i < result.value().robots.size(); ++i) {
    const simulation::RobotRun& run = result.value().robots[i];
    std::printf("  robot %zu: %zu scans, %.1f s, %.1f m, %zu relations, min clearance %.2f m\n", i,
                run.frames.size(), run.duration, run.distance, run.relations.size(),
                run.min_clearance);
  }
  if (options.robots > 1) {
    std::printf("  between robots: %zu relations\n", result.value().between.size());
  }
  std::printf("simulated in %.2f s; outputs in %s\n", sim_seconds, args.output.c_str());
  return kExitOk;
}

RunFunction SetupSimulate(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<SimulateArgs>();
  sub.add_option("--world", args->world,
                 "Built-in world (office, ambiguous, campus, corridors, courts), a PNG floor plan "
                 "(dark = wall) or a map_server YAML (default: simulation.world)");
  sub.add_option("--resolution", args->resolution,
                 "World cell size / PNG pixel size [m] (default: simulation.resolution)");
  sub.add_option("--robots", args->robots, "Number of robots, 1 to 4 (default 1)");
  sub.add_option("--seed", args->seed, "Random seed (same seed, byte-identical output)");
  sub.add_option("--duration", args->duration,
                 "Simulated seconds per robot; 0 = one tour of the route (default)");
  sub.add_option("--route", args->route, "Waypoints file, 'x y' per line (world frame, metres)");
  sub.add_option("-o,--output", args->output, "Output folder")->required()->check(OutputFolder());
  return [args](AppContext& ctx) { return RunSimulate(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "simulate", "Simulate laser logs with exact ground truth in a built-in or given world",
    SetupSimulate});

}  // namespace
}  // namespace gridslam::app
