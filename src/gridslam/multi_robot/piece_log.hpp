// Writing one piece of a split log as a robot's CARMEN log (issue 8; FORMATS.md §1): a comment
// saying where it came from, the laser-offset PARAMs, then for every scan an ODOM line with the
// piece's odometry at the scan and the scan as RAWLASER1 (with its beam geometry), both with the
// scan's printed timestamp, exactly as in the original log, so the benchmark relations still
// match. This is the layout of the project's fr-clinic log and of `gridslam simulate`; reading
// it back (io::CarmenReader) gives every scan exactly this odometry, to the printed precision
// (1e-6 m, 1e-6 rad), even with intel's unpadded timestamps, since ODOM and laser lines share
// each printed time.
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
