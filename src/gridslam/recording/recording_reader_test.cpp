#include "gridslam/recording/recording_reader.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "gridslam/recording/internal/test_bag_writer.hpp"

namespace gridslam::recording {
namespace {

namespace fs = std::filesystem;

class RecordingReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gridslam_recording_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& content) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }
  fs::path dir_;
};

TEST_F(RecordingReaderTest, ReadsACarmenLogAndABagThroughOneInterface) {
  const std::string log = Write("a.bag",  // the extension does not decide: the content does
                                "ODOM 0 0 0 0 0 0 1.0 h 1.0\n"
                                "ODOM 1 0 0 0 0 0 2.0 h 2.0\n"
                                "RAWLASER1 0 -1.5 3.0 1.5 80 0.01 0 3 1 2 3 0 1.5 h 1.5\n");
  auto frames = ReadRecording(log, {});
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 1U);
  EXPECT_NEAR(frames.value()[0].T_odom_base.x(), 0.5, 1e-9);

  using testing::Bytes;
  const Bytes b = testing::BuildRos1Bag(
      {{"/scan", "sensor_msgs/LaserScan"}},
      {{0, 5000000000LL,
        testing::ScanBytes(MessageEncoding::kRos1, 5000000000LL, "laser", -1, 0.1F, {1, 2})}},
      "bz2");
  const std::string bag = Write("scan.log", std::string(b.begin(), b.end()));
  auto reader = RecordingReader::Open(bag, {});
  ASSERT_TRUE(reader.ok()) << reader.error().ToString();
  EXPECT_EQ(reader.value().Format(), RecordingFormat::kRos1Bag);
  auto frame = reader.value().Next();
  ASSERT_TRUE(frame.ok() && frame.value().has_value());
  EXPECT_FALSE(frame.value()->has_odometry);
  frame = reader.value().Next();
  ASSERT_TRUE(frame.ok());
  EXPECT_FALSE(frame.value().has_value());
  EXPECT_EQ(reader.value().Stats().scans, 1);
}

TEST_F(RecordingReaderTest, RefusesFilesThatAreNotRecordings) {
  const std::pair<std::string, std::string> cases[] = {
      {"VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n", "g2o"},
      {"", "empty"},
      {"\x89PNG\r\n\x1a\n0000", "PNG"},
      {"1.0 2.0 0.1 0 0 0 0 0.01\n", "relations"},
  };
  for (const auto& [content, looks_like] : cases) {
    auto reader = RecordingReader::Open(Write("x.clf", content), {});
    ASSERT_FALSE(reader.ok()) << looks_like;
    EXPECT_EQ(reader.error().code, ErrorCode::kInvalidInput);
    EXPECT_NE(reader.error().message.find(looks_like), std::string::npos) << reader.error().message;
    EXPECT_NE(reader.error().file.find("x.clf"), std::string::npos);
  }
  auto missing = RecordingReader::Open((dir_ / "nope.clf").string(), {});
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::kNotFound);
}

TEST_F(RecordingReaderTest, ALogWithoutScansIsAnError) {
  auto frames = ReadRecording(Write("odom.clf", "ODOM 0 0 0 0 0 0 1.0 h 1.0\n"), {});
  ASSERT_FALSE(frames.ok());
  EXPECT_NE(frames.error().message.find("no laser scan"), std::string::npos);
}

}  // namespace
}  // namespace gridslam::recording
