#include "gridslam/recording/ros_messages.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "gridslam/recording/internal/test_bag_writer.hpp"

namespace gridslam::recording {
namespace {

using testing::Bytes;

class RosMessagesTest : public ::testing::TestWithParam<MessageEncoding> {};

TEST_P(RosMessagesTest, DecodesLaserScanWithNoReturns) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Bytes b = testing::ScanBytes(GetParam(), 1234567890123456789LL, "laser", -2.0F, 0.5F,
                                     {1.0F, nan, inf, 0.0F, 2.5F}, 0.05F, 5.6F);
  auto m = DecodeLaserScan(b, GetParam());
  ASSERT_TRUE(m.ok()) << m.error().ToString();
  EXPECT_EQ(m.value().stamp_ns, 1234567890123456789LL);
  EXPECT_EQ(m.value().frame_id, "laser");
  ASSERT_EQ(m.value().scan.size(), 5U);
  EXPECT_FLOAT_EQ(static_cast<float>(m.value().scan.angle_min), -2.0F);
  EXPECT_FLOAT_EQ(static_cast<float>(m.value().scan.angle_increment), 0.5F);
  EXPECT_FLOAT_EQ(static_cast<float>(m.value().scan.range_max), 5.6F);
  EXPECT_TRUE(m.value().scan.IsHit(0));
  EXPECT_FALSE(m.value().scan.IsHit(1));  // NaN
  EXPECT_FALSE(m.value().scan.IsHit(2));  // inf
  EXPECT_FALSE(m.value().scan.IsHit(3));  // 0
  EXPECT_TRUE(m.value().scan.IsHit(4));
}

TEST_P(RosMessagesTest, DecodesOdometryToThePlane) {
  const Bytes b = testing::OdometryBytes(GetParam(), 5000000001LL, 1.5, -2.0, 0.75, "base");
  auto m = DecodeOdometry(b, GetParam());
  ASSERT_TRUE(m.ok()) << m.error().ToString();
  EXPECT_EQ(m.value().stamp_ns, 5000000001LL);
  EXPECT_EQ(m.value().frame_id, "odom");
  EXPECT_EQ(m.value().child_frame_id, "base");
  EXPECT_NEAR(m.value().T_odom_base.x(), 1.5, 1e-12);
  EXPECT_NEAR(m.value().T_odom_base.y(), -2.0, 1e-12);
  EXPECT_NEAR(m.value().T_odom_base.theta(), 0.75, 1e-12);
}

TEST_P(RosMessagesTest, DecodesTfMessages) {
  const Bytes b = testing::TfBytes(
      GetParam(), {{1, "odom", "base_link", 1, 2, 0.1}, {2, "base_link", "laser", 0.2, 0, -3.0}});
  auto m = DecodeTfMessage(b, GetParam());
  ASSERT_TRUE(m.ok()) << m.error().ToString();
  ASSERT_EQ(m.value().size(), 2U);
  EXPECT_EQ(m.value()[1].parent, "base_link");
  EXPECT_EQ(m.value()[1].child, "laser");
  EXPECT_NEAR(m.value()[1].T_parent_child.x(), 0.2, 1e-12);
  EXPECT_NEAR(m.value()[1].T_parent_child.theta(), -3.0, 1e-12);
}

TEST_P(RosMessagesTest, TruncatedMessagesAreErrors) {
  const Bytes scan = testing::ScanBytes(GetParam(), 1, "laser", -1.0F, 0.1F, {1, 2, 3, 4});
  for (std::size_t cut : {std::size_t{0}, std::size_t{6}, scan.size() / 2, scan.size() - 9}) {
    EXPECT_FALSE(DecodeLaserScan(std::span(scan).first(cut), GetParam()).ok()) << cut;
  }
  const Bytes odom = testing::OdometryBytes(GetParam(), 1, 0, 0, 0);
  EXPECT_FALSE(DecodeOdometry(std::span(odom).first(40), GetParam()).ok());
  Bytes tf = testing::TfBytes(GetParam(), {{1, "a", "b", 0, 0, 0}});
  tf[GetParam() == MessageEncoding::kCdr ? 4 : 0] = 0xff;  // absurd count
  EXPECT_FALSE(DecodeTfMessage(tf, GetParam()).ok());
}

INSTANTIATE_TEST_SUITE_P(Encodings, RosMessagesTest,
                         ::testing::Values(MessageEncoding::kRos1, MessageEncoding::kCdr));

TEST(RosMessages, RejectsABadCdrEncapsulation) {
  Bytes b = testing::ScanBytes(MessageEncoding::kCdr, 1, "laser", -1.0F, 0.1F, {1, 2});
  b[1] = 0x07;
  auto m = DecodeLaserScan(b, MessageEncoding::kCdr);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("encapsulation"), std::string::npos);
}

TEST(RosMessages, MakesLaserScansFromMessageFields) {
  auto scan = MakeLaserScan(-1.5F, 0.25F, -0.1F, 30.0F, {1.0F, 2.0F});
  ASSERT_TRUE(scan.ok()) << scan.error().ToString();
  EXPECT_EQ(scan.value().size(), 2U);
  EXPECT_DOUBLE_EQ(scan.value().angle_min, -1.5);
  EXPECT_DOUBLE_EQ(scan.value().Angle(1), -1.25);
  EXPECT_DOUBLE_EQ(scan.value().range_min, 0.0);  // negative: clamped to 0
  EXPECT_DOUBLE_EQ(scan.value().range_max, 30.0);
  EXPECT_FALSE(MakeLaserScan(-1.5F, 0.0F, 0.1F, 30.0F, {1.0F}).ok());  // zero increment
  EXPECT_FALSE(MakeLaserScan(-1.5F, 0.25F, 0.1F, 30.0F, {}).ok());     // no beams
  EXPECT_FALSE(
      MakeLaserScan(std::numeric_limits<float>::quiet_NaN(), 0.25F, 0.1F, 30.0F, {1.0F}).ok());
}

TEST(RosMessages, KindsOfRos1AndRos2TypeNames) {
  EXPECT_EQ(KindOfType("sensor_msgs/LaserScan"), MessageKind::kLaserScan);
  EXPECT_EQ(KindOfType("sensor_msgs/msg/LaserScan"), MessageKind::kLaserScan);
  EXPECT_EQ(KindOfType("nav_msgs/msg/Odometry"), MessageKind::kOdometry);
  EXPECT_EQ(KindOfType("tf2_msgs/TFMessage"), MessageKind::kTf);
  EXPECT_EQ(KindOfType("std_msgs/String"), MessageKind::kOther);
}

}  // namespace
}  // namespace gridslam::recording
