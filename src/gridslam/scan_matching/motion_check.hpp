// Plausibility of each odometry increment (front_end.hpp). Odometry fails in ways a per-scan
// prior cannot absorb: a wheel encoder or gyro glitch turns the pose by tens of degrees, or
// shifts it by a metre, in one step while the robot moves smoothly; some recordings carry no
// odometry at all. This check compares the odometry increment since the previous scan with a
// constant-velocity prediction from the front end's own recent estimates, and scores the
// difference (the innovation) against the robust spread of the innovations of recent consistent
// scans (median of the squares, as odometry_noise.hpp), so the threshold adapts to the robot's
// dynamics, its scan rate and its odometry: a robot that accelerates hard or a log decimated to
// 1 Hz raises the spread, a smooth platform lowers it. A floor keeps the test meaningful before
// the statistics exist. An increment is doubtful when it is implausible in translation or in
// yaw, or not finite. The front end then matches from both predictions, searches widely when
// neither explains the scan, and lets the scan overrule the odometry only when it clearly prefers
// another pose: a false alarm (a real manoeuvre) costs a second match, never the estimate.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"

namespace gridslam::scan_matching {

/// What the check says of one odometry increment.
enum class OdometryCheck {
  kConsistent,  ///< Agrees with the recent motion (or nothing to compare with yet).
  /// Implausible: a glitch, or a manoeuvre far beyond the recent dynamics; or the first
  /// increment after the scan overruled the odometry (it must earn back its trust).
  kDoubtful,
  kMissing,  ///< The frame has no odometry.
};

const char* ToString(OdometryCheck check);

struct MotionCheckOptions {
  bool enabled = true;  ///< false: every increment with odometry is consistent.
  int window = 100;     ///< Consistent scans in the robust spread of the innovations [-].
  /// An innovation beyond this many robust standard deviations is doubtful [-].
  double sigmas = 6.0;
  double floor_xy = 0.1;      ///< Innovations below this are never doubtful [m].
  double floor_theta = 0.15;  ///< ... [rad].
  /// The velocity is the estimated motion over the last this many seconds: long enough that
  /// timestamp jitter and the matcher's millimetres do not dominate it [s].
  double velocity_baseline = 1.0;
  /// The physical limit: no ground robot's velocity changes faster than its wheels' traction
  /// allows, below 1 g (a friction coefficient below 1). An increment whose translation departs
  /// from the constant velocity by more than max_acceleration * dt^2 / 2 over the scan interval
  /// dt is impossible, not merely doubtful (MotionPrediction::impossible) [m/s^2].
  double max_acceleration = 9.81;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled, "Check each odometry increment against the recent motion");
    v("window", window, "Recent consistent scans in the innovations' robust spread [-]");
    v("sigmas", sigmas, "Innovations beyond this many robust std are doubtful [-]");
    v("floor_xy", floor_xy, "Translation innovations below this are never doubtful [m]");
    v("floor_theta", floor_theta, "Yaw innovations below this are never doubtful [rad]");
    v("velocity_baseline", velocity_baseline,
      "The velocity is the estimated motion over this last stretch of time [s]");
    v("max_acceleration", max_acceleration,
      "Increments departing from the recent velocity by more than this acceleration allows "
      "over the scan interval are impossible, not merely doubtful [m/s^2]");
  }
  [[nodiscard]] bool Valid() const {
    return window > 0 && sigmas > 0.0 && floor_xy > 0.0 && floor_theta > 0.0 &&
           velocity_baseline > 0.0 && max_acceleration > 0.0;
  }
};

/// The two motion predictions of a frame and the verdict on its odometry.
struct MotionPrediction {
  Pose2 odometry;           ///< Previous estimate composed with the odometry increment.
  Pose2 constant_velocity;  ///< Previous estimate moved at the recent velocity.
  Pose2 odometry_increment;
  OdometryCheck check = OdometryCheck::kConsistent;
  double innovation_xy = 0.0;     ///< |odometry - constant velocity|, translation [m].
  double innovation_theta = 0.0;  ///< ... yaw [rad].
  /// Doubtful only because the scan overruled the previous increment: odometry that missed a
  /// reversal or a slip looks consistent with itself afterwards, so it stays doubtful until a
  /// match confirms it.
  bool after_overrule = false;
  /// Doubtful, and beyond the physical limit (MotionCheckOptions::max_acceleration): the
  /// increment is a glitch, not a manoeuvre, so it is no measurement of the motion.
  bool impossible = false;
};

class MotionCheck {
 public:
  /// `options` must be Valid().
  explicit MotionCheck(const MotionCheckOptions& options);

  /// Starts the history at the first frame.
  void Reset(Time time, const Pose2& odometry, const Pose2& estimate);

  /// Predicts the pose of a frame at `time` with odometry pose `odometry` (nullopt: none).
  [[nodiscard]] MotionPrediction Predict(Time time, const std::optional<Pose2>& odometry) const;

  /// Records the frame's final estimate; `prediction` is what Predict returned for it, and
  /// `odometry_overruled` whether the scan match replaced a doubtful odometry increment. The
  /// odometry increment enters the velocity and the statistics unless it was overruled.
  void Update(Time time, const std::optional<Pose2>& odometry, const Pose2& estimate,
              const MotionPrediction& prediction, bool odometry_overruled = false);

  /// Current thresholds (floor or k robust std) [m], [rad].
  [[nodiscard]] double ThresholdXy() const;
  [[nodiscard]] double ThresholdTheta() const;

 private:
  MotionCheckOptions options_;
  Time last_time_;
  Pose2 last_odometry_;
  Pose2 last_estimate_;
  struct Stamped {
    Time time;
    Pose2 motion;
  };
  /// The robot's motion as the check believes it: the odometry chained unless the scan
  /// overruled it or there is none, the scan-matched estimates there.
  Pose2 motion_;
  std::deque<Stamped> recent_;  ///< motion_ over the last velocity_baseline seconds.
  std::vector<double> squares_xy_;
  std::vector<double> squares_theta_;
  std::size_t next_ = 0;
  double scale_xy_ = 0.0;
  double scale_theta_ = 0.0;
  bool overruled_ = false;  ///< The scan overruled the last increment.
};

}  // namespace gridslam::scan_matching
