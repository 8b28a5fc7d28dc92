// Writing what `gridslam map` produces (docs/design.md §2): map.pgm + map.yaml, map.png,
// map_graph.png (trajectories and accepted loop closures over the map), trajectory files,
// graph.g2o, config.yaml and report.json. Only apps/ knows these file names.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gridslam/common/result.hpp"
#include "gridslam/pipeline/mapper.hpp"

#include "app_image_buffer.hpp"

namespace gridslam::app {

/// Per-robot data the writer needs besides the mapper's result.
struct RobotOutput {
  std::string log;
  std::vector<Pose2> T_base_laser;  ///< Laser mounting of every scan (for laser-frame output).
  long scans = 0;
  double duration = 0.0;         ///< Log duration [s].
  long skipped_malformed = 0;    ///< Malformed lines or messages skipped (--lenient).
  long repaired_timestamps = 0;  ///< Timestamps changed by the repair (log.repair_timestamps).
};

/// Writes every output file into `dir` (which exists). `trajectory_frame`: "base" or "laser".
/// The pictures are drawn in `pictures` (a buffer of their own when null).
Status WriteMapOutputs(const std::string& dir, const pipeline::MapperResult& result,
                       const std::vector<RobotOutput>& robots, const std::string& trajectory_frame,
                       const std::string& config_yaml, nlohmann::json report,
                       ImageBuffer* pictures = nullptr, int threads = 1);

}  // namespace gridslam::app
