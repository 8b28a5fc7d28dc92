#include "app_map_output.hpp"

#include <filesystem>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/g2o_io.hpp"
#include "gridslam/io/map_io.hpp"
#include "gridslam/io/trajectory_io.hpp"

#include "app_map_pictures.hpp"

namespace gridslam::app {

Status WriteMapOutputs(const std::string& dir, const pipeline::MapperResult& result,
                       const std::vector<RobotOutput>& robots, const std::string& trajectory_frame,
                       const std::string& config_yaml, nlohmann::json report, ImageBuffer* pictures,
                       int threads) {
  const std::filesystem::path out(dir);
  ImageBuffer own;
  ImageBuffer& buffer = pictures != nullptr ? *pictures : own;
  const bool several_robots = robots.size() > 1;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    std::vector<io::StampedPose> poses;
    const auto& trajectory = result.trajectories[r];
    for (std::size_t k = 0; k < trajectory.size(); ++k) {
      Pose2 pose = trajectory[k].T_map_base;
      if (trajectory_frame == "laser" && k < robots[r].T_base_laser.size()) {
        pose = pose * robots[r].T_base_laser[k];
      }
      poses.push_back({trajectory[k].time, pose});
    }
    const std::string stem = several_robots ? "trajectory_" + std::to_string(r) : "trajectory";
    GRIDSLAM_RETURN_IF_ERROR(io::WriteTrajectory((out / (stem + ".txt")).string(), poses));
    GRIDSLAM_RETURN_IF_ERROR(io::WriteTrajectoryTum((out / (stem + ".tum")).string(), poses));
  }
  nlohmann::json maps = nlohmann::json::array();
  for (std::size_t c = 0; c < result.maps.size(); ++c) {
    const std::string stem = result.maps.size() == 1 ? "map" : "map_" + std::to_string(c);
    fusion::FusionOptions fusion;  // thresholds only
    const OccupancyImage image = fusion::ToOccupancy(result.maps[c], fusion);
    GRIDSLAM_RETURN_IF_ERROR(io::WriteMap((out / (stem + ".yaml")).string(), stem + ".pgm", image));
    GRIDSLAM_RETURN_IF_ERROR(
        WriteMapPicture((out / (stem + ".png")).string(), image, buffer, threads));
    GRIDSLAM_RETURN_IF_ERROR(WriteGraphPicture((out / (stem + "_graph.png")).string(), image,
                                               result, static_cast<int>(c), buffer, threads));
    nlohmann::json robots_in = nlohmann::json::array();
    for (std::size_t r = 0; r < robots.size(); ++r) {
      if (result.component_of_robot[r] == static_cast<int>(c)) {
        robots_in.push_back(r);
      }
    }
    maps.push_back({{"name", stem},
                    {"robots", robots_in},
                    {"width", image.Width()},
                    {"height", image.Height()},
                    {"resolution", image.Limits().Resolution()},
                    {"origin", {image.Limits().Origin().x(), image.Limits().Origin().y()}}});
  }
  report["maps"] = maps;
  GRIDSLAM_RETURN_IF_ERROR(io::WriteG2o((out / "graph.g2o").string(), result.graph));
  GRIDSLAM_RETURN_IF_ERROR(io::WriteFileAtomically((out / "config.yaml").string(), config_yaml));
  GRIDSLAM_RETURN_IF_ERROR(
      io::WriteFileAtomically((out / "report.json").string(), report.dump(2) + "\n"));
  return Status::Ok();
}

}  // namespace gridslam::app
