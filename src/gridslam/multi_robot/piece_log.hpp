// Writing one piece of a split log as a robot's CARMEN log (issue 8; docs/formats.md §1): a comment
// saying where it came from, the laser-offset PARAMs, then for every scan an ODOM line with the
// piece's odometry at the scan and the scan as ROBOTLASER1 (beam geometry plus the robot's and
// the laser's odometry poses), both with the scan's printed timestamp, exactly as in the original
// log, so the benchmark relations still match. ROBOTLASER1 rather than RAWLASER1 because the
// reader takes a ROBOTLASER1 scan's odometry from the line itself: with RAWLASER1 it would
// interpolate the ODOM lines at the repaired time, and on intel the timestamp repair
// (io/timestamp_repair.hpp) sometimes gives an ODOM line and the scan of the same printed time
// different repaired times, moving ~1 % of the scans by up to 5 cm. Read back, every scan has
// exactly the piece's odometry, to the printed precision (1e-6 m, 1e-6 rad).
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::multi_robot {

/// Writes `frames` (one piece, file order) to `path` through a temporary file; `comment` (may
/// hold several lines) goes into the header. RuntimeError if the file cannot be written.
Status WritePieceLog(const std::string& path, const std::vector<Frame>& frames,
                     const std::string& comment);

}  // namespace gridslam::multi_robot
