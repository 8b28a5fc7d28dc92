#include "gridslam/io/simulation_io.hpp"

#include <fstream>

#include <gtest/gtest.h>

#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

TEST(SimulationIo, ScanIndexRoundTrip) {
  const auto dir = testing::MakeTempDir("scan_index");
  const std::vector<ScanIndexEntry> entries = {{*ParseSeconds("1577836800.000000"), 0},
                                               {*ParseSeconds("1577836800.002500"), 1},
                                               {*ParseSeconds("1577836800.200000"), 0}};
  const std::string path = (dir / "index.txt").string();
  ASSERT_TRUE(WriteScanIndex(path, entries).ok());
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "1577836800.000000 0");
  const auto read = ReadScanIndex(path);
  ASSERT_TRUE(read.ok());
  ASSERT_EQ(read.value().size(), 3U);
  EXPECT_EQ(read.value()[1].time, entries[1].time);
  EXPECT_EQ(read.value()[1].robot, 1);
}

TEST(SimulationIo, WaypointsAndTheirErrors) {
  const auto dir = testing::MakeTempDir("waypoints");
  std::ofstream(dir / "good.txt") << "# a route\n1.0 2.5\n\n  3 -4\n";
  const auto good = ReadWaypoints((dir / "good.txt").string());
  ASSERT_TRUE(good.ok());
  ASSERT_EQ(good.value().size(), 2U);
  EXPECT_TRUE(good.value()[1].isApprox(Eigen::Vector2d(3.0, -4.0)));
  std::ofstream(dir / "bad.txt") << "1 2\n3 x\n";
  const auto bad = ReadWaypoints((dir / "bad.txt").string());
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().line, 2);
  EXPECT_EQ(ReadWaypoints((dir / "none.txt").string()).error().code, ErrorCode::kNotFound);
}

}  // namespace
}  // namespace gridslam::io
