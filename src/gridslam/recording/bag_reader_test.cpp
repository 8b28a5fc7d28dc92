#include "gridslam/recording/bag_reader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "gridslam/recording/internal/test_bag_writer.hpp"

#include <sqlite3.h>

namespace gridslam::recording {
namespace {

namespace t = testing;
using t::Bytes;

constexpr std::int64_t kSecond = 1000000000LL;
constexpr std::int64_t kStart = 1000 * kSecond;

std::vector<t::TestTopic> Topics() {
  return {{"/scan", "sensor_msgs/LaserScan"},
          {"/odom", "nav_msgs/Odometry"},
          {"/tf", "tf2_msgs/TFMessage"},
          {"/tf_static", "tf2_msgs/TFMessage"}};
}

// Odometry x = t (s since start), yaw = 0.1 t, at 0, 1, 2, 3 s; scans at 0.25, 1.5, 2.75 s;
// base_link -> mount (0.1 m ahead) -> laser (0.05 m left, rotated pi).
std::vector<t::TestMessage> Messages(MessageEncoding e) {
  std::vector<t::TestMessage> m;
  m.push_back({3, kStart,
               t::TfBytes(e, {{kStart, "base_link", "mount", 0.1, 0, 0},
                              {kStart, "/mount", "laser", 0, 0.05, M_PI}})});
  for (int i = 0; i <= 3; ++i) {
    const std::int64_t stamp = kStart + i * kSecond;
    m.push_back({1, stamp, t::OdometryBytes(e, stamp, i, 0, 0.1 * i)});
    m.push_back({2, stamp, t::TfBytes(e, {{stamp, "odom", "base_link", 1.0 * i, 0, 0.1 * i}})});
  }
  for (double s : {0.25, 1.5, 2.75}) {
    const auto stamp = kStart + static_cast<std::int64_t>(s * 1e9);
    m.push_back({0, stamp + 10, t::ScanBytes(e, stamp, "laser", -1.0F, 0.01F, {1, 2, 3})});
  }
  return m;
}

void ExpectAssembled(const BagContents& bag, const BagOptions& options = {}) {
  BagAssembly a;
  auto frames = AssembleBagFrames(bag, options, 80.0, &a);
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 3U);
  EXPECT_EQ(a.scan_topic, "/scan");
  EXPECT_TRUE(a.mounting_from_tf);
  const double times[] = {0.25, 1.5, 2.75};
  for (int i = 0; i < 3; ++i) {
    const Frame& f = frames.value()[static_cast<std::size_t>(i)];
    EXPECT_TRUE(f.has_odometry);
    EXPECT_EQ(f.time.time_since_epoch().count(),
              kStart + static_cast<std::int64_t>(times[i] * 1e9));
    // Interpolated at the scan stamp, not the latest message.
    EXPECT_NEAR(f.T_odom_base.x(), times[i], 1e-9);
    EXPECT_NEAR(f.T_odom_base.theta(), 0.1 * times[i], 1e-9);
    // Composed chain base_link -> mount -> laser.
    EXPECT_NEAR(f.T_base_laser.x(), 0.1, 1e-12);
    EXPECT_NEAR(f.T_base_laser.y(), 0.05, 1e-12);
    EXPECT_NEAR(std::abs(f.T_base_laser.theta()), M_PI, 1e-9);
    EXPECT_EQ(f.scan.size(), 3U);
  }
}

class Ros1BagTest : public ::testing::TestWithParam<std::string> {};

TEST_P(Ros1BagTest, ReadsScansOdometryAndMounting) {
  const Bytes bytes = t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), GetParam());
  auto bag = LoadBagBytes(bytes, false);
  ASSERT_TRUE(bag.ok()) << bag.error().ToString();
  EXPECT_EQ(bag.value().format, BagFormat::kRos1);
  ASSERT_EQ(bag.value().topics.size(), 4U);
  EXPECT_EQ(bag.value().topics[0].count, 3);
  EXPECT_EQ(bag.value().topics[1].count, 4);
  ExpectAssembled(bag.value());
  BagAssembly a;
  ASSERT_TRUE(AssembleBagFrames(bag.value(), {}, 80.0, &a).ok());
  EXPECT_EQ(a.odometry_source, "/odom");
}

