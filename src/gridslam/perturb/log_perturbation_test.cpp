#include "gridslam/perturb/log_perturbation.hpp"

#include <gtest/gtest.h>

namespace gridslam::perturb {
namespace {

std::vector<Frame> MakeLog(int n) {  // 10 Hz, 1 m/s along x, 5 beams at 3 m
  std::vector<Frame> frames(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    Frame& f = frames[static_cast<std::size_t>(k)];
    f.time = FromSeconds(500.0 + 0.1 * k);
    f.corrected_time = f.time;
    f.T_odom_base = Pose2(0.1 * k, 0.0, 0.0);
    f.scan.angle_min = -0.2;
    f.scan.angle_increment = 0.1;
    f.scan.range_max = 30.0;
    f.scan.ranges = {3.0F, 3.0F, 3.0F, 3.0F, 3.0F};
  }
  return frames;
}

TEST(LogPerturbation, DefaultOptionsCopyTheLog) {
  const auto frames = MakeLog(30);
  auto out = PerturbLog(frames, {});
  ASSERT_TRUE(out.ok());
  ASSERT_EQ(out.value().frames.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_EQ(out.value().frames[k].time, frames[k].time);
    EXPECT_TRUE(IsApprox(out.value().frames[k].T_odom_base, frames[k].T_odom_base));
    EXPECT_EQ(out.value().frames[k].scan.ranges, frames[k].scan.ranges);
    EXPECT_TRUE(out.value().frames[k].has_odometry);
  }
}

TEST(LogPerturbation, CutAndKeepEveryKeepThePrintedTimestamps) {
  const auto frames = MakeLog(100);  // 0 .. 9.9 s
  PerturbOptions options;
  options.start = 2.0;
  options.duration = 5.0;  // 2.0 .. 7.0 s: scans 20 .. 70
  options.keep_every = 3;
  auto out = PerturbLog(frames, options);
  ASSERT_TRUE(out.ok());
  const auto& kept = out.value().frames;
  ASSERT_EQ(kept.size(), 17U);  // 20, 23, ..., 68
  for (std::size_t j = 0; j < kept.size(); ++j) {
    EXPECT_EQ(kept[j].time, frames[20 + 3 * j].time);
  }
  EXPECT_EQ(out.value().cut, 49);
  EXPECT_EQ(out.value().decimated, 34);
}

TEST(LogPerturbation, EmptyCutIsAnError) {
  PerturbOptions options;
  options.start = 100.0;
  EXPECT_FALSE(PerturbLog(MakeLog(10), options).ok());
  options = {};
  options.keep_every = 0;
  EXPECT_FALSE(PerturbLog(MakeLog(10), options).ok());
}

TEST(LogPerturbation, GlitchesDoNotDependOnKeepEvery) {
  const auto frames = MakeLog(3000);
  PerturbOptions options;
  options.glitch_period = 20.0;
  auto all = PerturbLog(frames, options);
  options.keep_every = 3;
  auto some = PerturbLog(frames, options);
  ASSERT_TRUE(all.ok() && some.ok());
  ASSERT_FALSE(all.value().glitches.empty());
  ASSERT_EQ(all.value().glitches.size(), some.value().glitches.size());
  // The kept scans have the same (glitched) odometry as in the full variant.
  for (std::size_t j = 0; j < some.value().frames.size(); ++j) {
    EXPECT_TRUE(IsApprox(some.value().frames[j].T_odom_base, all.value().frames[3 * j].T_odom_base,
                         1e-9, 1e-9));
  }
}

TEST(LogPerturbation, RemovedOdometryIsMarked) {
  PerturbOptions options;
  options.remove_odometry = true;
  auto out = PerturbLog(MakeLog(10), options);
  ASSERT_TRUE(out.ok());
  for (const Frame& f : out.value().frames) {
    EXPECT_FALSE(f.has_odometry);
    EXPECT_TRUE(IsApprox(f.T_odom_base, Pose2::Identity()));
  }
}

}  // namespace
}  // namespace gridslam::perturb
