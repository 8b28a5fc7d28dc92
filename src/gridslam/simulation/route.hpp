// Routes and the controller that drives them. A Route is a closed polyline parameterized by arc
// length (an open list of waypoints is driven there and back). PurePursuit steers a unicycle
// robot along it (Coulter 1992, "Implementation of the pure pursuit path tracking algorithm"):
// it steers towards the route point one lookahead distance ahead of the robot's progress, with
// curvature 2 sin(alpha) / d, slows down where the curvature demands more than the turn-rate
// limit, turns in place when the target is far off to the side, and respects acceleration
// limits. Progress along the route only moves forward, within a short arc-length window, so
// overlapping parts of a route (a room entered and left through the same door) cannot confuse it.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "gridslam/common/result.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/simulation/simulation_options.hpp"

namespace gridslam::simulation {

class Route {
 public:
  /// A closed route through `points` (at least 2, no two consecutive equal). If the last point
  /// differs from the first, the route drives back through the points in reverse order.
  static Result<Route> Make(const std::vector<Eigen::Vector2d>& points);

  /// Total arc length [m].
  [[nodiscard]] double Length() const { return cumulative_.back(); }
  /// The point at arc length s (taken modulo Length()).
  [[nodiscard]] Eigen::Vector2d PointAt(double s) const;
  /// Arc length in [s_from, s_to] (unwrapped, s_from <= s_to) of the route point closest to p.
  [[nodiscard]] double Project(const Eigen::Vector2d& p, double s_from, double s_to) const;
  /// The same loop driven in the opposite direction.
  [[nodiscard]] Route Reversed() const;
  /// Vertices, the last equal to the first.
  [[nodiscard]] const std::vector<Eigen::Vector2d>& Points() const { return points_; }

 private:
  Route() = default;
  void Finish();
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> cumulative_;
};

/// The robot's true state.
struct RobotState {
  Pose2 pose;      ///< T_world_base.
  double v = 0.0;  ///< Forward speed [m/s].
  double w = 0.0;  ///< Turn rate [rad/s].
};

class PurePursuit {
 public:
  /// Drives `route` (which must outlive the controller) from arc length `s_start` to `s_end`
  /// (unwrapped; infinity = forever).
  PurePursuit(const Route& route, const MotionSimOptions& options, double s_start, double s_end);

  /// The pose at s_start, facing along the route.
  [[nodiscard]] Pose2 StartPose() const;
  /// Updates the progress from `state.pose`, then sets `state.v` and `state.w` for the next
  /// `dt` seconds, within the speed and acceleration limits.
  void Control(RobotState& state, double dt);
  /// True once the robot has reached s_end.
  [[nodiscard]] bool Finished() const;

 private:
  const Route& route_;
  MotionSimOptions options_;
  double s_end_;
  double progress_;
  bool turning_in_place_ = false;
};

/// Moves `pose` for `dt` seconds at forward speed v and turn rate w (exact circular arc).
Pose2 IntegrateUnicycle(const Pose2& pose, double v, double w, double dt);

}  // namespace gridslam::simulation
