#include "gridslam/simulation/simulator.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "gridslam/simulation/random.hpp"
#include "gridslam/simulation/relation_builder.hpp"
#include "gridslam/simulation/route.hpp"
#include "gridslam/simulation/sensor_models.hpp"

namespace gridslam::simulation {
namespace {

constexpr std::uint64_t kLaserStream = 1;
constexpr std::uint64_t kOdometryStream = 2;

std::string FormatPoint(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s.precision(3);
  s << std::fixed << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

Status CheckWaypoints(const World& world, const std::vector<Eigen::Vector2d>& points,
                      double radius) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (world.Clearance(points[k]) < radius) {
      return InvalidInput("route waypoint " + std::to_string(k) + " " + FormatPoint(points[k]) +
                          " is closer than the robot radius to a wall or outside the world");
    }
  }
  return Status::Ok();
}

Result<RobotRun> RunRobot(const World& world, const Route& base_route,
                          const SimulationOptions& options, int index) {
  const Route route = index % 2 == 1 ? base_route.Reversed() : base_route;
  const double length = route.Length();
  // Robot i starts at fraction i / N of the route (in the forward direction, also when it drives
  // the route backwards).
  const double fraction = static_cast<double>(index) / options.robots;
  const double s_start = length * (index % 2 == 1 ? 1.0 - fraction : fraction);
  const bool forever = options.duration > 0.0;
  const double s_end = forever ? std::numeric_limits<double>::infinity() : s_start + length;
  PurePursuit controller(route, options.motion, s_start, s_end);
  const LaserSimulator laser(world, options.laser);
  const OdometrySimulator odometry(options.odometry);
  const auto seed = static_cast<std::uint64_t>(options.seed);
  Random laser_random(seed, 16U * static_cast<std::uint64_t>(index) + kLaserStream);
  Random odometry_random(seed, 16U * static_cast<std::uint64_t>(index) + kOdometryStream);

  const double dt = options.motion.control_period;
  const std::int64_t dt_us = std::llround(dt * 1e6);
  // Robot i's clock runs i/4 of a control period late: robots never share a timestamp.
  const std::int64_t start_us = std::llround(options.start_time * 1e6) + index * (dt_us / 4);
  const long steps_per_scan = std::max(1L, std::lround(1.0 / (options.laser.rate * dt)));
  const long steps_per_odom = std::max(1L, std::lround(1.0 / (options.motion.odometry_rate * dt)));
  const long max_steps = forever
                             ? std::lround(options.duration / dt)
                             : std::lround((4.0 * length / options.motion.max_speed + 120.0) / dt);
  const Pose2 T_base_laser(options.laser.offset[0], options.laser.offset[1],
                           options.laser.offset[2]);

  RobotRun run;
  RobotState state{controller.StartPose(), 0.0, 0.0};
  run.T_world_odom = state.pose;
  run.min_clearance = world.Clearance(state.pose.translation());
  Pose2 odom;
  double tv = 0.0;
  double rv = 0.0;
  for (long k = 0;; ++k) {
    const Time time{Duration((start_us + k * dt_us) * 1000)};
    const bool scan_due = k % steps_per_scan == 0;
    if (scan_due || k % steps_per_odom == 0) {
      run.odometry.push_back({time, odom, tv, rv});
    }
    if (scan_due) {
      Frame frame;
      frame.time = time;
      frame.corrected_time = time;
      frame.T_odom_base = odom;
      frame.T_base_laser = T_base_laser;
      frame.scan = laser.Scan(state.pose * T_base_laser, laser_random);
      frame.T_world_base_true = state.pose;
      run.frames.push_back(std::move(frame));
    }
    if (forever ? k >= max_steps : controller.Finished()) {
      run.duration = static_cast<double>(k) * dt;
      break;
    }
    if (k >= max_steps) {
      return RuntimeError("robot " + std::to_string(index) + " got stuck near " +
                          FormatPoint(state.pose.translation()));
    }
    controller.Control(state, dt);
    const Pose2 next = IntegrateUnicycle(state.pose, state.v, state.w, dt);
    const Pose2 measured = odometry.Measure(Between(state.pose, next), odometry_random);
    odom = odom * measured;
    tv = measured.x() / dt;
    rv = measured.theta() / dt;
    run.distance += (next.translation() - state.pose.translation()).norm();
    state.pose = next;
    const double clearance = world.Clearance(next.translation());
    run.min_clearance = std::min(run.min_clearance, clearance);
    if (clearance < options.motion.robot_radius) {
      std::ostringstream message;
      message.precision(2);
      message << std::fixed << "robot " << index << " comes within " << clearance
              << " m of a wall at " << FormatPoint(next.translation()) << " after "
              << static_cast<double>(k) * dt << " s; the route must keep "
              << options.motion.robot_radius << " m (robot_radius) clear of walls";
      return InvalidInput(message.str());
    }
  }
  return run;
}

}  // namespace

Result<SimulationResult> Simulate(const World& world, const std::vector<Eigen::Vector2d>& route,
                                  const SimulationOptions& options) {
  GRIDSLAM_RETURN_IF_ERROR(options.Validate());
  const std::vector<Eigen::Vector2d>& points = route.empty() ? world.route : route;
  if (points.empty()) {
    return InvalidInput("world '" + world.name + "' has no built-in route: give a waypoints file");
  }
  GRIDSLAM_RETURN_IF_ERROR(CheckWaypoints(world, points, options.motion.robot_radius));
  auto loop = Route::Make(points);
  if (!loop.ok()) {
    return loop.error();
  }
  SimulationResult result;
  const RayCaster caster(world);
  for (int i = 0; i < options.robots; ++i) {
    auto run = RunRobot(world, loop.value(), options, i);
    if (!run.ok()) {
      return run.error();
    }
    run.value().relations = MakeWithinRelations(run.value().frames, options.relations, caster);
    result.robots.push_back(std::move(run).value());
  }
  if (options.robots > 1) {
    result.between = MakeBetweenRelations(result.robots, options.relations, caster);
  }
  return result;
}

}  // namespace gridslam::simulation
