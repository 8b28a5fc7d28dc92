#include "gridslam/io/carmen_reader.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>
#include <zlib.h>

#include "gridslam/io/internal/carmen_line.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

using testing::FixtureDir;

std::vector<Frame> ReadFixture(const std::string& name, CarmenStats* stats = nullptr,
                               CarmenOptions options = {}) {
  auto frames = ReadCarmenLog((FixtureDir() / name).string(), options, stats);
  EXPECT_TRUE(frames.ok()) << (frames.ok() ? "" : frames.error().ToString());
  return frames.ok() ? frames.value() : std::vector<Frame>{};
}

TEST(CarmenReader, InterpolatesOdometryAtPoselessScans) {
  CarmenStats stats;
  const auto frames = ReadFixture("carmen_interpolation.clf", &stats);
  ASSERT_EQ(frames.size(), 4U);
  EXPECT_EQ(stats.scans, 4);
  EXPECT_EQ(stats.odometry, 3);
  // Before the first ODOM line and after the last: clamped and counted.
  EXPECT_EQ(stats.scans_without_odometry, 2);
  EXPECT_TRUE(IsApprox(frames[0].T_odom_base, Pose2(0.0, 0.0, 3.041593)));
  EXPECT_TRUE(IsApprox(frames[3].T_odom_base, Pose2(2.0, 2.0, -3.041593)));
  // alpha = 0.25 between (0, 0, 3.041593) and (1, 2, -3.041593): the short way across pi.
  EXPECT_NEAR(frames[1].T_odom_base.x(), 0.25, 1e-9);
  EXPECT_NEAR(frames[1].T_odom_base.y(), 0.5, 1e-9);
  EXPECT_NEAR(NormalizeAngle(frames[1].T_odom_base.theta() - 3.091593), 0.0, 1e-6);
  // Exactly at an ODOM timestamp: that line's pose.
  EXPECT_TRUE(IsApprox(frames[2].T_odom_base, Pose2(1.0, 2.0, -3.041593)));
  EXPECT_EQ(frames[1].time, *ParseSeconds("100.25"));
  EXPECT_EQ(frames[1].source_line, 5);
  EXPECT_TRUE(IsApprox(frames[1].T_base_laser, Pose2::Identity()));
}

TEST(CarmenReader, NoReturnsStayInRangesButAreNotHits) {
  const auto frames = ReadFixture("carmen_interpolation.clf");
  ASSERT_EQ(frames.size(), 4U);
  const LaserScan& scan = frames[1].scan;
  ASSERT_EQ(scan.size(), 5U);
  EXPECT_FLOAT_EQ(scan.ranges[2], 81.83f);  // raw value kept for free-space clearing
  EXPECT_TRUE(scan.IsHit(0));
  EXPECT_TRUE(scan.IsHit(1));
  EXPECT_FALSE(scan.IsHit(2));  // sentinel 81.83
  EXPECT_FALSE(scan.IsHit(3));  // sentinel 81.91
  EXPECT_FALSE(scan.IsHit(4));  // 0 m
  EXPECT_NEAR(scan.angle_min, -std::numbers::pi / 2, 1e-6);
  EXPECT_NEAR(scan.angle_increment, std::numbers::pi / 4, 1e-6);
}

TEST(CarmenReader, FlaserGeometryGuessAndParamOffset) {
  CarmenStats stats;
  const auto frames = ReadFixture("carmen_flaser_param.clf", &stats);
  ASSERT_EQ(frames.size(), 8U);
  EXPECT_EQ(stats.params, 2);
  // FLASER: robot pose from the odom fields; mounting from PARAM robot_frontlaser_offset.
  EXPECT_TRUE(IsApprox(frames[0].T_odom_base, Pose2(1.0, 2.0, 0.5)));
  EXPECT_TRUE(IsApprox(frames[0].T_base_laser, Pose2(-0.04, 0.0, 0.0)));
  EXPECT_NEAR((frames[0].T_odom_laser().translation() - Eigen::Vector2d(0.9649, 1.980821)).norm(),
              0.0, 1e-5);
  ASSERT_TRUE(frames[0].T_world_base_true.has_value());
  EXPECT_TRUE(IsApprox(*frames[0].T_world_base_true, Pose2(5.0, 6.0, 0.1)));
  // RLASER without a rear PARAM: mounting from its two poses.
  EXPECT_TRUE(IsApprox(frames[1].T_base_laser, Pose2(0.0, 0.0, 1.0), 1e-9, 1e-9));
  const struct {
    std::size_t beams;
    double step_deg;
  } expected[] = {{180, 1.0}, {181, 1.0}, {360, 0.5}, {361, 0.5}, {400, 0.25}, {100, 180.0 / 99}};
  for (std::size_t i = 0; i < 6; ++i) {
    const LaserScan& s = frames[2 + i].scan;
    EXPECT_EQ(s.size(), expected[i].beams);
    EXPECT_NEAR(s.angle_min, -std::numbers::pi / 2, 1e-12);
    EXPECT_NEAR(RadToDeg(s.angle_increment), expected[i].step_deg, 1e-9);
    EXPECT_NEAR(s.range_max, 80.0, 1e-12);
  }
  // Last beam of a 180-beam FLASER at +89 degrees, of a 181-beam one at +90.
  EXPECT_NEAR(RadToDeg(frames[2].scan.Angle(179)), 89.0, 1e-9);
  EXPECT_NEAR(RadToDeg(frames[3].scan.Angle(180)), 90.0, 1e-9);
}

