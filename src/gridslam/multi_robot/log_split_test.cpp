#include "gridslam/multi_robot/log_split.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/multi_robot/piece_log.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::multi_robot {
namespace {

/// A log of `n` scans 0.2 s apart (a few out of order, as in intel) driving a curve.
std::vector<Frame> MakeLog(int n) {
  std::vector<Frame> frames;
  Pose2 odom(3.0, -2.0, 0.4);
  const Time start = *ParseSeconds("976052857.337530");
  for (int k = 0; k < n; ++k) {
    Frame frame;
    // Every 7th scan is stamped 0.3 s late (printed time out of file order).
    const int late = k % 7 == 3 ? 300 : 0;
    frame.time = start + std::chrono::milliseconds(200 * k + late) + std::chrono::microseconds(17);
    frame.corrected_time = frame.time;
    frame.T_odom_base = odom;
    frame.T_base_laser = Pose2(0.1, 0.0, 0.0);
    frame.scan.angle_min = -1.570796;
    frame.scan.angle_increment = 0.017453;
    frame.scan.range_max = 30.0;
    for (int b = 0; b < 181; ++b) {
      frame.scan.ranges.push_back(
          static_cast<float>(std::round(100.0 * (2.0 + std::sin(0.1 * b + 0.01 * k))) / 100.0));
    }
    frames.push_back(frame);
    odom = odom * Pose2(0.1, 0.0, 0.02 * std::sin(0.05 * k));
  }
  return frames;
}

TEST(LogSplit, PiecesPartitionTheLogByScans) {
  const std::vector<Frame> frames = MakeLog(100);
  auto plan = PlanSplit(frames, 3, 7, SplitOptions{});
  ASSERT_TRUE(plan.ok()) << plan.error().ToString();
  const auto& pieces = plan.value().pieces;
  ASSERT_EQ(pieces.size(), 3U);
  EXPECT_EQ(pieces[0].core_begin, 0U);
  EXPECT_EQ(pieces[2].core_end, 100U);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    EXPECT_EQ(pieces[i].begin, pieces[i].core_begin);  // no overlap
    EXPECT_EQ(pieces[i].end, pieces[i].core_end);
    EXPECT_NEAR(static_cast<double>(pieces[i].core_end - pieces[i].core_begin), 100.0 / 3.0, 1.0);
    if (i > 0) {
      EXPECT_EQ(pieces[i].core_begin, pieces[i - 1].core_end);
    }
    for (std::size_t k = pieces[i].core_begin; k < pieces[i].core_end; ++k) {
      EXPECT_EQ(plan.value().home[k], static_cast<int>(i));
    }
    // The piece's first odometry pose is its random start.
    const std::vector<Frame> piece = PieceFrames(frames, pieces[i]);
    EXPECT_TRUE(
        IsApprox(piece.front().T_odom_base, RandomStart(7, static_cast<int>(i), 50.0), 1e-9, 1e-9));
  }
}

TEST(LogSplit, OverlapReachesBackIntoThePreviousPiece) {
  const std::vector<Frame> frames = MakeLog(100);
  SplitOptions options;
  options.overlap = 2.0;  // ten scans at 0.2 s
  auto plan = PlanSplit(frames, 2, 1, options);
  ASSERT_TRUE(plan.ok());
  const SplitPiece& second = plan.value().pieces[1];
  EXPECT_EQ(second.core_begin, 50U);
  EXPECT_LT(second.begin, 50U);
  EXPECT_GE(second.begin, 39U);
  for (std::size_t k = second.begin; k < second.core_begin; ++k) {
    EXPECT_LE(ToSeconds(frames[second.core_begin].corrected_time - frames[k].corrected_time), 2.0);
    EXPECT_EQ(plan.value().home[k], 0);  // the overlap's scans stay at home in piece 0
  }
  EXPECT_GT(
      ToSeconds(frames[second.core_begin].corrected_time - frames[second.begin - 1].corrected_time),
      2.0);
  EXPECT_EQ(plan.value().pieces[0].begin, 0U);
  EXPECT_EQ(plan.value().pieces[0].end, 50U);
}

TEST(LogSplit, ByTimeGivesEqualDurations) {
  std::vector<Frame> frames = MakeLog(120);
  for (std::size_t k = 60; k < frames.size(); ++k) {  // a denser second half
    frames[k].corrected_time = frames[60].corrected_time +
                               Duration((frames[k].corrected_time - frames[60].corrected_time) / 4);
  }
  SplitOptions options;
  options.by = "time";
  auto plan = PlanSplit(frames, 2, 1, options);
  ASSERT_TRUE(plan.ok());
  // Scans 0..59 span 12 s, 60..119 span 3 s: the half-time point lies at scan ~38.
  EXPECT_NEAR(static_cast<double>(plan.value().pieces[1].core_begin), 38.0, 2.0);
}

