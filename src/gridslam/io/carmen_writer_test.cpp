#include "gridslam/io/carmen_writer.hpp"

#include <gtest/gtest.h>

#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

Time At(const char* seconds) { return *ParseSeconds(seconds); }

Frame MakeFrame(const char* time, const Pose2& odom, float first_range) {
  Frame frame;
  frame.time = At(time);
  frame.corrected_time = frame.time;
  frame.T_odom_base = odom;
  frame.scan.angle_min = -std::numbers::pi / 2.0;
  frame.scan.angle_increment = std::numbers::pi / 4.0;
  frame.scan.range_max = 30.0;
  frame.scan.ranges = {first_range, 2.333F, 30.0F, 4.0F, 0.5F};
  frame.T_world_base_true = Pose2(10.0, 20.0, 0.5);
  return frame;
}

TEST(CarmenWriter, LinesAreFormattedAsCarmenWritesThem) {
  const Time start = At("1000.000000");
  EXPECT_EQ(FormatOdometryLine({At("1000.250000"), Pose2(1.25, -0.32, 0.785398), 0.3, 0.05}, "host",
                               start),
            "ODOM 1.250000 -0.320000 0.785398 0.300000 0.050000 0.000000 1000.250000 host "
            "0.250000\n");
  CarmenWriterOptions options;
  options.hostname = "sim";
  const Frame frame = MakeFrame("1000.500000", Pose2(1.0, 2.0, 0.1), 2.3149F);
  EXPECT_EQ(FormatLaserLines(frame, options, start),
            "RAWLASER1 0 -1.570796 3.141593 0.785398 30.000000 0.010000 0 5 2.31 2.33 30.00 "
            "4.00 0.50 0 1000.500000 sim 0.500000\n");
  options.write_truepos = true;
  options.laser_message = CarmenLaserMessage::kFlaser;
  EXPECT_EQ(FormatLaserLines(frame, options, start),
            "TRUEPOS 10.000000 20.000000 0.500000 1.000000 2.000000 0.100000 1000.500000 sim "
            "0.500000\n"
            "FLASER 5 2.31 2.33 30.00 4.00 0.50 1.000000 2.000000 0.100000 1.000000 2.000000 "
            "0.100000 1000.500000 sim 0.500000\n");
}

TEST(CarmenWriter, ReaderGetsBackWhatWasWritten) {
  const auto dir = testing::MakeTempDir("carmen_writer");
  std::vector<Frame> frames;
  for (int k = 0; k < 20; ++k) {
    const Time t = At("1577836800.0") + std::chrono::milliseconds(200 * k + 3);
    const double x = 0.1 * k;
    frames.push_back(MakeFrame(FormatSeconds(t).c_str(), Pose2(x, x * x, 0.05 * k - 0.4),
                               static_cast<float>(1.0 + x)));
    frames.back().T_base_laser = Pose2(0.2, 0.0, 0.0);
  }
  for (const auto message : {CarmenLaserMessage::kRawLaser1, CarmenLaserMessage::kRobotLaser1,
                             CarmenLaserMessage::kFlaser}) {
    CarmenWriterOptions options;
    options.laser_message = message;
    const std::string path = (dir / "log.clf").string();
    ASSERT_TRUE(WriteCarmenLog(path, frames, options).ok());
    const auto read = ReadCarmenLog(path, CarmenOptions{});
    ASSERT_TRUE(read.ok()) << read.error().ToString();
    ASSERT_EQ(read.value().size(), frames.size());
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const Frame& a = frames[k];
      const Frame& b = read.value()[k];
      EXPECT_EQ(a.time, b.time);
      EXPECT_TRUE(IsApprox(a.T_odom_base, b.T_odom_base, 1e-6, 1e-6));
      EXPECT_TRUE(IsApprox(a.T_base_laser, b.T_base_laser, 1e-6, 1e-6));
      ASSERT_EQ(a.scan.size(), b.scan.size());
      if (message != CarmenLaserMessage::kFlaser) {  // FLASER carries no geometry
        EXPECT_NEAR(a.scan.angle_min, b.scan.angle_min, 1e-6);
        EXPECT_NEAR(a.scan.angle_increment, b.scan.angle_increment, 1e-6);
        for (std::size_t i = 0; i < a.scan.size(); ++i) {
          EXPECT_NEAR(a.scan.ranges[i], b.scan.ranges[i], 0.0051);
          EXPECT_EQ(a.scan.IsHit(i), b.scan.IsHit(i)) << "beam " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace gridslam::io