TEST(CarmenReader, GuessesMatchCarmen) {
  using internal::GuessLaserFov;
  EXPECT_NEAR(RadToDeg(GuessLaserFov(180)), 179.0, 1e-9);
  EXPECT_NEAR(RadToDeg(GuessLaserFov(181)), 180.0, 1e-9);
  EXPECT_NEAR(RadToDeg(GuessLaserFov(360)), 179.5, 1e-9);
  EXPECT_NEAR(RadToDeg(GuessLaserFov(401)), 100.0, 1e-9);
  EXPECT_NEAR(GuessLaserFov(400), std::numbers::pi / 100.0 * 99.75, 1e-12);  // CARMEN's formula
  EXPECT_NEAR(RadToDeg(GuessLaserFov(7)), 180.0, 1e-9);
}

TEST(CarmenReader, OptionsOverrideGeometryAndMounting) {
  CarmenOptions options;
  options.laser_offset = {0.22, 0.0, 0.0};
  options.flaser_angle_min = -1.0;
  options.flaser_angle_increment = 0.01;
  const auto frames = ReadFixture("carmen_flaser_param.clf", nullptr, options);
  ASSERT_FALSE(frames.empty());
  EXPECT_TRUE(IsApprox(frames[0].T_base_laser, Pose2(0.22, 0.0, 0.0)));
  EXPECT_DOUBLE_EQ(frames[0].scan.angle_min, -1.0);
  EXPECT_DOUBLE_EQ(frames[0].scan.angle_increment, 0.01);
}

TEST(CarmenReader, RobotLaserAndInterleavedPhases) {
  const auto frames = ReadFixture("carmen_robotlaser_interleaved.clf");
  ASSERT_EQ(frames.size(), 4U);
  // ROBOTLASER1: poses from the line, mounting = robot^-1 * laser.
  EXPECT_TRUE(IsApprox(frames[0].T_odom_base, Pose2(1.0, 2.0, 0.0)));
  EXPECT_TRUE(IsApprox(frames[0].T_base_laser, Pose2(0.22, 0.0, 0.0), 1e-9));
  EXPECT_EQ(frames[0].scan.size(), 5U);
  // Each RAWLASER1 line keeps its own start angle and beam count.
  EXPECT_EQ(frames[1].scan.size(), 5U);
  EXPECT_EQ(frames[2].scan.size(), 4U);
  EXPECT_EQ(frames[3].scan.size(), 3U);
  EXPECT_NEAR(RadToDeg(frames[1].scan.angle_min), -90.0, 1e-4);
  EXPECT_NEAR(RadToDeg(frames[2].scan.angle_min), -89.75, 1e-4);
  EXPECT_NEAR(RadToDeg(frames[3].scan.angle_min), -89.5, 1e-4);
  // No-returns: sentinels, NaN, <= 0, and readings beyond the usable range (80 m).
  const LaserScan& a = frames[1].scan;
  EXPECT_TRUE(a.IsHit(0));
  EXPECT_FALSE(a.IsHit(1));
  EXPECT_FALSE(a.IsHit(2));
  EXPECT_TRUE(std::isnan(a.ranges[3]));
  EXPECT_FALSE(a.IsHit(3));
  EXPECT_FALSE(a.IsHit(4));
  const LaserScan& b = frames[2].scan;
  EXPECT_FALSE(b.IsHit(0));  // -1
  EXPECT_FALSE(b.IsHit(1));  // 81.82 >= 80
  EXPECT_TRUE(b.IsHit(2));   // 79.99
  EXPECT_FALSE(b.IsHit(3));  // 80.50
  // Odometry interpolated between ODOM 20.15 (x 0) and 20.55 (x 1).
  EXPECT_NEAR(frames[1].T_odom_base.x(), 0.125, 1e-9);
  EXPECT_NEAR(frames[3].T_odom_base.x(), 0.625, 1e-9);
}

