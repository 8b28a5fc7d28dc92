// Several robots' frames delivered as a team would deliver them: interleaved by corrected time
// (Frame::corrected_time, the repaired time used for ordering), each robot's frames in its log
// order; on equal times the lower robot first. Used by `gridslam map` (CARMEN readers) and the
// multi-robot tests (frames in memory), so both feed the Mapper the same way.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::pipeline {

/// One robot's frames in log order: the next one, nullopt at the end, or an error.
using FrameSource = std::function<Result<std::optional<Frame>>()>;

/// The frames of `frames` in order (borrowed: must outlive the source).
FrameSource FramesOf(const std::vector<Frame>& frames);

/// Reads the first frame of every source, then repeatedly calls `deliver(robot, frame)` with
/// the earliest pending frame and reads that robot's next one, until all sources are done.
/// Returns the first error of a source (frames delivered before it stay delivered).
Status InterleaveFrames(std::vector<FrameSource> sources,
                        const std::function<void(int robot, const Frame& frame)>& deliver);

}  // namespace gridslam::pipeline