TEST_P(Ros1BagTest, TruncatedAndCorruptBagsAreErrors) {
  const Bytes bytes = t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), GetParam());
  for (std::size_t cut : {bytes.size() / 3, bytes.size() / 2, bytes.size() - 3}) {
    auto bag = LoadBagBytes(std::span(bytes).first(cut), false);
    EXPECT_FALSE(bag.ok()) << cut;
  }
  Bytes corrupt = bytes;
  for (std::size_t i = 200; i < 260 && i < corrupt.size(); ++i) {
    corrupt[i] ^= 0x5a;
  }
  auto bag = LoadBagBytes(corrupt, false);
  EXPECT_FALSE(bag.ok());
}

INSTANTIATE_TEST_SUITE_P(Compressions, Ros1BagTest, ::testing::Values("none", "bz2", "lz4"));

TEST(Ros1Bag, ReadsAnUnindexedBagSequentially) {
  const Bytes bytes = t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), "bz2", false);
  auto bag = LoadBagBytes(bytes, false);
  ASSERT_TRUE(bag.ok()) << bag.error().ToString();
  ExpectAssembled(bag.value());
  EXPECT_FALSE(LoadBagBytes(std::span(bytes).first(bytes.size() / 2), false).ok());
}

TEST(Ros1Bag, FollowsTheChunkIndexPastAMisleadingRecordLength) {
  const Bytes bytes =
      t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), "none", true, true);
  auto bag = LoadBagBytes(bytes, false);
  ASSERT_TRUE(bag.ok()) << bag.error().ToString();
  ExpectAssembled(bag.value());
}

TEST(Ros1Bag, IndexPointingPastTheEndIsTruncation) {
  const Bytes bytes = t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), "none");
  auto bag = LoadBagBytes(std::span(bytes).first(bytes.size() - 40), false);
  ASSERT_FALSE(bag.ok());
  EXPECT_NE(bag.error().message.find("truncated"), std::string::npos) << bag.error().message;
}

TEST(Ros1Bag, WrongMagicIsAnError) {
  Bytes bytes = t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), "none");
  bytes[9] = '1';
  auto bag = LoadBagBytes(bytes, false);
  ASSERT_FALSE(bag.ok());
  EXPECT_NE(bag.error().message.find("version"), std::string::npos);
  bytes[0] = 'X';
  EXPECT_FALSE(LoadBagBytes(bytes, false).ok());
}

TEST(Ros1Bag, CorruptCompressedChunkSaysSo) {
  Bytes bytes = t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), "bz2");
  bytes[bytes.size() / 2] ^= 0xff;
  bytes[bytes.size() / 2 + 1] ^= 0xff;
  auto bag = LoadBagBytes(bytes, false);
  ASSERT_FALSE(bag.ok());
  EXPECT_NE(bag.error().message.find("chunk"), std::string::npos) << bag.error().message;
}

class McapTest : public ::testing::TestWithParam<std::string> {};

TEST_P(McapTest, ReadsScansOdometryAndMounting) {
  const Bytes bytes = t::BuildMcap(Topics(), Messages(MessageEncoding::kCdr), GetParam());
  auto bag = LoadBagBytes(bytes, false);
  ASSERT_TRUE(bag.ok()) << bag.error().ToString();
  EXPECT_EQ(bag.value().format, BagFormat::kMcap);
  ExpectAssembled(bag.value());
}

TEST_P(McapTest, TruncatedAndCorruptFilesAreErrors) {
  const Bytes bytes = t::BuildMcap(Topics(), Messages(MessageEncoding::kCdr), GetParam());
  for (std::size_t cut : {bytes.size() / 3, bytes.size() / 2, bytes.size() - 60}) {
    EXPECT_FALSE(LoadBagBytes(std::span(bytes).first(cut), false).ok()) << cut;
  }
  Bytes corrupt = bytes;
  corrupt[corrupt.size() / 2] ^= 0x01;  // inside the chunk: decompression or CRC fails
  auto bag = LoadBagBytes(corrupt, false);
  ASSERT_FALSE(bag.ok());
  EXPECT_NE(bag.error().message.find("chunk"), std::string::npos) << bag.error().message;
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapTest, ::testing::Values("", "zstd", "lz4"));

BagContents Load(const std::vector<t::TestTopic>& topics,
                 const std::vector<t::TestMessage>& messages) {
  auto bag = LoadBagBytes(t::BuildRos1Bag(topics, messages, "none"), false);
  EXPECT_TRUE(bag.ok());
  return bag.value();
}