TEST(CarmenReader, SentinelBelowUsableRangeLowersRangeMax) {
  CarmenOptions options;
  options.max_usable_range = 100.0;
  const auto frames = ReadFixture("carmen_robotlaser_interleaved.clf", nullptr, options);
  ASSERT_EQ(frames.size(), 4U);
  EXPECT_NEAR(frames[1].scan.range_max, 81.825, 1e-9);
  EXPECT_FALSE(frames[1].scan.IsHit(1));  // 81.83 is a sentinel
  EXPECT_TRUE(frames[2].scan.IsHit(1));   // 81.82 is a real reading
}

TEST(CarmenReader, RepairsUnpaddedMicrosecondsButKeepsPrintedTimes) {
  CarmenStats stats;
  const auto frames = ReadFixture("carmen_unpadded.clf", &stats);
  ASSERT_EQ(frames.size(), 28U);
  EXPECT_GT(stats.repaired_timestamps, 0);
  for (std::size_t i = 0; i + 1 < frames.size(); ++i) {  // the last scan is after the last ODOM
    // ODOM x = true time - 50, so the interpolated x shows which time was used.
    const Frame& f = frames[i];
    EXPECT_NEAR(f.T_odom_base.x(), ToSeconds(f.corrected_time) - 50.0, 1e-6)
        << FormatSeconds(f.time);
  }
  const Frame& f = frames[9];  // true 51.0623, printed 51.623000
  EXPECT_EQ(FormatSeconds(f.time), "51.623000");
  EXPECT_EQ(FormatSeconds(f.corrected_time), "51.062300");
  EXPECT_NEAR(f.T_odom_base.x(), 1.0623, 1e-6);

  CarmenOptions no_repair;
  no_repair.repair_timestamps = false;
  const auto raw = ReadFixture("carmen_unpadded.clf", nullptr, no_repair);
  ASSERT_EQ(raw.size(), 28U);
  EXPECT_EQ(raw[9].corrected_time, raw[9].time);
  EXPECT_GT(std::abs(raw[9].T_odom_base.x() - 1.0623), 0.2);
}

TEST(CarmenReader, InterleavedOutOfTimeOrderUsesTimeSortedOdometry) {
  CarmenStats stats;
  const auto frames = ReadFixture("carmen_out_of_order.clf", &stats);
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_EQ(stats.repaired_timestamps, 0);
  EXPECT_NEAR(frames[0].T_odom_base.x(), 0.35, 1e-9);
  EXPECT_NEAR(frames[1].T_odom_base.x(), 0.45, 1e-9);
}

