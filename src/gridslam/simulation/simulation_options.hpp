// Options of the built-in 2D laser simulator (`gridslam simulate`, issue 3): the world, the
// robots, a range sensor like a SICK LMS on a Pioneer, the odometry error model and the rules
// that turn ground truth into benchmark relations (Kümmerle et al. 2009; docs/formats.md §4). The
// defaults give a log that looks like the Freiburg/Intel logs: 181 beams over 180°, 5 Hz scans,
// 10 Hz ODOM, 0.5 m/s, about 1 cm range noise and odometry that drifts a few percent.
#pragma once

#include <numbers>
#include <string>
#include <vector>

#include "gridslam/common/options.hpp"

namespace gridslam::simulation {

/// The simulated range sensor.
struct LaserSimOptions {
  int num_beams = 181;                           ///< Beams per scan, 2 to 100000.
  double field_of_view = std::numbers::pi;       ///< Angle from first to last beam [rad].
  double angular_resolution = 0.0;               ///< Beam spacing [rad]; 0 = fov / (beams - 1).
  double max_range = 30.0;                       ///< Longest reading; beyond = no return [m].
  double no_return_range = 0.0;                  ///< Value written for no-returns; 0 = max_range.
  double range_noise = 0.01;                     ///< Gaussian range noise sigma [m].
  double spurious_probability = 0.002;           ///< Chance a beam returns short (dust, people).
  double missing_probability = 0.002;            ///< Chance a beam has no return.
  double rate = 5.0;                             ///< Scans per second [Hz].
  std::vector<double> offset = {0.0, 0.0, 0.0};  ///< Laser pose on the robot [m, m, rad].

  template <class V>
  void Visit(V& v) {
    v("num_beams", num_beams, "Beams per scan");
    v("field_of_view", field_of_view, "Angle from the first to the last beam [rad]");
    v("angular_resolution", angular_resolution,
      "Beam spacing [rad]; 0 = field_of_view / (num_beams - 1); beams are centred on +x");
    v("max_range", max_range, "Longest reading; farther walls give a no-return [m]");
    v("no_return_range", no_return_range,
      "Range written for a no-return (e.g. 81.91 like a SICK sentinel); 0 = max_range [m]");
    v("range_noise", range_noise, "Standard deviation of the Gaussian range noise [m]");
    v("spurious_probability", spurious_probability,
      "Probability that a beam returns a random short range (dust, people)");
    v("missing_probability", missing_probability, "Probability that a beam has no return");
    v("rate", rate, "Scans per second [Hz]");
    v("offset", offset, "Laser pose on the robot [x m, y m, theta rad]");
  }
  [[nodiscard]] Status Validate() const;
  /// Beam spacing actually used [rad].
  [[nodiscard]] double Increment() const;
  /// Angle of the first beam [rad] (beams are symmetric about the laser's +x axis).
  [[nodiscard]] double StartAngle() const;
  /// The range written for a no-return [m].
  [[nodiscard]] double NoReturnRange() const;
};

/// Odometry error: a random walk whose variance grows with distance and rotation, plus an
/// optional systematic bias (wheel radius / wheel base errors).
struct OdometryNoiseOptions {
  double translation_noise = 0.03;          ///< Along-track sigma after 1 m [m/sqrt(m)].
  double lateral_noise = 0.01;              ///< Sideways sigma after 1 m [m/sqrt(m)].
  double rotation_noise_per_meter = 0.01;   ///< Heading sigma after 1 m [rad/sqrt(m)].
  double rotation_noise_per_radian = 0.04;  ///< Heading sigma after 1 rad turned [rad/sqrt(rad)].
  double translation_scale_bias = 0.0;      ///< Relative error of measured distance (0.01 = +1 %).
  double rotation_scale_bias = 0.0;         ///< Relative error of measured rotation.
  double rotation_drift = 0.0;              ///< Heading drift per metre travelled [rad/m].

  template <class V>
  void Visit(V& v) {
    v("translation_noise", translation_noise, "Along-track sigma after 1 m [m/sqrt(m)]");
    v("lateral_noise", lateral_noise, "Sideways sigma after 1 m [m/sqrt(m)]");
    v("rotation_noise_per_meter", rotation_noise_per_meter,
      "Heading sigma after 1 m travelled [rad/sqrt(m)]");
    v("rotation_noise_per_radian", rotation_noise_per_radian,
      "Heading sigma after 1 rad turned [rad/sqrt(rad)]");
    v("translation_scale_bias", translation_scale_bias,
      "Systematic relative error of measured distance (0.01 = 1 % too long)");
    v("rotation_scale_bias", rotation_scale_bias,
      "Systematic relative error of measured rotation (0.01 = 1 % too much)");
    v("rotation_drift", rotation_drift, "Systematic heading drift per metre travelled [rad/m]");
  }
  [[nodiscard]] Status Validate() const;
};

/// Robot motion: a pure-pursuit controller with speed and acceleration limits.
struct MotionSimOptions {
  double max_speed = 0.5;                 ///< Cruise speed [m/s].
  double max_angular_speed = 0.8;         ///< [rad/s].
  double max_acceleration = 0.5;          ///< [m/s^2].
  double max_angular_acceleration = 2.0;  ///< [rad/s^2].
  double lookahead = 0.8;                 ///< Pure-pursuit lookahead distance [m].
  double robot_radius = 0.25;             ///< Required clearance from walls [m].
  double odometry_rate = 10.0;            ///< ODOM lines per second [Hz].
  double control_period = 0.01;           ///< Control and integration step [s], >= 0.004.

