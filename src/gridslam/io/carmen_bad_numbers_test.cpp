// Issue 17's CARMEN reproducers: non-finite and out-of-range numbers, oversized timestamps and
// NUL bytes are rejected with file, line and field (exit 2 in the commands), never passed on.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

constexpr const char* kScan =
    "RAWLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 5 1.00 1.00 1.00 1.00 1.00 0 ";
constexpr const char* kOdom = "ODOM 0.000000 0.000000 0.000000 0.0 0.0 0.0 ";

std::string Write(const std::string& name, const std::string& text) {
  const auto dir = testing::MakeTempDir("carmen_bad_numbers");
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// Reads `text` as a log and expects an InvalidInput error at `line` mentioning `needle`.
void ExpectRejected(const std::string& text, long line, const std::string& needle) {
  const std::string path = Write("log.clf", text);
  const auto frames = ReadCarmenLog(path, CarmenOptions{});
  ASSERT_FALSE(frames.ok()) << "accepted:\n" << text;
  const Error& e = frames.error();
  EXPECT_EQ(e.code, ErrorCode::kInvalidInput);
  EXPECT_EQ(e.file, path);
  EXPECT_EQ(e.line, line) << e.ToString();
  EXPECT_NE(e.message.find(needle), std::string::npos) << e.ToString();
}

std::string Line(const std::string& prefix, const std::string& time) {
  return prefix + time + " host 0.0\n";
}

TEST(CarmenBadNumbers, NonFiniteOrHugeOdometryIsRejected) {
  for (const char* x : {"nan", "inf", "-inf", "1e308", "-1e6"}) {
    const std::string text = Line(kOdom, "100.0") + Line(kScan, "100.1") +
                             Line(std::string("ODOM ") + x + " 0 0 0 0 0 ", "100.2") +
                             Line(kScan, "100.3");
    ExpectRejected(text, 3, "odom_x");
  }
  ExpectRejected(Line("ODOM 0 0 nan 0 0 0 ", "100.0"), 1, "odom_theta");
}

TEST(CarmenBadNumbers, HugeLaserOffsetParamIsRejected) {
  ExpectRejected("PARAM robot_frontlaser_offset 1e308 nohost 0\n" + Line(kOdom, "100.0"), 1,
                 "robot_frontlaser_offset");
  ExpectRejected("PARAM robot_rearlaser_angular_offset -1e300 nohost 0\n", 1,
                 "robot_rearlaser_angular_offset");
}

TEST(CarmenBadNumbers, RobotLaserPosesAndGeometryAreBounded) {
  const std::string robot = "ROBOTLASER1 0 -1.570796 3.141593 0.785398 81.90 0.01 0 2 1.0 1.0 0 ";
  ExpectRejected(Line(robot + "0 0 0 1e308 0 0 0 0 0 0 0 ", "100.0"), 1, "robot_pose_x");
  ExpectRejected(Line(robot + "inf 0 0 0 0 0 0 0 0 0 0 ", "100.0"), 1, "laser_pose_x");
  ExpectRejected(Line("RAWLASER1 0 -1.5 3.1 1e300 81.9 0.01 0 1 1.0 0 ", "100.0"), 1,
                 "angular_resolution");
}

TEST(CarmenBadNumbers, TimestampsBeyondTheRangeAreRejected) {
  ExpectRejected(Line(kOdom, "100.0") + Line(kScan, "20000000000.000000"), 2, "ipc_timestamp");
  ExpectRejected(Line(kScan, "1e308"), 1, "ipc_timestamp");
  ExpectRejected(Line(kOdom, "-1e300"), 1, "ipc_timestamp");
}

// Issue 17: a NUL byte merged two lines (gzgets/strlen), so every later line number was off by
// one. Now the line holding it is named, and the lines after it keep their numbers.
TEST(CarmenBadNumbers, NulByteIsReportedAtItsLine) {
  std::string text = "# comment\n# second\n# bad";
  text += '\0';
  text += "byte\n";
  text += Line(kOdom, "100.0");
  ExpectRejected(text, 3, "NUL");
  // Lenient: the line is skipped and the next lines keep their numbers.
  const std::string path = Write("nul.clf", text + "ODOM x\n");
  CarmenOptions options;
  options.lenient = true;
  CarmenStats stats;
  const auto frames = ReadCarmenLog(path, options, &stats);
  ASSERT_TRUE(frames.ok());
  EXPECT_EQ(stats.lines, 5);
  EXPECT_EQ(stats.skipped_malformed, 2);
  EXPECT_EQ(stats.odometry, 1);
}

TEST(CarmenBadNumbers, LongLinesWithoutNewlineAreReadWhole) {
  // A line longer than the reader's chunk and a last line without a newline.
  std::string scan = "RAWLASER1 0 -1.570796 0.0 0.0001 81.90 0.01 0 20000";
  for (int i = 0; i < 20000; ++i) {
    scan += " 1.00";
  }
  scan += " 0 ";
  const std::string path =
      Write("long.clf", Line(kOdom, "100.0") + Line(scan, "100.1") + kOdom + "100.2 host 0.0");
  CarmenStats stats;
  const auto frames = ReadCarmenLog(path, CarmenOptions{}, &stats);
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 1U);
  EXPECT_EQ(frames.value()[0].scan.size(), 20000U);
  EXPECT_EQ(stats.odometry, 2);
}

}  // namespace
}  // namespace gridslam::io
