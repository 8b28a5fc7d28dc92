// Online estimate of how good a robot's odometry yaw is (front_end.hpp). The odometry prior of
// the scan matcher has documented default standard deviations (front_end_options.hpp), loose
// enough for poor odometry (intel's wheels slip by degrees). Some robots' odometry is far better
// (the Freiburg hospital log's is near-exact), and a loose prior then lets a poorly constrained
// match (wide halls at 1° beam spacing) turn by degrees at once. This estimator scales the yaw
// prior to the odometry at hand, innovation-based, as adaptive Kalman filters do (Mehra, IEEE TAC
// 15(2), 1970): each accepted match's yaw correction of the odometry prediction, in units of the
// default standard deviation, goes into a window of the last N; the scale is the robust RMS of
// the window (median of the squares over the median of chi-square with one degree of freedom),
// clamped to [min_scale, 1]. The correction holds the matcher's error too, so the scaled prior is
// never tighter than odometry and matcher disagree: a good matcher still corrects good odometry.
//
// Translation is not adapted: odometry's translation errors are mostly systematic (a wrong wheel
// radius: fr079's odometry is 4 % short), small per scan and invisible to a per-scan statistic,
// and a tightened prior lets them through wherever the scan constrains translation weakly (a
// corridor): measured, fr079 all relations went from 0.037 m to 3.5 m when translation was
// adapted too (docs/front_end.md).
#pragma once

#include <cstddef>
#include <vector>

namespace gridslam::scan_matching {

class OdometryNoiseEstimate {
 public:
  /// `window`: corrections kept (> 0); `min_scale` in (0, 1].
  OdometryNoiseEstimate(int window, double min_scale);

  /// Adds the yaw correction of one accepted match [rad], given the default standard deviation
  /// of the prediction's yaw [rad].
  void Add(double theta_correction, double sigma_theta);

  /// Factor of the default yaw standard deviation; 1 until the window has filled once.
  [[nodiscard]] double RotationScale() const { return rotation_scale_; }

 private:
  std::size_t window_;
  double min_scale_;
  std::vector<double> rotation_;  ///< Squared normalized corrections, ring buffer.
  std::size_t next_ = 0;
  double rotation_scale_ = 1.0;
};

}  // namespace gridslam::scan_matching
