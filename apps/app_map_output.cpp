#include "app_map_output.hpp"

#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/g2o_io.hpp"
#include "gridslam/io/map_io.hpp"
#include "gridslam/io/trajectory_io.hpp"

namespace gridslam::app {
namespace {

// map_graph.png: the map in grey, each robot's trajectory in its colour, key maps as dots and
// accepted loop closures as green lines.
Status WriteGraphPicture(const std::string& path, const OccupancyImage& map,
                         const pipeline::MapperResult& result, int component) {
  const MapLimits& limits = map.Limits();
  cv::Mat image(limits.Height(), limits.Width(), CV_8UC3);
  for (int j = 0; j < limits.Height(); ++j) {
    for (int i = 0; i < limits.Width(); ++i) {
      const signed char v = map(i, j);
      const std::uint8_t g = v == kOccupiedCell ? 0 : (v == kFreeCell ? 255 : 205);
      image.at<cv::Vec3b>(limits.Height() - 1 - j, i) = cv::Vec3b(g, g, g);
    }
  }
  const auto pixel = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d c = (p - limits.Origin()) / limits.Resolution();
    return cv::Point(static_cast<int>(c.x()), limits.Height() - 1 - static_cast<int>(c.y()));
  };
  const std::vector<cv::Scalar> colours = {{0, 0, 220}, {220, 0, 0}, {0, 140, 0}, {0, 140, 255}};
  for (std::size_t r = 0; r < result.trajectories.size(); ++r) {
    if (result.component_of_robot[r] != component) {
      continue;
    }
    const auto& trajectory = result.trajectories[r];
    for (std::size_t k = 1; k < trajectory.size(); ++k) {
      cv::line(image, pixel(trajectory[k - 1].T_map_base.translation()),
               pixel(trajectory[k].T_map_base.translation()), colours[r % colours.size()], 1);
    }
  }
  const pose_graph::PoseGraph& graph = result.graph;
  const auto in_component = [&](int id) {
    return result.component_of_robot[static_cast<std::size_t>(
               result.vertex_robot[static_cast<std::size_t>(id)])] == component;
  };
  for (const pipeline::ClosureRecord& c : result.closures) {
    if ((c.outcome == "accepted" || c.outcome == "joined") && in_component(c.from)) {
      cv::line(image, pixel(graph.vertex(graph.IndexOf(c.from)).T_map_v.translation()),
               pixel(graph.vertex(graph.IndexOf(c.to)).T_map_v.translation()),
               cv::Scalar(0, 200, 0), 1);
    }
  }
  for (const auto& v : graph.vertices()) {
    if (in_component(v.id)) {
      cv::circle(image, pixel(v.T_map_v.translation()), 2, cv::Scalar(120, 60, 0), -1);
    }
  }
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", image, png)) {
    return RuntimeError("cannot encode " + path);
  }
  return io::WriteFileAtomically(path, std::string(png.begin(), png.end()));
}

}  // namespace

Status WriteMapOutputs(const std::string& dir, const pipeline::MapperResult& result,
                       const std::vector<RobotOutput>& robots, const std::string& trajectory_frame,
                       const std::string& config_yaml, nlohmann::json report) {
  const std::filesystem::path out(dir);
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
    GRIDSLAM_RETURN_IF_ERROR(io::WriteMapImage((out / (stem + ".png")).string(), image));
    GRIDSLAM_RETURN_IF_ERROR(WriteGraphPicture((out / (stem + "_graph.png")).string(), image,
                                               result, static_cast<int>(c)));
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