TEST(BagAssembly, TfOdometryWhenRequestedOrWithoutAnOdometryTopic) {
  auto topics = Topics();
  auto messages = Messages(MessageEncoding::kRos1);
  std::erase_if(messages, [](const t::TestMessage& m) { return m.connection == 1; });
  const BagContents bag = Load(topics, messages);
  BagAssembly a;
  ASSERT_TRUE(AssembleBagFrames(bag, {}, 80.0, &a).ok());
  EXPECT_EQ(a.odometry_source, "tf odom->base_link");
  ExpectAssembled(bag);
  BagOptions options;
  options.odom_frame = "/odom";  // a leading slash (ROS 1 style) names the same frame
  ExpectAssembled(Load(Topics(), Messages(MessageEncoding::kRos1)), options);
  ASSERT_TRUE(
      AssembleBagFrames(Load(Topics(), Messages(MessageEncoding::kRos1)), options, 80.0, &a).ok());
  EXPECT_EQ(a.odometry_source, "tf odom->base_link");  // requested TF wins over /odom
}

TEST(BagAssembly, TfOdometryThroughAnIntermediateFrame) {
  std::vector<t::TestMessage> m;
  m.push_back(
      {3, kStart,
       t::TfBytes(MessageEncoding::kRos1, {{kStart, "base_footprint", "base_link", 0.5, 0, 0},
                                           {kStart, "base_link", "laser", 0.1, 0, 0}})});
  for (int i = 0; i <= 1; ++i) {
    m.push_back({2, kStart + i * kSecond,
                 t::TfBytes(MessageEncoding::kRos1,
                            {{kStart + i * kSecond, "odom", "base_footprint", 2.0 * i, 0, 0}})});
  }
  m.push_back(
      {0, kStart + kSecond / 2,
       t::ScanBytes(MessageEncoding::kRos1, kStart + kSecond / 2, "laser", -1, 0.1F, {1, 2})});
  BagAssembly a;
  auto frames = AssembleBagFrames(Load(Topics(), m), {}, 80.0, &a);
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 1U);
  EXPECT_NEAR(frames.value()[0].T_odom_base.x(), 1.0 + 0.5, 1e-9);
  EXPECT_NEAR(frames.value()[0].T_base_laser.x(), 0.1, 1e-12);
  EXPECT_EQ(a.odometry_source, "tf odom->base_footprint->base_link");
}

TEST(BagAssembly, ScansWithoutOdometry) {
  std::vector<t::TestMessage> m;
  for (int i = 0; i < 4; ++i) {
    m.push_back(
        {0, kStart + i * kSecond,
         t::ScanBytes(MessageEncoding::kRos1, kStart + i * kSecond, "laser", -2, 0.1F, {1, 2, 3})});
  }
  BagAssembly a;
  auto frames = AssembleBagFrames(Load({{"/scan", "sensor_msgs/LaserScan"}}, m), {}, 80.0, &a);
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  ASSERT_EQ(frames.value().size(), 4U);
  EXPECT_EQ(a.odometry_source, "none");
  for (const Frame& f : frames.value()) {
    EXPECT_FALSE(f.has_odometry);
    EXPECT_EQ(f.T_odom_base.x(), 0.0);
    EXPECT_EQ(f.T_odom_base.theta(), 0.0);
  }
}