  template <class V>
  void Visit(V& v) {
    v("max_speed", max_speed, "Cruise speed [m/s]");
    v("max_angular_speed", max_angular_speed, "Largest turn rate [rad/s]");
    v("max_acceleration", max_acceleration, "Linear acceleration limit [m/s^2]");
    v("max_angular_acceleration", max_angular_acceleration, "Angular acceleration limit [rad/s^2]");
    v("lookahead", lookahead, "Pure-pursuit lookahead distance along the route [m]");
    v("robot_radius", robot_radius, "Clearance the robot keeps from walls (checked) [m]");
    v("odometry_rate", odometry_rate, "ODOM lines per second [Hz]");
    v("control_period", control_period,
      "Control and integration step [s]; scans and ODOM fall on its multiples");
  }
  [[nodiscard]] Status Validate() const;
};

/// Which pairs of scans become ground-truth relations.
struct RelationSimOptions {
  int short_stride = 5;               ///< A short relation starts at every n-th scan.
  double short_span = 1.0;            ///< Time from a short relation's first to second scan [s].
  int revisit_stride = 5;             ///< Every n-th scan looks for an earlier visit.
  double revisit_min_gap = 30.0;      ///< Revisits are at least this far apart in time [s].
  double revisit_max_distance = 1.5;  ///< Largest distance between revisit poses [m].
  double revisit_max_angle = 1.0;     ///< Largest heading difference of a revisit [rad].
  int between_stride = 5;             ///< Every n-th scan looks for other robots' scans.

  template <class V>
  void Visit(V& v) {
    v("short_stride", short_stride, "A relation close in time starts at every n-th scan");
    v("short_span", short_span, "Time between the two scans of a relation close in time [s]");
    v("revisit_stride", revisit_stride, "Every n-th scan looks for an earlier visit of its place");
    v("revisit_min_gap", revisit_min_gap, "Minimum time between the scans of a revisit [s]");
    v("revisit_max_distance", revisit_max_distance,
      "Largest distance between the poses of a revisit or between-robot pair [m]");
    v("revisit_max_angle", revisit_max_angle,
      "Largest heading difference of a revisit or between-robot pair [rad]");
    v("between_stride", between_stride, "Every n-th scan looks for another robot's nearby scan");
  }
  [[nodiscard]] Status Validate() const;
};

/// Bounds checked by SimulationOptions::Validate() before a simulation starts.
constexpr double kMaxSimulatedDuration = 86400.0;  ///< simulation.duration [s].
constexpr double kMaxSimulatedReadings = 2e8;      ///< Range readings over all robots' logs.

struct SimulationOptions {
  std::string world = "office";      ///< Built-in world name, or a PNG floor plan / map YAML path.
  std::string route;                 ///< Waypoints file; "" = the world's built-in tour.
  double resolution = 0.05;          ///< World grid cell size (and PNG pixel size) [m].
  int layout = 1;                    ///< Draw of a world laid out at random (courts), >= 1.
  int robots = 1;                    ///< Number of robots (1..4).
  int seed = 1;                      ///< Random seed; equal seeds give byte-identical output.
  double duration = 0.0;             ///< Simulated time per robot [s], <= 86400; 0 = one tour.
  double start_time = 1577836800.0;  ///< Timestamp of the first message [s since epoch].
  LaserSimOptions laser;
  MotionSimOptions motion;
  OdometryNoiseOptions odometry;
  RelationSimOptions relations;

  template <class V>
  void Visit(V& v) {
    v("world", world,
      "Built-in world (office, ambiguous, campus, corridors, courts) or a PNG floor plan / map "
      "YAML file");
    v("route", route, "Waypoints file (x y per line, world frame); empty = built-in tour");
    v("resolution", resolution, "World grid cell size; pixel size of a PNG floor plan [m]");
    v("layout", layout, "Draw of the rooms of a world laid out at random (courts), 1 or more");
    v("robots", robots, "Number of robots, 1 to 4");
    v("seed", seed, "Random seed; the same seed gives byte-identical output");
    v("duration", duration, "Simulated time per robot [s]; 0 = one tour of the route");
    v("start_time", start_time, "Timestamp of the first message [s since the epoch]");
    v.Section("laser", laser, "Range sensor (a SICK LMS by default)");
    v.Section("motion", motion, "Robot motion and controller (a Pioneer by default)");
    v.Section("odometry", odometry, "Odometry error model");
    v.Section("relations", relations, "Which scan pairs become ground-truth relations");
  }
  [[nodiscard]] Status Validate() const;
};

}  // namespace gridslam::simulation
