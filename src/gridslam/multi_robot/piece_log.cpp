#include "gridslam/multi_robot/piece_log.hpp"

#include "gridslam/io/carmen_writer.hpp"

namespace gridslam::multi_robot {

Status WritePieceLog(const std::string& path, const std::vector<Frame>& frames,
                     const std::string& comment) {
  io::CarmenWriterOptions options;
  options.hostname = "gridslam-split";
  options.laser_message = io::CarmenLaserMessage::kRobotLaser1;
  const Time start = frames.empty() ? Time() : frames.front().time;
  io::CarmenWriter writer(path, options, start);
  if (!comment.empty()) {
    writer.Comment(comment);
  }
  if (!frames.empty()) {
    writer.LaserOffsetParams(frames.front().T_base_laser, start);
  }
  for (std::size_t k = 0; k < frames.size(); ++k) {
    io::CarmenOdometry odometry{frames[k].time, frames[k].T_odom_base};
    if (k > 0) {
      // Speeds from the previous scan (what CARMEN's ODOM carries; no reader relies on them).
      const double dt = ToSeconds(frames[k].corrected_time - frames[k - 1].corrected_time);
      if (dt > 0.0) {
        const Pose2 delta = Between(frames[k - 1].T_odom_base, frames[k].T_odom_base);
        odometry.tv = delta.x() / dt;
        odometry.rv = delta.theta() / dt;
      }
    }
    writer.Odometry(odometry);
    writer.Laser(frames[k]);
  }
  return writer.Close();
}

}  // namespace gridslam::multi_robot
