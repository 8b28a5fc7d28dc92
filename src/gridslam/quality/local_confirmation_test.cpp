#include "gridslam/quality/local_confirmation.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <gtest/gtest.h>

#include "gridslam/grid/scan_points.hpp"
#include "gridslam/quality/self_check_room_testing.hpp"

namespace gridslam::quality {
namespace {

using testing::MakeRun;
using testing::SimRun;

SelfCheckOptions EveryScan() {
  SelfCheckOptions options;
  options.min_motion = 0.0;  // replay every scan
  return options;
}

// Confirmed returns and all returns of LocalConfirmation's flags.
std::pair<long, long> Counts(const std::vector<std::vector<std::uint8_t>>& flags) {
  long confirmed = 0;
  long returns = 0;
  for (const auto& f : flags) {
    confirmed += std::count(f.begin(), f.end(), std::uint8_t{1});
    returns += static_cast<long>(f.size());
  }
  return {confirmed, returns};
}

// The scan's beams straight ahead (index 180 of 360, angle 0) end on a passer-by 1 m ahead.
void AddPasserBy(LaserScan& scan) {
  for (std::size_t k = 178; k <= 182; ++k) {
    scan.ranges[k] = 1.0F;
  }
}

TEST(ReplayedScans, KeepsOneScanPerMinMotionAndSkipsMissingScans) {
  SimRun run = MakeRun(0.0, 0.0);  // poses 0.25 m apart, 41 per leg
  run.posed[1].scan = nullptr;
  SelfCheckOptions options;
  options.min_motion = 0.5;
  options.min_rotation = 10.0;
  const std::vector<std::size_t> replayed = ReplayedScans(run.posed, options);
  ASSERT_GE(replayed.size(), 3U);
  EXPECT_EQ(replayed[0], 0U);
  EXPECT_EQ(replayed[1], 2U);
  EXPECT_EQ(replayed[2], 4U);
  EXPECT_EQ(ReplayedScans(run.posed, EveryScan()).size(), run.posed.size() - 1);
}

TEST(LocalConfirmation, OneFlagPerReturnOfEveryReplayedScan) {
  SimRun run = MakeRun(0.0, 0.0);
  run.posed[3].scan = nullptr;
  const SelfCheckOptions options = EveryScan();
  const auto flags = LocalConfirmation(run.posed, fusion::FusionOptions{}, options);
  ASSERT_EQ(flags.size(), run.posed.size());
  EXPECT_TRUE(flags[3].empty());
  for (std::size_t s = 0; s < run.posed.size(); ++s) {
    if (s == 3) continue;
    const ScanReturns r = ExtractScanReturns(run.scans[s], Pose2(), options.max_range);
    ASSERT_EQ(flags[s].size(), r.points.size()) << "scan " << s;
  }
  const auto [confirmed, returns] = Counts(flags);
  // The walls of a static room, seen along one leg at a time: nearly every return confirmed.
  EXPECT_GT(static_cast<double>(confirmed) / static_cast<double>(returns), 0.97);
}

TEST(LocalConfirmation, APasserByIsNotConfirmedByTheScansAroundIt) {
  SimRun run = MakeRun(0.0, 0.0);
  AddPasserBy(run.scans[8]);  // seen once; the scans before look through the spot
  const auto flags = LocalConfirmation(run.posed, fusion::FusionOptions{}, EveryScan());
  const ScanReturns r = ExtractScanReturns(run.scans[8], Pose2(), 30.0);
  int passer_by = 0;
  int confirmed = 0;
  for (std::size_t p = 0; p < r.points.size(); ++p) {
    if (std::abs(r.points[p].norm() - 1.0) < 1e-6) {
      ++passer_by;
      confirmed += flags[8][p];
    }
  }
  EXPECT_EQ(passer_by, 5);
  EXPECT_EQ(confirmed, 0);
}

TEST(LocalConfirmation, AMisalignedLegIsConfirmedByItsOwnStretch) {
  // The way back is off by 0.5 m; each leg is one stretch of 10 m, so each leg's walls confirm
  // its own returns: what the final map then contradicts is the misalignment.
  const SimRun run = MakeRun(0.0, 0.5);
  const auto [confirmed, returns] =
      Counts(LocalConfirmation(run.posed, fusion::FusionOptions{}, EveryScan()));
  EXPECT_GT(static_cast<double>(confirmed) / static_cast<double>(returns), 0.97);
  // One stretch over both legs would see the double walls itself.
  SelfCheckOptions whole = EveryScan();
  whole.local_travel = 1000.0;
  const long whole_confirmed =
      Counts(LocalConfirmation(run.posed, fusion::FusionOptions{}, whole)).first;
  EXPECT_LT(whole_confirmed, confirmed);
}

TEST(LocalConfirmation, AStretchTooLargeToFuseConfirmsEveryReturn) {
  // Two returns 900 m away at right angles, at a 5 mm resolution: 1.6e10 cells, more than a map
  // may hold.
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = 1.5707963267948966;
  scan.range_min = 0.1;
  scan.range_max = 1000.0;
  scan.ranges = {900.0F, 900.0F};
  const std::vector<fusion::PosedScan> posed = {{Pose2(), Pose2(), &scan}};
  fusion::FusionOptions fusion;
  fusion.resolution = 0.005;
  fusion.max_range = 1000.0;
  SelfCheckOptions options = EveryScan();
  options.max_range = 1000.0;
  ASSERT_THROW((void)fusion::FuseScans(posed, fusion), std::length_error);
  std::vector<std::vector<std::uint8_t>> flags;
  ASSERT_NO_THROW(flags = LocalConfirmation(posed, fusion, options));
  ASSERT_EQ(flags.size(), 1U);
  EXPECT_EQ(flags[0], std::vector<std::uint8_t>({1, 1}));
}

TEST(LocalConfirmation, TheSameFlagsWhateverTheThreads) {
  SimRun run = MakeRun(0.0, 0.3);
  AddPasserBy(run.scans[8]);
  SelfCheckOptions options = EveryScan();
  options.local_travel = 3.0;  // several stretches
  const auto one = LocalConfirmation(run.posed, fusion::FusionOptions{}, options, 1);
  const auto three = LocalConfirmation(run.posed, fusion::FusionOptions{}, options, 3);
  EXPECT_EQ(one, three);
}

}  // namespace
}  // namespace gridslam::quality
