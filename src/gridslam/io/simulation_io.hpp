// Small text formats around the simulator and multi-robot runs (docs/design.md §2): the scan index
// `index.txt` (one line `timestamp robot` per laser scan of several robots' logs, in time order,
// timestamps with 6 decimals as in the logs) and route waypoint files (one `x y` line per
// waypoint in metres, world frame; '#' comments and blank lines skipped).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/result.hpp"
#include "gridslam/common/time.hpp"

namespace gridslam::io {

struct ScanIndexEntry {
  Time time;
  int robot = 0;
};

/// Writes `timestamp robot` lines in the given order.
Status WriteScanIndex(const std::string& path, const std::vector<ScanIndexEntry>& entries);

/// Reads an index file; a malformed line is an error naming file and line.
Result<std::vector<ScanIndexEntry>> ReadScanIndex(const std::string& path);

/// Reads waypoints (`x y` per line); a malformed line is an error naming file and line.
Result<std::vector<Eigen::Vector2d>> ReadWaypoints(const std::string& path);

}  // namespace gridslam::io