TEST(LogSplit, BadRequestsAreInvalidInput) {
  const std::vector<Frame> frames = MakeLog(30);
  EXPECT_FALSE(PlanSplit(frames, 0, 1, SplitOptions{}).ok());
  EXPECT_FALSE(PlanSplit(frames, 4, 1, SplitOptions{}).ok());  // 7 scans < min_scans
  SplitOptions bad;
  bad.by = "distance";
  EXPECT_FALSE(PlanSplit(frames, 2, 1, bad).ok());
  bad = SplitOptions{};
  bad.overlap = -1.0;
  EXPECT_FALSE(PlanSplit(frames, 2, 1, bad).ok());
  const auto result = PlanSplit(frames, 4, 1, SplitOptions{});
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidInput);
}

TEST(LogSplit, StartsAreDeterministicAndCoverAllRotations) {
  EXPECT_TRUE(IsApprox(RandomStart(3, 1, 50.0), RandomStart(3, 1, 50.0)));
  EXPECT_FALSE(IsApprox(RandomStart(3, 1, 50.0), RandomStart(4, 1, 50.0), 1e-3, 1e-3));
  EXPECT_FALSE(IsApprox(RandomStart(3, 1, 50.0), RandomStart(3, 2, 50.0), 1e-3, 1e-3));
  int quadrants[4] = {0, 0, 0, 0};
  double largest = 0.0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const Pose2 p = RandomStart(seed, 0, 50.0);
    EXPECT_LE(std::abs(p.x()), 50.0);
    EXPECT_LE(std::abs(p.y()), 50.0);
    largest = std::max(largest, p.translation().norm());
    ++quadrants[static_cast<int>((p.theta() + std::numbers::pi) / (std::numbers::pi / 2.0)) % 4];
  }
  EXPECT_GT(largest, 30.0);  // tens of metres
  for (const int count : quadrants) {
    EXPECT_GT(count, 25);
  }
}

// Pieces written as logs, read back, concatenated and transformed back equal the original.
TEST(LogSplit, WrittenPiecesReadBackAsTheOriginalOdometry) {
  const std::vector<Frame> frames = MakeLog(90);
  SplitOptions options;
  options.overlap = 1.0;
  auto plan = PlanSplit(frames, 3, 11, options);
  ASSERT_TRUE(plan.ok());
  const auto dir = testing::MakeTempDir("log_split");
  std::vector<Frame> joined;
  for (std::size_t i = 0; i < 3; ++i) {
    const SplitPiece& piece = plan.value().pieces[i];
    const std::string path = (dir / ("robot_" + std::to_string(i) + ".clf")).string();
    ASSERT_TRUE(WritePieceLog(path, PieceFrames(frames, piece), "test\npiece").ok());
    auto read = io::ReadCarmenLog(path, io::CarmenOptions{});
    ASSERT_TRUE(read.ok()) << read.error().ToString();
    ASSERT_EQ(read.value().size(), piece.end - piece.begin);
    // The first odometry pose is the random start, far from the original.
    EXPECT_TRUE(IsApprox(read.value().front().T_odom_base,
                         RandomStart(11, static_cast<int>(i), 50.0), 2e-6, 2e-6));
    for (std::size_t k = piece.core_begin - piece.begin; k < read.value().size(); ++k) {
      Frame f = read.value()[k];
      f.T_odom_base = piece.T_new_old.Inverse() * f.T_odom_base;
      joined.push_back(f);
    }
  }
  ASSERT_EQ(joined.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_EQ(joined[k].time, frames[k].time) << k;
    EXPECT_TRUE(IsApprox(joined[k].T_odom_base, frames[k].T_odom_base, 1e-5, 1e-5))
        << k << ": " << joined[k].T_odom_base.ToVector().transpose() << " vs "
        << frames[k].T_odom_base.ToVector().transpose();
    EXPECT_TRUE(IsApprox(joined[k].T_base_laser, frames[k].T_base_laser, 1e-6, 1e-6));
    EXPECT_EQ(joined[k].scan.ranges, frames[k].scan.ranges);
    EXPECT_NEAR(joined[k].scan.angle_min, frames[k].scan.angle_min, 1e-9);
    EXPECT_NEAR(joined[k].scan.angle_increment, frames[k].scan.angle_increment, 1e-9);
  }
}

}  // namespace
}  // namespace gridslam::multi_robot
