// One mapping session besides the mapper (docs/design.md §2): what `gridslam map` records with
// every frame (the laser mounting of each scan, scan counts and durations, the self-check's scan
// sample) and, once the mapper has finished, writes into an output folder: the self-check, the
// map, trajectories, graph, configuration and report (app_map_output.hpp). Shared by
// `gridslam map` and the ROS node (ros/), so both write the same files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gridslam/common/result.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"

#include "app_map_output.hpp"
#include "app_map_quality.hpp"

namespace gridslam::app {

class MapSession {
 public:
  /// One robot per entry of `logs` (the name written into report.json).
  MapSession(const SlamOptions& options, const std::vector<std::string>& logs);

  /// Records `robot`'s next frame: call with every frame given to Mapper::AddFrame.
  void Record(int robot, const Frame& frame);

  /// Per robot: log name, mounting of every scan, counts (the caller may set the reader's).
  [[nodiscard]] std::vector<RobotOutput>& Robots() { return robots_; }
  [[nodiscard]] const std::vector<RobotOutput>& Robots() const { return robots_; }
  /// The longest robot's duration so far [s] (first to latest frame).
  [[nodiscard]] double Duration() const;

  /// report.json's common part (MapReport): statistics, logs, joins.
  [[nodiscard]] nlohmann::json Report(const pipeline::MapperResult& result) const;

  /// Runs the self-check (its heat images go into `dir`), adds it to `report` as "quality" and
  /// writes every output file into `dir` (which exists; normally an OutputDir's staging folder).
  /// `producer` heads config.yaml ("gridslam map"). Returns the self-check's summary line.
  Result<std::string> Write(const std::string& dir, const pipeline::MapperResult& result,
                            nlohmann::json report, const std::string& producer) const;

 private:
  SlamOptions options_;
  QualityScans quality_scans_;
  std::vector<RobotOutput> robots_;
  std::vector<std::optional<Time>> first_time_;
};

/// Removes the files of an earlier map run in `dir` that this run did not write (e.g.
/// trajectory_2.* of a 3-robot run, map_1.* of a run with two maps); returns how many.
int RemoveStaleMapOutputs(const std::string& dir, std::size_t num_robots, std::size_t num_maps);

}  // namespace gridslam::app
