// Relations files of the SLAM benchmark (Kümmerle et al. 2009; docs/formats.md §4): one relation
// per line, "t1 t2 x y z roll pitch yaw", the motion from the robot's pose at t1 to its pose at t2
// expressed in the frame at t1 (z, roll, pitch are 0 in 2D and ignored on reading). Lines
// starting with '#' and blank lines are skipped.
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/eval/relation.hpp"

namespace gridslam::io {

/// Reads a relations file; a malformed line is an error naming file, line and field.
Result<std::vector<eval::Relation>> ReadRelations(const std::string& path);

/// Writes relations (timestamps with 6 decimals, poses at full precision) via a temporary file.
Status WriteRelations(const std::string& path, const std::vector<eval::Relation>& relations);

}  // namespace gridslam::io