TEST(BagAssembly, MissingOrAmbiguousTopicsListTheBagsTopics) {
  const BagContents bag = Load(Topics(), Messages(MessageEncoding::kRos1));
  BagOptions options;
  options.scan_topic = "/base_scan";
  auto frames = AssembleBagFrames(bag, options, 80.0, nullptr);
  ASSERT_FALSE(frames.ok());
  EXPECT_EQ(frames.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(frames.error().message.find("/base_scan"), std::string::npos);
  EXPECT_NE(frames.error().message.find("/odom  nav_msgs/Odometry  4 messages"), std::string::npos)
      << frames.error().message;

  options = {};
  options.odom_topic = "/wheel_odom";
  EXPECT_FALSE(AssembleBagFrames(bag, options, 80.0, nullptr).ok());

  auto topics = Topics();
  topics.push_back({"/scan2", "sensor_msgs/LaserScan"});
  auto messages = Messages(MessageEncoding::kRos1);
  messages.push_back(
      {4, kStart, t::ScanBytes(MessageEncoding::kRos1, kStart, "laser2", -1, 0.1F, {1})});
  const BagContents two = Load(topics, messages);
  frames = AssembleBagFrames(two, {}, 80.0, nullptr);
  ASSERT_FALSE(frames.ok());
  EXPECT_NE(frames.error().message.find("--scan-topic"), std::string::npos);
  EXPECT_NE(frames.error().message.find("/scan2"), std::string::npos);
  options = {};
  options.scan_topic = "/scan";
  ExpectAssembled(two, options);

  const BagContents no_scans =
      Load({{"/odom", "nav_msgs/Odometry"}},
           {{0, kStart, t::OdometryBytes(MessageEncoding::kRos1, 1, 0, 0, 0)}});
  EXPECT_FALSE(AssembleBagFrames(no_scans, {}, 80.0, nullptr).ok());
}

TEST(BagAssembly, MalformedMessageIsAnErrorUnlessLenient) {
  auto messages = Messages(MessageEncoding::kRos1);
  messages.back().data.resize(20);
  const Bytes bytes = t::BuildRos1Bag(Topics(), messages, "none");
  auto strict = LoadBagBytes(bytes, false);
  ASSERT_FALSE(strict.ok());
  EXPECT_NE(strict.error().message.find("/scan"), std::string::npos);
  auto lenient = LoadBagBytes(bytes, true);
  ASSERT_TRUE(lenient.ok());
  EXPECT_EQ(lenient.value().skipped_malformed, 1);
}

TEST(Rosbag2Sqlite, ReadsAFolderAndAFile) {
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("gridslam_db3_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string db_path = (dir / "bag_0.db3").string();
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db_path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, "
                         "serialization_format TEXT, offered_qos_profiles TEXT);"
                         "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, "
                         "timestamp INTEGER, data BLOB);",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  const auto topics = Topics();
  for (std::size_t i = 0; i < topics.size(); ++i) {
    std::string type = topics[i].type;
    type.insert(type.find('/'), "/msg");
    const std::string sql = "INSERT INTO topics VALUES(" + std::to_string(i + 1) + ", '" +
                            topics[i].topic + "', '" + type + "', 'cdr', '')";
    ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  }
  sqlite3_stmt* insert = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?,?,?)",
                               -1, &insert, nullptr),
            SQLITE_OK);
  for (const t::TestMessage& m : Messages(MessageEncoding::kCdr)) {
    sqlite3_bind_int(insert, 1, m.connection + 1);
    sqlite3_bind_int64(insert, 2, m.time_ns);
    sqlite3_bind_blob(insert, 3, m.data.data(), static_cast<int>(m.data.size()), SQLITE_STATIC);
    ASSERT_EQ(sqlite3_step(insert), SQLITE_DONE);
    sqlite3_reset(insert);
  }
  sqlite3_finalize(insert);
  sqlite3_close(db);
  for (const std::string& path : {dir.string(), db_path}) {
    auto bag = LoadBag(path, false);
    ASSERT_TRUE(bag.ok()) << bag.error().ToString();
    EXPECT_EQ(bag.value().format, BagFormat::kRosbag2Sqlite);
    ExpectAssembled(bag.value());
  }
  std::filesystem::remove_all(dir);
}

TEST(BagFuzzEntry, ArbitraryBytesNeverCrash) {
  const Bytes good = t::BuildRos1Bag(Topics(), Messages(MessageEncoding::kRos1), "lz4");
  const Bytes mcap = t::BuildMcap(Topics(), Messages(MessageEncoding::kCdr), "zstd");
  ASSERT_TRUE(DecodeBagForFuzzing(good).ok());
  ASSERT_TRUE(DecodeBagForFuzzing(mcap).ok());
  std::uint32_t state = 12345;
  for (const Bytes* base : {&good, &mcap}) {
    for (int trial = 0; trial < 300; ++trial) {
      Bytes b = *base;
      for (int k = 0; k < 4; ++k) {
        state = state * 1664525U + 1013904223U;
        b[8 + state % (b.size() - 8)] = static_cast<std::uint8_t>(state >> 24);
      }
      (void)DecodeBagForFuzzing(b);  // value or error, must not crash
    }
  }
}

}  // namespace
}  // namespace gridslam::recording
