#include "gridslam/pipeline/frame_interleaver.hpp"

namespace gridslam::pipeline {

FrameSource FramesOf(const std::vector<Frame>& frames) {
  return [&frames, next = std::size_t{0}]() mutable -> Result<std::optional<Frame>> {
    if (next >= frames.size()) {
      return std::optional<Frame>();
    }
    return std::optional<Frame>(frames[next++]);
  };
}

Status InterleaveFrames(std::vector<FrameSource> sources,
                        const std::function<void(int robot, const Frame& frame)>& deliver) {
  std::vector<std::optional<Frame>> next(sources.size());
  const auto advance = [&](std::size_t r) -> Status {
    Result<std::optional<Frame>> frame = sources[r]();
    if (!frame.ok()) {
      return frame.error();
    }
    next[r] = std::move(frame).value();
    return Status::Ok();
  };
  for (std::size_t r = 0; r < sources.size(); ++r) {
    GRIDSLAM_RETURN_IF_ERROR(advance(r));
  }
  while (true) {
    std::optional<std::size_t> robot;
    for (std::size_t r = 0; r < next.size(); ++r) {
      if (next[r].has_value() &&
          (!robot || next[r]->corrected_time < next[*robot]->corrected_time)) {
        robot = r;
      }
    }
    if (!robot) {
      return Status::Ok();
    }
    deliver(static_cast<int>(*robot), *next[*robot]);
    GRIDSLAM_RETURN_IF_ERROR(advance(*robot));
  }
}

}  // namespace gridslam::pipeline
