#include "gridslam/scan_matching/laser_noise_monitor.hpp"

#include <gtest/gtest.h>

namespace gridslam::scan_matching {
namespace {

TEST(LaserNoiseMonitor, NeedsTenScansBeforeItJudges) {
  LaserNoiseMonitor monitor(101);
  for (std::size_t i = 0; i + 1 < LaserNoiseMonitor::kMinScans; ++i) {
    monitor.Add(0.05);
  }
  EXPECT_EQ(monitor.Median(), 0.0);
  EXPECT_FALSE(monitor.Above(0.01));
  monitor.Add(0.05);
  EXPECT_DOUBLE_EQ(monitor.Median(), 0.05);
  EXPECT_TRUE(monitor.Above(0.01));
}

TEST(LaserNoiseMonitor, OneNoisyScanInAQuietRunDoesNotSwitchIt) {
  LaserNoiseMonitor monitor(11);
  for (int i = 0; i < 30; ++i) {
    monitor.Add(i % 4 == 0 ? 0.2 : 0.004);  // a sparse or cluttered scan now and then
  }
  EXPECT_DOUBLE_EQ(monitor.Median(), 0.004);
  EXPECT_FALSE(monitor.Above(0.0144));
}

TEST(LaserNoiseMonitor, FollowsTheRecentScansAndIgnoresScansWithoutAWindow) {
  LaserNoiseMonitor monitor(11);
  for (int i = 0; i < 20; ++i) {
    monitor.Add(0.004);
  }
  for (int i = 0; i < 20; ++i) {
    monitor.Add(0.0);  // no five-beam window: no measurement
    monitor.Add(-1.0);
  }
  EXPECT_DOUBLE_EQ(monitor.Median(), 0.004);
  for (int i = 0; i < 6; ++i) {
    monitor.Add(0.03);  // a majority of the last 11
  }
  EXPECT_DOUBLE_EQ(monitor.Median(), 0.03);
}

}  // namespace
}  // namespace gridslam::scan_matching
