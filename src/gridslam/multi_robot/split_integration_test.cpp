// Splitting the project's real logs (docs/formats.md §1.5): intel (unpadded and late timestamps,
// repaired by the reader) and fr079 (laser and ODOM out of time order). Each piece, written as
// a log and read back, must give every scan the original odometry moved by the piece's
// transform, with the printed timestamps unchanged, and the benchmark relations must be
// partitioned without loss.
#include <gtest/gtest.h>

#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/multi_robot/log_split.hpp"
#include "gridslam/multi_robot/piece_log.hpp"
#include "gridslam/multi_robot/relation_split.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::multi_robot {
namespace {

class RealLogSplit : public ::testing::TestWithParam<const char*> {};

TEST_P(RealLogSplit, PiecesReadBackAsTheOriginalAndRelationsArePartitioned) {
  GRIDSLAM_REQUIRE_DATA();
  const std::string name = GetParam();
  const auto log = testing::DataDir() / "logs" / (name + ".reconstructed.clf");
  auto frames = io::ReadCarmenLog(log.string(), io::CarmenOptions{});
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  SplitOptions options;
  options.overlap = 20.0;
  auto plan = PlanSplit(frames.value(), 3, 2, options);
  ASSERT_TRUE(plan.ok());
  const auto dir = testing::MakeTempDir("split_" + name);
  std::size_t compared = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const SplitPiece& piece = plan.value().pieces[i];
    const std::string path = (dir / ("robot_" + std::to_string(i) + ".clf")).string();
    ASSERT_TRUE(WritePieceLog(path, PieceFrames(frames.value(), piece), name).ok());
    auto read = io::ReadCarmenLog(path, io::CarmenOptions{});
    ASSERT_TRUE(read.ok()) << read.error().ToString();
    ASSERT_EQ(read.value().size(), piece.end - piece.begin);
    const Pose2 T_old_new = piece.T_new_old.Inverse();
    int bad = 0;
    for (std::size_t k = 0; k < read.value().size(); ++k) {
      const Frame& original = frames.value()[piece.begin + k];
      const Frame& copy = read.value()[k];
      ASSERT_EQ(copy.time, original.time) << path << " scan " << k;
      bad += IsApprox(T_old_new * copy.T_odom_base, original.T_odom_base, 2e-5, 2e-6) ? 0 : 1;
      bad += copy.scan.ranges == original.scan.ranges ? 0 : 1;
      ++compared;
    }
    EXPECT_EQ(bad, 0) << path;
  }
  EXPECT_GT(compared, frames.value().size());  // the overlaps were compared twice

  auto relations =
      io::ReadRelations((testing::DataDir() / "relations" / (name + ".relations")).string());
  ASSERT_TRUE(relations.ok());
  std::vector<std::pair<Time, int>> home;
  for (std::size_t k = 0; k < frames.value().size(); ++k) {
    home.emplace_back(frames.value()[k].time, plan.value().home[k]);
  }
  const RelationSplit split =
      SplitRelations(relations.value(), RobotIndex(home), 3, std::chrono::milliseconds(1));
  EXPECT_EQ(split.unmatched, 0);
  EXPECT_EQ(split.within.size() + split.between.size(), relations.value().size());
  EXPECT_GT(split.between.size(), 10U);
  std::size_t per_robot = 0;
  for (const auto& r : split.per_robot) {
    EXPECT_GT(r.size(), 10U);
    per_robot += r.size();
  }
  EXPECT_EQ(per_robot, split.within.size());
}

INSTANTIATE_TEST_SUITE_P(Logs, RealLogSplit, ::testing::Values("intel", "fr079"));

}  // namespace
}  // namespace gridslam::multi_robot
