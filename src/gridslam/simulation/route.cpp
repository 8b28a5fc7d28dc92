#include "gridslam/simulation/route.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridslam::simulation {
namespace {

constexpr double kFinishTolerance = 0.02;   // [m]
constexpr double kTurnInPlaceEnter = 1.2;   // [rad]
constexpr double kTurnInPlaceLeave = 0.3;   // [rad]
constexpr double kTurnGain = 2.0;           // [1/s]
constexpr double kMinApproachSpeed = 0.05;  // [m/s]

}  // namespace

Result<Route> Route::Make(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 2) {
    return InvalidInput("a route needs at least 2 waypoints");
  }
  for (std::size_t k = 1; k < points.size(); ++k) {
    if ((points[k] - points[k - 1]).norm() < 1e-6) {
      return InvalidInput("route waypoints " + std::to_string(k - 1) + " and " + std::to_string(k) +
                          " coincide");
    }
  }
  Route route;
  route.points_ = points;
  if ((points.back() - points.front()).norm() >= 1e-6) {
    // Open list: drive there and back.
    for (std::size_t k = points.size() - 1; k-- > 0;) {
      route.points_.push_back(points[k]);
    }
  } else {
    route.points_.back() = points.front();
  }
  if (route.points_.size() < 3) {
    return InvalidInput("a closed route needs at least 2 distinct waypoints");
  }
  route.Finish();
  return route;
}

void Route::Finish() {
  cumulative_.assign(1, 0.0);
  for (std::size_t k = 1; k < points_.size(); ++k) {
    cumulative_.push_back(cumulative_.back() + (points_[k] - points_[k - 1]).norm());
  }
}

Eigen::Vector2d Route::PointAt(double s) const {
  const double length = Length();
  s = std::fmod(s, length);
  if (s < 0.0) {
    s += length;
  }
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const auto k = static_cast<std::size_t>(
      std::clamp<long>(it - cumulative_.begin() - 1, 0, static_cast<long>(points_.size()) - 2));
  const double segment = cumulative_[k + 1] - cumulative_[k];
  const double alpha = segment > 0.0 ? (s - cumulative_[k]) / segment : 0.0;
  return points_[k] + std::clamp(alpha, 0.0, 1.0) * (points_[k + 1] - points_[k]);
}

double Route::Project(const Eigen::Vector2d& p, double s_from, double s_to) const {
  const double length = Length();
  double best_s = s_from;
  double best_d = std::numeric_limits<double>::infinity();
  const auto lap_first = static_cast<long>(std::floor(s_from / length));
  const auto lap_last = static_cast<long>(std::floor(s_to / length));
  for (long lap = lap_first; lap <= lap_last; ++lap) {
    const double base = static_cast<double>(lap) * length;
    for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
      const double a = std::max(base + cumulative_[k], s_from);
      const double b = std::min(base + cumulative_[k + 1], s_to);
      if (a > b) {
        continue;
      }
      const Eigen::Vector2d d = points_[k + 1] - points_[k];
      const double seg = cumulative_[k + 1] - cumulative_[k];
      double s = base + cumulative_[k];
      if (seg > 0.0) {
        s += (p - points_[k]).dot(d) / seg;
      }
      s = std::clamp(s, a, b);
      const double dist = (PointAt(s) - p).squaredNorm();
      if (dist < best_d) {
        best_d = dist;
        best_s = s;
      }
    }
  }
  return best_s;
}

Route Route::Reversed() const {
  Route route;
  route.points_.assign(points_.rbegin(), points_.rend());
  route.Finish();
  return route;
}

PurePursuit::PurePursuit(const Route& route, const MotionSimOptions& options, double s_start,
                         double s_end)
    : route_(route), options_(options), s_end_(s_end), progress_(s_start) {}

Pose2 PurePursuit::StartPose() const {
  const Eigen::Vector2d p = route_.PointAt(progress_);
  const Eigen::Vector2d q = route_.PointAt(progress_ + std::min(options_.lookahead, 0.2));
  return {p, std::atan2(q.y() - p.y(), q.x() - p.x())};
}

bool PurePursuit::Finished() const { return progress_ >= s_end_ - kFinishTolerance; }

void PurePursuit::Control(RobotState& state, double dt) {
  const Eigen::Vector2d p = state.pose.translation();
  progress_ = std::max(progress_, route_.Project(p, progress_, progress_ + 1.0));
  double v_cmd = 0.0;
  double w_cmd = 0.0;
  if (!Finished()) {
    const double s_target = std::min(progress_ + options_.lookahead, s_end_);
    const Eigen::Vector2d target = state.pose.Inverse() * route_.PointAt(s_target);
    const double d = target.norm();
    const double alpha = std::atan2(target.y(), target.x());
    if (std::abs(alpha) > kTurnInPlaceEnter) {
      turning_in_place_ = true;
    } else if (std::abs(alpha) < kTurnInPlaceLeave) {
      turning_in_place_ = false;
    }
    if (turning_in_place_) {
      w_cmd =
          std::clamp(kTurnGain * alpha, -options_.max_angular_speed, options_.max_angular_speed);
    } else if (d > 1e-9) {
      const double curvature = 2.0 * std::sin(alpha) / d;
      v_cmd = options_.max_speed;
      if (std::isfinite(s_end_)) {
        const double remaining = s_end_ - progress_;
        v_cmd = std::min(v_cmd, std::max(kMinApproachSpeed,
                                         std::sqrt(2.0 * options_.max_acceleration * remaining)));
      }
      if (std::abs(curvature) * v_cmd > options_.max_angular_speed) {
        v_cmd = options_.max_angular_speed / std::abs(curvature);
      }
      w_cmd = curvature * v_cmd;
    }
  }
  const double dv = options_.max_acceleration * dt;
  const double dw = options_.max_angular_acceleration * dt;
  state.v += std::clamp(v_cmd - state.v, -dv, dv);
  state.w += std::clamp(w_cmd - state.w, -dw, dw);
}

Pose2 IntegrateUnicycle(const Pose2& pose, double v, double w, double dt) {
  const double theta = pose.theta();
  const double dtheta = w * dt;
  double x = pose.x();
  double y = pose.y();
  if (std::abs(dtheta) < 1e-9) {
    const double mid = theta + 0.5 * dtheta;
    x += v * dt * std::cos(mid);
    y += v * dt * std::sin(mid);
  } else {
    const double r = v / w;
    x += r * (std::sin(theta + dtheta) - std::sin(theta));
    y -= r * (std::cos(theta + dtheta) - std::cos(theta));
  }
  return {x, y, theta + dtheta};
}

}  // namespace gridslam::simulation
