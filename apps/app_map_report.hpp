// report.json of a mapping session (docs/guide.md §3): the mapper's statistics, one block per log,
// the robot joins. Shared by `gridslam map` and the ROS node (ros/); each adds what only it knows
// (timing, snapshots, map rotation, the self-check).
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "gridslam/pipeline/mapper.hpp"

#include "app_map_output.hpp"

namespace gridslam::app {

/// Version of report.json's layout (docs/guide.md §3): raised when a field changes meaning or is
/// removed; new fields may appear without a change.
constexpr int kReportSchemaVersion = 1;

/// The mapper's counters and timings.
nlohmann::json StatsJson(const pipeline::MapperStats& s);

/// StatsJson of the result plus schema_version, "logs" (one block per robot) and "robot_joins".
nlohmann::json MapReport(const pipeline::MapperResult& result,
                         const std::vector<RobotOutput>& robots);

}  // namespace gridslam::app