TEST(CarmenReader, MalformedLineNamesFileLineAndField) {
  const std::string path = (FixtureDir() / "carmen_bad_input.clf").string();
  auto frames = ReadCarmenLog(path, CarmenOptions{});
  ASSERT_FALSE(frames.ok());
  const Error& e = frames.error();
  EXPECT_EQ(e.code, ErrorCode::kInvalidInput);
  EXPECT_EQ(e.file, path);
  EXPECT_EQ(e.line, 9);
  EXPECT_NE(e.message.find("RAWLASER1"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("range[1]"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("abc"), std::string::npos) << e.message;
}

TEST(CarmenReader, LenientSkipsAndCounts) {
  CarmenOptions options;
  options.lenient = true;
  CarmenStats stats;
  const auto frames = ReadFixture("carmen_bad_input.clf", &stats, options);
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_EQ(stats.skipped_malformed, 1);
  EXPECT_EQ(stats.skipped_unknown, 3);
  EXPECT_EQ(stats.unknown_types, (std::set<std::string>{"GPSNMEA", "NEFF"}));
  EXPECT_EQ(stats.skipped_bad_odometry, 2);  // timestamps 0 and -0.958593
  EXPECT_EQ(stats.odometry, 2);
  EXPECT_NEAR(frames[0].T_odom_base.x(), 0.5, 1e-9);  // ODOM at 30.0 (x 0) and 30.2 (x 1)
}

TEST(CarmenReader, ReadsGzipTransparently) {
  const auto dir = testing::MakeTempDir("carmen_gz");
  const std::string plain = (FixtureDir() / "carmen_robotlaser_interleaved.clf").string();
  const std::string gz = (dir / "log.clf.gz").string();
  std::ifstream in(plain, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  gzFile f = gzopen(gz.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(gzwrite(f, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  ASSERT_EQ(gzclose(f), Z_OK);
  const auto a = ReadCarmenLog(plain, {});
  const auto b = ReadCarmenLog(gz, {});
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a.value().size(), b.value().size());
  for (std::size_t i = 0; i < a.value().size(); ++i) {
    EXPECT_EQ(a.value()[i].time, b.value()[i].time);
    EXPECT_EQ(a.value()[i].scan.size(), b.value()[i].scan.size());
    EXPECT_TRUE(IsApprox(a.value()[i].T_odom_base, b.value()[i].T_odom_base));
  }
  // A truncated gzip file is an error, not a silent short read.
  const std::string cut = (dir / "cut.clf.gz").string();
  {
    std::ifstream full(gz, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(full)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<long>(bytes.size() / 2));
  }
  EXPECT_FALSE(ReadCarmenLog(cut, {}).ok());
  std::filesystem::remove_all(dir);
}

TEST(CarmenReader, StreamsWithBoundedLookAhead) {
  // A long synthetic log: the first frame must come out long before the end is read.
  const auto dir = testing::MakeTempDir("carmen_stream");
  const std::string path = (dir / "long.clf").string();
  {
    std::ofstream out(path);
    for (int k = 0; k < 20000; ++k) {
      const double t = 1000.0 + 0.1 * k;
      out << "ODOM " << 0.1 * k << " 0 0 0 0 0 " << std::fixed << t << " h " << t << "\n";
      out << "RAWLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 2 1.00 1.00 0 " << t + 0.05
          << " h 0\n";
    }
  }
  auto reader = CarmenReader::Open(path, {});
  ASSERT_TRUE(reader.ok());
  auto first = reader.value().Next();
  ASSERT_TRUE(first.ok() && first.value().has_value());
  EXPECT_LT(reader.value().Stats().lines, 200);
  long count = 1;
  while (true) {
    auto next = reader.value().Next();
    ASSERT_TRUE(next.ok());
    if (!next.value()) {
      break;
    }
    ++count;
    if (count < 20000) {  // the last scan comes after the last ODOM line
      EXPECT_NEAR(next.value()->T_odom_base.x(), ToSeconds(next.value()->time) - 1000.0, 1e-6);
    }
  }
  EXPECT_EQ(count, 20000);
  std::filesystem::remove_all(dir);
}

TEST(CarmenReader, ScansBeyondTheOdometryWaitOnlyMaxLookahead) {
  // ODOM stops after 1 s while scans go on for 40 s: each scan is emitted, clamped to the last
  // ODOM, once the log has moved max_lookahead (10 s) past it, not at the end of the file.
  const auto dir = testing::MakeTempDir("carmen_lookahead");
  const std::string path = (dir / "gap.clf").string();
  {
    std::ofstream out(path);
    out << std::fixed;
    out << "ODOM 0 0 0 0 0 0 100.000000 h 0\nODOM 1 0 0 0 0 0 101.000000 h 0\n";
    for (int k = 0; k < 400; ++k) {
      out << "RAWLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 2 1.00 1.00 0 "
          << 101.05 + 0.1 * k << " h 0\n";
    }
  }
  auto reader = CarmenReader::Open(path, {});
  ASSERT_TRUE(reader.ok());
  auto first = reader.value().Next();
  ASSERT_TRUE(first.ok() && first.value().has_value());
  EXPECT_NEAR(first.value()->T_odom_base.x(), 1.0, 1e-12);
  EXPECT_LT(reader.value().Stats().lines, 150);
  EXPECT_GT(reader.value().Stats().lines, 100);
  std::filesystem::remove_all(dir);
}

TEST(CarmenReader, LogWithoutAnyOdometryMarksFramesWithoutOdometry) {
  const auto dir = testing::MakeTempDir("carmen_no_odometry");
  const std::string path = (dir / "no_odom.clf").string();
  {
    std::ofstream out(path);
    out << std::fixed;
    for (int k = 0; k < 5; ++k) {
      out << "RAWLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 2 1.00 1.00 0 "
          << 100.0 + 0.1 * k << " h 0\n";
    }
  }
  const auto frames = ReadCarmenLog(path, {});
  ASSERT_TRUE(frames.ok());
  ASSERT_EQ(frames.value().size(), 5U);
  for (const Frame& f : frames.value()) {
    EXPECT_FALSE(f.has_odometry);
    EXPECT_TRUE(IsApprox(f.T_odom_base, Pose2::Identity()));
  }
  // With ODOM lines (or laser lines carrying poses) the frames have odometry.
  for (const auto& f : ReadFixture("carmen_interpolation.clf")) {
    EXPECT_TRUE(f.has_odometry);
  }
  for (const auto& f : ReadFixture("carmen_robotlaser_interleaved.clf")) {
    EXPECT_TRUE(f.has_odometry);
  }
  std::filesystem::remove_all(dir);
}

std::string WriteTempLog(const std::string& dir_name, const std::string& text) {
  const auto dir = testing::MakeTempDir(dir_name);
  const std::string path = (dir / "log.clf").string();
  std::ofstream(path) << text;
  return path;
}

TEST(CarmenReader, SynthesizesTimesWhenTheLogHasNoTimestampFields) {
  // laserazos: FLASER n ranges x y theta odom_x odom_y odom_theta, nothing after.
  const std::string path = WriteTempLog("carmen_untimed",
                                        "FLASER 3 1.0 2.0 3.0 0.5 0.0 0.1 0.5 0.0 0.1\n"
                                        "FLASER 3 1.0 2.0 3.0 0.6 0.0 0.1 0.6 0.0 0.1\n"
                                        "FLASER 3 1.0 2.0 3.0 0.7 0.0 0.1 0.7 0.0 0.1\n");
  CarmenStats stats;
  auto frames = ReadCarmenLog(path, {}, &stats);
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 3U);
  EXPECT_EQ(stats.synthesized_timestamps, 3);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(frames.value()[k].time, FromSeconds(0.1 * static_cast<double>(k)));  // 10 Hz
    EXPECT_NEAR(frames.value()[k].T_odom_base.x(), 0.5 + 0.1 * static_cast<double>(k), 1e-9);
    EXPECT_TRUE(frames.value()[k].has_odometry);
  }
  CarmenOptions options;
  options.timestamp_rate = 4.0;
  frames = ReadCarmenLog(path, options);
  ASSERT_TRUE(frames.ok());
  EXPECT_EQ(frames.value()[2].time, FromSeconds(0.5));
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST(CarmenReader, OrebroStyleZeroOdometryAndNoIpcTimestamp) {
  // orebro: `... x y theta 0 0 0 pippo 0`: no ipc_timestamp, the odometry in the laser triple.
  const std::string path = WriteTempLog("carmen_orebro",
                                        "FLASER 2 1.0 2.0 0 0 -0.001 0 0 0 pippo 0\n"
                                        "FLASER 2 1.0 2.0 0.5 0.03 0.05 0 0 0 pippo 0\n");
  CarmenStats stats;
  auto frames = ReadCarmenLog(path, {}, &stats);
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 2U);
  EXPECT_EQ(stats.synthesized_timestamps, 2);
  EXPECT_EQ(frames.value()[1].time, FromSeconds(0.1));
  EXPECT_TRUE(IsApprox(frames.value()[1].T_odom_base, Pose2(0.5, 0.03, 0.05)));
  EXPECT_TRUE(IsApprox(frames.value()[1].T_base_laser, Pose2::Identity()));
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST(CarmenReader, TimestampZeroOnTheFirstLaserLineSynthesizesTimes) {
  const std::string path =
      WriteTempLog("carmen_zero_time",
                   "ODOM 0 0 0 0 0 0 0 h 0\n"
                   "RAWLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 2 1.00 1.00 0 0 h 0\n"
                   "ODOM 1 0 0 0 0 0 0 h 0\n"
                   "RAWLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 2 1.00 1.00 0 0 h 0\n");
  auto frames = ReadCarmenLog(path, {});
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 2U);
  EXPECT_EQ(frames.value()[1].time, FromSeconds(0.1));
  // The ODOM line before each laser line gets its time: the second scan sits on x = 1.
  EXPECT_NEAR(frames.value()[1].T_odom_base.x(), 1.0, 1e-9);
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST(CarmenReader, MissingTimestampInATimedLogIsAnError) {
  const std::string path = WriteTempLog("carmen_missing_time",
                                        "FLASER 2 1.0 2.0 0 0 0 0 0 0 10.0 h 0\n"
                                        "FLASER 2 1.0 2.0 0 0 0 0 0 0\n");
  auto frames = ReadCarmenLog(path, {});
  ASSERT_FALSE(frames.ok());
  EXPECT_EQ(frames.error().line, 2);
  EXPECT_NE(frames.error().message.find("ipc_timestamp"), std::string::npos);
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST(CarmenReader, MissingFileIsNotFound) {
  auto r = CarmenReader::Open("/nonexistent/log.clf", {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kNotFound);
}

}  // namespace
}  // namespace gridslam::io
