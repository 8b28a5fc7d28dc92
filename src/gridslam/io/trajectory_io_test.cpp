#include "gridslam/io/trajectory_io.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "gridslam/io/relations_io.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

std::vector<StampedPose> SomePoses() {
  return {{*ParseSeconds("976052857.337530"), Pose2(0.1234567890123, -5.5, 3.1)},
          {*ParseSeconds("976052857.348896"), Pose2(-1e-9, 2.0 / 3.0, -3.14159)},
          {*ParseSeconds("1211.500000"), Pose2(100.0, 1e5, 0.0)}};
}

void ExpectSame(const std::vector<StampedPose>& a, const std::vector<StampedPose>& b, double tol) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].time, b[i].time);
    EXPECT_TRUE(IsApprox(a[i].pose, b[i].pose, tol, tol)) << i;
  }
}

TEST(TrajectoryIo, PlainRoundTripIsExact) {
  const auto dir = testing::MakeTempDir("traj");
  const std::string path = (dir / "t.txt").string();
  ASSERT_TRUE(WriteTrajectory(path, SomePoses()).ok());
  const auto read = ReadTrajectory(path);
  ASSERT_TRUE(read.ok());
  ExpectSame(read.value(), SomePoses(), 0.0);
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first.substr(0, 17), "976052857.337530 ");
  std::filesystem::remove_all(dir);
}

TEST(TrajectoryIo, TumRoundTripAndExtension) {
  const auto dir = testing::MakeTempDir("traj_tum");
  const std::string path = (dir / "t.tum").string();
  ASSERT_TRUE(WriteTrajectoryByExtension(path, SomePoses()).ok());
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::istringstream fields(line);
  std::vector<std::string> tokens{std::istream_iterator<std::string>(fields), {}};
  EXPECT_EQ(tokens.size(), 8U);
  const auto read = ReadTrajectory(path);
  ASSERT_TRUE(read.ok());
  // TUM is written in ascending time (SomePoses' last stamp is the earliest).
  const std::vector<StampedPose> p = SomePoses();
  ExpectSame(read.value(), {p[2], p[0], p[1]}, 1e-12);
  std::filesystem::remove_all(dir);
}

TEST(TrajectoryIo, TumAscendingPlainInGivenOrder) {
  const auto dir = testing::MakeTempDir("traj_order");
  // A log whose stamps go backwards, with two equal stamps (which keep their order).
  const std::vector<StampedPose> poses = {{*ParseSeconds("10.0"), Pose2(1, 0, 0)},
                                          {*ParseSeconds("9.5"), Pose2(2, 0, 0)},
                                          {*ParseSeconds("11.0"), Pose2(3, 0, 0)},
                                          {*ParseSeconds("9.5"), Pose2(4, 0, 0)}};
  const std::string plain = (dir / "t.txt").string();
  const std::string tum = (dir / "t.tum").string();
  ASSERT_TRUE(WriteTrajectory(plain, poses).ok());
  ASSERT_TRUE(WriteTrajectoryTum(tum, poses).ok());
  ExpectSame(ReadTrajectory(plain).value(), poses, 1e-12);
  ExpectSame(ReadTrajectory(tum).value(), {poses[1], poses[3], poses[0], poses[2]}, 1e-12);
  std::filesystem::remove_all(dir);
}

TEST(TrajectoryIo, MalformedLineNamesLineAndField) {
  const auto dir = testing::MakeTempDir("traj_bad");
  const std::string path = (dir / "bad.txt").string();
  std::ofstream(path) << "# comment\n1.0 0 0 0\n\n2.0 0 x 0\n";
  const auto read = ReadTrajectory(path);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().line, 4);
  EXPECT_NE(read.error().message.find("'y'"), std::string::npos) << read.error().message;
  std::ofstream(path) << "1.0 0 0\n";
  EXPECT_FALSE(ReadTrajectory(path).ok());
  EXPECT_FALSE(ReadTrajectory((dir / "missing.txt").string()).ok());
  std::filesystem::remove_all(dir);
}

TEST(TrajectoryIo, FailedWriteLeavesNoFile) {
  const std::string path = "/nonexistent_dir_gridslam/t.txt";
  const Status s = WriteTrajectory(path, SomePoses());
  EXPECT_FALSE(s.ok());
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(TrajectoryIo, EntryInBaseOrLaserFrame) {
  Frame f;
  f.time = *ParseSeconds("5.0");
  f.T_base_laser = Pose2(0.22, 0.0, 0.0);
  const Pose2 T_w_b(1.0, 1.0, std::numbers::pi / 2);
  EXPECT_TRUE(IsApprox(TrajectoryEntry(f, T_w_b, "base").pose, T_w_b));
  EXPECT_TRUE(IsApprox(TrajectoryEntry(f, T_w_b, "laser").pose,
                       Pose2(1.0, 1.22, std::numbers::pi / 2), 1e-12));
}

TEST(RelationsIo, RoundTripSkipsCommentsAndIgnores3dFields) {
  const auto dir = testing::MakeTempDir("rel");
  const std::string path = (dir / "r.relations").string();
  std::ofstream(path) << "# timestamp1 timestamp2 x y z roll pitch yaw\n"
                      << "1232658478.161285 1232658644.149293 1.031273 -0.003531 0.000000 "
                         "0.000000 -0.000000 -0.009755\n"
                      << "\n1215.570000 1216.2 0.5 0.25 0 0 0 3.0\n";
  const auto read = ReadRelations(path);
  ASSERT_TRUE(read.ok());
  ASSERT_EQ(read.value().size(), 2U);
  const eval::Relation& r = read.value()[0];
  EXPECT_EQ(FormatSeconds(r.t1), "1232658478.161285");
  EXPECT_EQ(FormatSeconds(r.t2), "1232658644.149293");
  EXPECT_TRUE(IsApprox(r.T_1_2, Pose2(1.031273, -0.003531, -0.009755)));
  const std::string again = (dir / "again.relations").string();
  ASSERT_TRUE(WriteRelations(again, read.value()).ok());
  const auto reread = ReadRelations(again);
  ASSERT_TRUE(reread.ok());
  ASSERT_EQ(reread.value().size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(reread.value()[i].t1, read.value()[i].t1);
    EXPECT_EQ(reread.value()[i].t2, read.value()[i].t2);
    EXPECT_TRUE(IsApprox(reread.value()[i].T_1_2, read.value()[i].T_1_2, 0.0, 0.0));
  }
  std::filesystem::remove_all(dir);
}

TEST(RelationsIo, MalformedRelation) {
  const auto dir = testing::MakeTempDir("rel_bad");
  const std::string path = (dir / "r.relations").string();
  std::ofstream(path) << "1 2 0 0 0 0 0 0\n1 2 0 0 0 0 0\n";
  auto read = ReadRelations(path);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().line, 2);
  EXPECT_NE(read.error().message.find("yaw"), std::string::npos) << read.error().message;
  std::ofstream(path) << "1 2 0 0 0 0 0 zz\n";
  read = ReadRelations(path);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.error().message.find("zz"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace gridslam::io
