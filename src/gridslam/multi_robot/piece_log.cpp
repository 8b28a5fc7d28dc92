#include "gridslam/multi_robot/piece_log.hpp"

#include "gridslam/io/carmen_writer.hpp"

namespace gridslam::multi_robot {

Status WritePieceLog(const std::string& path, const std::vector<Frame>& frames,
                     const std::string& comment) {
  io::CarmenWriterOptions options;
  options.hostname = "gridslam-split";
  options.laser_message = io::CarmenLaserMessage::kRobotLaser1;
  return io::WriteCarmenLog(path, frames, options, comment);
}

}  // namespace gridslam::multi_robot
