// The simulator behind `gridslam simulate` (issue 3): drives one to four robots along a route
// through a World, each with its own noisy odometry and range sensor, and records what a real
// robot's log would hold (ODOM readings and laser frames in the robot's own odometry frame,
// whose origin is its start pose) together with the exact ground truth and benchmark relations
// (Kümmerle et al. 2009) derived from it. Robot i starts at fraction i / N of the route (odd
// robots drive it backwards), so routes overlap; its clock is offset by i / 4 of a control
// period, so no two robots ever share a timestamp. Everything is deterministic for a seed:
// each robot and each noise source draws from its own random stream.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "gridslam/common/result.hpp"
#include "gridslam/eval/relation.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/simulation/simulation_options.hpp"
#include "gridslam/simulation/world.hpp"

namespace gridslam::simulation {

/// One ODOM message.
struct OdometryReading {
  Time time;
  Pose2 pose;       ///< T_odom_base, as the wheel encoders integrate it.
  double tv = 0.0;  ///< Measured forward speed [m/s].
  double rv = 0.0;  ///< Measured turn rate [rad/s].
};

struct RobotRun {
  std::vector<OdometryReading> odometry;  ///< Every ODOM message, in time order.
  /// Every laser scan: time, T_odom_base (odometry at the scan), T_base_laser, the scan, and the
  /// ground truth T_world_base in T_world_base_true.
  std::vector<Frame> frames;
  std::vector<eval::Relation> relations;  ///< Within this robot's log (close in time, revisits).
  Pose2 T_world_odom;          ///< The robot's start pose: its odometry frame in the world.
  double distance = 0.0;       ///< Distance driven [m].
  double duration = 0.0;       ///< Time driven [s].
  double min_clearance = 0.0;  ///< Smallest distance to a wall along the way [m].
};

struct SimulationResult {
  std::vector<RobotRun> robots;
  /// Relations between robots: t1 from one robot's log, t2 from another's, from world-frame
  /// ground truth.
  std::vector<eval::Relation> between;
};

/// Runs the simulation. `route` overrides the world's built-in tour when not empty. Errors:
/// InvalidInput for invalid options, a route missing or leaving free space, or a robot coming
/// closer than options.motion.robot_radius to a wall; Runtime if a robot gets stuck.
Result<SimulationResult> Simulate(const World& world, const std::vector<Eigen::Vector2d>& route,
                                  const SimulationOptions& options);

}  // namespace gridslam::simulation
