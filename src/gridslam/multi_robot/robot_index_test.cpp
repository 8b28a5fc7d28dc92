#include "gridslam/multi_robot/robot_index.hpp"

#include <gtest/gtest.h>

#include "gridslam/eval/relation_metric.hpp"
#include "gridslam/multi_robot/relation_split.hpp"

namespace gridslam::multi_robot {
namespace {

Time At(double seconds) { return FromSeconds(1000.0 + seconds); }
constexpr Duration kTolerance = std::chrono::milliseconds(1);

TEST(RobotIndex, NearestTimeWithinTolerance) {
  const RobotIndex index({{At(2.0), 1}, {At(1.0), 0}, {At(3.0), 2}, {At(2.0), 2}});
  EXPECT_EQ(index.size(), 3U);  // the repeated 2.0 keeps its first robot
  EXPECT_EQ(index.RobotAt(At(1.0), kTolerance), 0);
  EXPECT_EQ(index.RobotAt(At(2.0), kTolerance), 1);
  EXPECT_EQ(index.RobotAt(At(2.0005), kTolerance), 1);
  EXPECT_EQ(index.RobotAt(At(2.9995), kTolerance), 2);
  EXPECT_FALSE(index.RobotAt(At(2.5), kTolerance).has_value());
  EXPECT_FALSE(index.RobotAt(At(0.0), kTolerance).has_value());
  EXPECT_FALSE(index.RobotAt(At(4.0), kTolerance).has_value());
  EXPECT_FALSE(RobotIndex().RobotAt(At(1.0), kTolerance).has_value());
}

/// A robot driving a straight line in the world, with scans at `times`.
std::vector<eval::StampedPose> Truth(const std::vector<double>& times) {
  std::vector<eval::StampedPose> poses;
  for (const double t : times) {
    poses.push_back({At(t), Pose2(0.5 * t, 0.1 * t * t, 0.05 * t)});
  }
  return poses;
}

TEST(CombineTrajectories, ScoresRelationsWithinAndBetweenRobots) {
  // One robot's true path, cut into two robots: 0..4 s and 5..9 s.
  const std::vector<eval::StampedPose> truth = Truth({0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  const std::vector<eval::StampedPose> a(truth.begin(), truth.begin() + 5);
  std::vector<eval::StampedPose> b(truth.begin() + 5, truth.end());
  std::vector<eval::Relation> relations;
  for (int i = 0; i + 3 < 10; ++i) {
    relations.push_back({truth[static_cast<std::size_t>(i)].time,
                         truth[static_cast<std::size_t>(i + 3)].time,
                         Between(truth[static_cast<std::size_t>(i)].pose,
                                 truth[static_cast<std::size_t>(i + 3)].pose)});
  }
  std::vector<std::pair<Time, int>> entries;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    entries.emplace_back(truth[k].time, k < 5 ? 0 : 1);
  }
  const RobotIndex index(entries);
  const RelationSplit split = SplitRelations(relations, index, 2, kTolerance);
  ASSERT_EQ(split.within.size(), 4U);   // 0-3, 1-4 in robot 0; 5-8, 6-9 in robot 1
  ASSERT_EQ(split.between.size(), 3U);  // 2-5, 3-6, 4-7

  eval::EvalOptions options;
  // Both robots in one correct frame: every relation scores zero.
  const auto exact = eval::EvaluateRelations(
      split.between, CombineTrajectories({a, b}, index, kTolerance), options);
  EXPECT_EQ(exact.used, 3);
  EXPECT_NEAR(exact.translation.mean, 0.0, 1e-9);
  // Robot 1 misplaced by a rigid transform: within-robot relations still score zero, relations
  // between the robots do not.
  for (eval::StampedPose& p : b) {
    p.pose = Pose2(0.3, -0.2, 0.1) * p.pose;
  }
  const auto combined = CombineTrajectories({a, b}, index, kTolerance);
  const auto within = eval::EvaluateRelations(split.within, combined, options);
  const auto between = eval::EvaluateRelations(split.between, combined, options);
  EXPECT_EQ(within.used, 4);
  EXPECT_NEAR(within.translation.mean, 0.0, 1e-9);
  EXPECT_EQ(between.used, 3);
  EXPECT_GT(between.translation.mean, 0.1);
}

TEST(CombineTrajectories, SharedTimesGoToTheIndexedOrFirstRobot) {
  const std::vector<eval::StampedPose> a = Truth({0, 1, 2, 3});
  std::vector<eval::StampedPose> b = Truth({2, 3, 4, 5});  // overlap at 2 and 3
  for (eval::StampedPose& p : b) {
    p.pose = Pose2(5.0, 0.0, 0.0) * p.pose;  // a different pose for the same time
  }
  CombineStats stats;
  auto combined = CombineTrajectories({a, b}, RobotIndex(), kTolerance, &stats);
  EXPECT_EQ(stats.poses, 8);
  EXPECT_EQ(stats.shared_times, 2);
  EXPECT_EQ(stats.dropped, 0);
  const eval::Relation r{At(2.0), At(3.0), Between(a[2].pose, a[3].pose)};
  EXPECT_NEAR(eval::EvaluateRelations({r}, combined, {}).translation.mean, 0.0, 1e-9);

  // The index gives time 2 to robot 1 (b's pose) and time 3 to robot 0 (a's).
  const RobotIndex index({{At(0), 0}, {At(1), 0}, {At(2), 1}, {At(3), 0}, {At(4), 1}, {At(5), 1}});
  combined = CombineTrajectories({a, b}, index, kTolerance, &stats);
  EXPECT_EQ(stats.poses, 6);
  EXPECT_EQ(stats.dropped, 2);
  EXPECT_EQ(stats.shared_times, 0);
  const eval::Relation mixed{At(2.0), At(3.0), Between(b[0].pose, a[3].pose)};
  EXPECT_NEAR(eval::EvaluateRelations({mixed}, combined, {}).translation.mean, 0.0, 1e-9);
}

TEST(SplitRelations, UnknownTimestampsAreCountedNotGuessed) {
  const RobotIndex index({{At(0), 0}, {At(1), 0}, {At(2), 1}});
  const std::vector<eval::Relation> relations = {{At(0), At(1), Pose2()},
                                                 {At(1), At(2), Pose2()},
                                                 {At(2), At(7), Pose2()},
                                                 {At(2), At(2.0004), Pose2()}};
  const RelationSplit split = SplitRelations(relations, index, 3, kTolerance);
  EXPECT_EQ(split.within.size(), 2U);
  EXPECT_EQ(split.between.size(), 1U);
  EXPECT_EQ(split.unmatched, 1);
  ASSERT_EQ(split.per_robot.size(), 3U);
  EXPECT_EQ(split.per_robot[0].size(), 1U);
  EXPECT_EQ(split.per_robot[1].size(), 1U);
  EXPECT_TRUE(split.per_robot[2].empty());
}

}  // namespace
}  // namespace gridslam::multi_robot
