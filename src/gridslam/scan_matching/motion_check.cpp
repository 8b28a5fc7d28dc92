#include "gridslam/scan_matching/motion_check.hpp"

#include <algorithm>
#include <cmath>

#include "gridslam/common/angles.hpp"
#include "gridslam/common/check.hpp"

namespace gridslam::scan_matching {
namespace {

/// Median of the chi-square distribution with one degree of freedom.
constexpr double kChi2Median1 = 0.45493642311957283;
/// Median of the chi-square distribution with two degrees of freedom.
constexpr double kChi2Median2 = 1.3862943611198906;

double RobustStd(std::vector<double> squares, double chi2_median) {
  if (squares.empty()) {
    return 0.0;
  }
  const auto middle = squares.begin() + static_cast<std::ptrdiff_t>(squares.size() / 2);
  std::nth_element(squares.begin(), middle, squares.end());
  return std::sqrt(*middle / chi2_median);
}

/// `increment` scaled to a duration `factor` times as long (constant twist).
Pose2 ScaleIncrement(const Pose2& increment, double factor) {
  return Pose2::Exp(factor * increment.Log());
}

}  // namespace

const char* ToString(OdometryCheck check) {
  switch (check) {
    case OdometryCheck::kConsistent:
      return "consistent";
    case OdometryCheck::kDoubtful:
      return "doubtful";
    case OdometryCheck::kMissing:
      return "missing";
  }
  return "unknown";
}

MotionCheck::MotionCheck(const MotionCheckOptions& options) : options_(options) {
  GRIDSLAM_CHECK(options.Valid());
}

void MotionCheck::Reset(Time time, const Pose2& odometry, const Pose2& estimate) {
  last_time_ = time;
  last_odometry_ = odometry;
  last_estimate_ = estimate;
  motion_ = odometry;
  recent_.clear();
  recent_.push_back({time, motion_});
  overruled_ = false;
}

double MotionCheck::ThresholdXy() const {
  return std::max(options_.floor_xy, options_.sigmas * scale_xy_);
}

double MotionCheck::ThresholdTheta() const {
  return std::max(options_.floor_theta, options_.sigmas * scale_theta_);
}

MotionPrediction MotionCheck::Predict(Time time, const std::optional<Pose2>& odometry) const {
  MotionPrediction prediction;
  const double dt = ToSeconds(time - last_time_);
  Pose2 velocity;
  const double span = recent_.empty() ? 0.0 : ToSeconds(recent_.back().time - recent_.front().time);
  // Half the baseline at least, so that the estimate is an average, not one interval's jitter.
  const bool known_velocity = span >= 0.5 * options_.velocity_baseline && dt > 0.0;
  if (known_velocity) {
    // A long gap (a pause in the log) says little about the motion through it: extrapolate over
    // at most the baseline.
    const Pose2 moved = Between(recent_.front().motion, recent_.back().motion);
    velocity = ScaleIncrement(moved, std::min(dt, options_.velocity_baseline) / span);
  }
  prediction.constant_velocity = last_estimate_ * velocity;
  if (!odometry.has_value()) {
    prediction.check = OdometryCheck::kMissing;
    prediction.odometry = prediction.constant_velocity;
    prediction.odometry_increment = velocity;
    return prediction;
  }
  prediction.odometry_increment = Between(last_odometry_, *odometry);
  prediction.odometry = last_estimate_ * prediction.odometry_increment;
  const Pose2 innovation = Between(velocity, prediction.odometry_increment);
  prediction.innovation_xy = innovation.translation().norm();
  prediction.innovation_theta = std::abs(NormalizeAngle(innovation.theta()));
  const bool finite = odometry->ToVector().allFinite();
  if (!finite) {
    prediction.check = OdometryCheck::kDoubtful;
    prediction.odometry = prediction.constant_velocity;
  } else if (options_.enabled && known_velocity &&
             (prediction.innovation_xy > ThresholdXy() ||
              prediction.innovation_theta > ThresholdTheta())) {
    prediction.check = OdometryCheck::kDoubtful;
    prediction.impossible = prediction.innovation_xy > 0.5 * options_.max_acceleration * dt * dt;
  } else if (options_.enabled && overruled_) {
    prediction.check = OdometryCheck::kDoubtful;
    prediction.after_overrule = true;
  }
  return prediction;
}

void MotionCheck::Update(Time time, const std::optional<Pose2>& odometry, const Pose2& estimate,
                         const MotionPrediction& prediction, bool odometry_overruled) {
  const bool believed = prediction.check == OdometryCheck::kConsistent ||
                        (prediction.check == OdometryCheck::kDoubtful && !odometry_overruled);
  // The velocity follows the odometry where it is consistent and the extrapolation where it is
  // doubtful, never the matcher: a wrong match must not make the correct odometry that follows
  // look implausible (and then be overruled by the wrong velocity, again and again). A doubtful
  // increment the scan did not overrule may be a real manoeuvre: the velocity must learn it, or
  // every later increment of the manoeuvre would look doubtful too. Where the scan overruled
  // the odometry, or there is none, the motion is the scan-matched one.
  if (believed) {
    motion_ = motion_ * prediction.odometry_increment;
  } else {
    motion_ = motion_ * Between(last_estimate_, estimate);
  }
  if (time < last_time_) {
    recent_.clear();  // time went backwards: the history says nothing about what follows
  }
  recent_.push_back({time, motion_});
  while (recent_.size() > 2 && ToSeconds(time - recent_[1].time) >= options_.velocity_baseline) {
    recent_.pop_front();
  }
  if (believed && odometry.has_value()) {
    const double sx = prediction.innovation_xy * prediction.innovation_xy;
    const double st = prediction.innovation_theta * prediction.innovation_theta;
    const auto window = static_cast<std::size_t>(options_.window);
    if (squares_xy_.size() < window) {
      squares_xy_.push_back(sx);
      squares_theta_.push_back(st);
    } else {
      squares_xy_[next_] = sx;
      squares_theta_[next_] = st;
      next_ = (next_ + 1) % window;
    }
    scale_xy_ = RobustStd(squares_xy_, kChi2Median2);
    scale_theta_ = RobustStd(squares_theta_, kChi2Median1);
  }
  last_time_ = time;
  if (odometry.has_value() && odometry->ToVector().allFinite()) {
    last_odometry_ = *odometry;
  }
  last_estimate_ = estimate;
  overruled_ = odometry_overruled && odometry.has_value();
}

}  // namespace gridslam::scan_matching
