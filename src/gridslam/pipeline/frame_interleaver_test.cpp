#include "gridslam/pipeline/frame_interleaver.hpp"

#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::pipeline {
namespace {

Frame At(double seconds) {
  Frame frame;
  frame.time = FromSeconds(seconds);
  frame.corrected_time = frame.time;
  return frame;
}

TEST(InterleaveFrames, DeliversByCorrectedTimeLowerRobotFirstOnTies) {
  const std::vector<Frame> a = {At(0.0), At(2.0), At(3.0)};
  const std::vector<Frame> b = {At(1.0), At(2.0), At(5.0)};
  std::vector<std::pair<int, double>> order;
  ASSERT_TRUE(InterleaveFrames({FramesOf(a), FramesOf(b)}, [&](int robot, const Frame& frame) {
                order.emplace_back(robot, ToSeconds(frame.time));
              }).ok());
  const std::vector<std::pair<int, double>> expected = {{0, 0.0}, {1, 1.0}, {0, 2.0},
                                                        {1, 2.0}, {0, 3.0}, {1, 5.0}};
  EXPECT_EQ(order, expected);
}

TEST(InterleaveFrames, StopsAtTheFirstError) {
  const std::vector<Frame> a = {At(0.0), At(2.0)};
  int calls = 0;
  FrameSource failing = [&calls]() -> Result<std::optional<Frame>> {
    if (calls++ == 0) {
      return std::optional<Frame>(At(1.0));
    }
    return InvalidInput("bad line", "b.clf", 7);
  };
  std::vector<double> delivered;
  const Status s = InterleaveFrames({FramesOf(a), failing}, [&](int, const Frame& frame) {
    delivered.push_back(ToSeconds(frame.time));
  });
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().line, 7);
  EXPECT_EQ(delivered, (std::vector<double>{0.0, 1.0}));
}

}  // namespace
}  // namespace gridslam::pipeline
