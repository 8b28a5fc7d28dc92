#include "gridslam/simulation/simulation_options.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::simulation {

Status LaserSimOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(
      Require(num_beams >= 2 && num_beams <= 100000, "simulation.laser.num_beams in [2, 100000]"));
  GRIDSLAM_RETURN_IF_ERROR(Require(field_of_view > 0.0 && field_of_view <= 2.0 * std::numbers::pi,
                                   "simulation.laser.field_of_view in (0, 2 pi]"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(angular_resolution >= 0.0 &&
                  angular_resolution * (num_beams - 1) <= 2.0 * std::numbers::pi + 1e-9,
              "simulation.laser.angular_resolution >= 0 and (num_beams - 1) * it <= 2 pi"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(max_range > 0.0 && max_range <= 1000.0, "simulation.laser.max_range in (0, 1000]"));
  GRIDSLAM_RETURN_IF_ERROR(Require(no_return_range == 0.0 || no_return_range >= max_range,
                                   "simulation.laser.no_return_range is 0 or >= max_range"));
  GRIDSLAM_RETURN_IF_ERROR(Require(range_noise >= 0.0, "simulation.laser.range_noise >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(spurious_probability >= 0.0 && spurious_probability <= 1.0 &&
                  missing_probability >= 0.0 && missing_probability <= 1.0,
              "simulation.laser.spurious_probability and missing_probability in [0, 1]"));
  GRIDSLAM_RETURN_IF_ERROR(Require(rate > 0.0, "simulation.laser.rate > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(offset.size() == 3, "simulation.laser.offset has 3 values"));
  return Status::Ok();
}

double LaserSimOptions::Increment() const {
  return angular_resolution > 0.0 ? angular_resolution
                                  : field_of_view / static_cast<double>(num_beams - 1);
}

double LaserSimOptions::StartAngle() const {
  return -0.5 * Increment() * static_cast<double>(num_beams - 1);
}

double LaserSimOptions::NoReturnRange() const {
  return no_return_range > 0.0 ? no_return_range : max_range;
}

Status OdometryNoiseOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(translation_noise >= 0.0 && lateral_noise >= 0.0 &&
                                       rotation_noise_per_meter >= 0.0 &&
                                       rotation_noise_per_radian >= 0.0,
                                   "simulation.odometry noise values >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(std::abs(translation_scale_bias) < 0.5 && std::abs(rotation_scale_bias) < 0.5,
              "simulation.odometry scale biases in (-0.5, 0.5)"));
  return Status::Ok();
}

Status MotionSimOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(max_speed > 0.0 && max_angular_speed > 0.0 &&
                                       max_acceleration > 0.0 && max_angular_acceleration > 0.0,
                                   "simulation.motion speed and acceleration limits > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(lookahead > 0.0, "simulation.motion.lookahead > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(robot_radius >= 0.0, "simulation.motion.robot_radius >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(control_period >= 0.004 && control_period <= 0.1,
              "simulation.motion.control_period in [0.004, 0.1] (robot clocks are offset by a "
              "quarter of it, more than eval.tolerance)"));
  GRIDSLAM_RETURN_IF_ERROR(Require(odometry_rate > 0.0 && 1.0 / odometry_rate >= control_period,
                                   "simulation.motion.odometry_rate > 0 and at most "
                                   "1 / control_period"));
  return Status::Ok();
}

Status RelationSimOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(short_stride >= 1 && revisit_stride >= 1 && between_stride >= 1,
                                   "simulation.relations strides >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(short_span >= 0.0 && revisit_min_gap >= 0.0,
                                   "simulation.relations short_span and revisit_min_gap >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(revisit_max_distance > 0.0 && revisit_max_angle > 0.0,
                                   "simulation.relations revisit limits > 0"));
  return Status::Ok();
}

Status SimulationOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(!world.empty(), "simulation.world is not empty"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(resolution >= 0.005 && resolution <= 0.5, "simulation.resolution in [0.005, 0.5]"));
  GRIDSLAM_RETURN_IF_ERROR(Require(layout >= 1, "simulation.layout is 1 or more"));
  GRIDSLAM_RETURN_IF_ERROR(Require(robots >= 1 && robots <= 4, "simulation.robots in 1..4"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(duration >= 0.0 && duration <= kMaxSimulatedDuration,
              "simulation.duration in [0, 86400] s (one day of log per robot at most)"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(start_time >= 0.0 && start_time < 4e9, "simulation.start_time in [0, 4e9) seconds"));
  GRIDSLAM_RETURN_IF_ERROR(laser.Validate());
  // What the logs will hold, bounded before anything runs (memory grows with it).
  const double readings = std::max(duration, 1.0) * laser.rate * laser.num_beams * robots;
  GRIDSLAM_RETURN_IF_ERROR(
      Require(readings <= kMaxSimulatedReadings,
              "simulation.duration * simulation.laser.rate * simulation.laser.num_beams * "
              "simulation.robots <= 2e8 range readings"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(1.0 / laser.rate >= motion.control_period,
              "simulation.laser.rate at most 1 / simulation.motion.control_period"));
  GRIDSLAM_RETURN_IF_ERROR(motion.Validate());
  GRIDSLAM_RETURN_IF_ERROR(odometry.Validate());
  GRIDSLAM_RETURN_IF_ERROR(relations.Validate());
  return Status::Ok();
}

}  // namespace gridslam::simulation
