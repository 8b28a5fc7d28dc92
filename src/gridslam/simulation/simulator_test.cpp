#include "gridslam/simulation/simulator.hpp"

#include <set>

#include <gtest/gtest.h>

#include "gridslam/eval/relation_metric.hpp"

namespace gridslam::simulation {
namespace {

std::vector<eval::StampedPose> TruthOf(const RobotRun& run) {
  std::vector<eval::StampedPose> poses;
  for (const Frame& f : run.frames) {
    poses.push_back({f.time, *f.T_world_base_true});
  }
  return poses;
}

std::vector<eval::StampedPose> OdometryOf(const RobotRun& run) {
  std::vector<eval::StampedPose> poses;
  for (const Frame& f : run.frames) {
    poses.push_back({f.time, f.T_odom_base});
  }
  return poses;
}

SimulationOptions ShortRun(double duration = 240.0) {
  SimulationOptions options;
  options.duration = duration;
  options.relations.revisit_min_gap = 20.0;
  return options;
}

const World& Office() {
  static const World world = MakeBuiltinWorld("office", 0.05).value();
  return world;
}

TEST(SimulatorTest, GroundTruthScoresZeroAgainstItsRelations) {
  // The office tour passes its start again after about 7 minutes: 500 s include revisits.
  const auto result = Simulate(Office(), {}, ShortRun(500.0));
  ASSERT_TRUE(result.ok()) << result.error().ToString();
  const RobotRun& run = result.value().robots.at(0);
  ASSERT_GT(run.relations.size(), 100U);
  long revisits = 0;
  for (const auto& r : run.relations) {
    revisits += ToSeconds(r.t2 - r.t1) >= 20.0 ? 1 : 0;
  }
  EXPECT_GT(revisits, 5);
  const auto metrics = eval::EvaluateRelations(run.relations, TruthOf(run), eval::EvalOptions{});
  EXPECT_EQ(metrics.used, static_cast<long>(run.relations.size()));
  EXPECT_EQ(metrics.missing, 0);
  EXPECT_LT(metrics.translation.mean, 1e-9);
  EXPECT_LT(metrics.rotation_deg.mean, 1e-9);
}

TEST(SimulatorTest, OdometryErrorIsClearlyNonZeroAndGrowsWithTheNoise) {
  std::vector<double> errors;
  for (const double scale : {1.0, 2.0, 4.0}) {
    SimulationOptions options = ShortRun();
    options.odometry.translation_noise *= scale;
    options.odometry.lateral_noise *= scale;
    options.odometry.rotation_noise_per_meter *= scale;
    options.odometry.rotation_noise_per_radian *= scale;
    const auto result = Simulate(Office(), {}, options);
    ASSERT_TRUE(result.ok()) << result.error().ToString();
    const RobotRun& run = result.value().robots.at(0);
    const auto metrics =
        eval::EvaluateRelations(run.relations, OdometryOf(run), eval::EvalOptions{});
    EXPECT_EQ(metrics.missing, 0);
    errors.push_back(metrics.translation.mean);
  }
  EXPECT_GT(errors[0], 0.005);
  EXPECT_GT(errors[1], 1.5 * errors[0]);
  EXPECT_GT(errors[2], 1.5 * errors[1]);
}

TEST(SimulatorTest, BiasAloneMakesASystematicError) {
  SimulationOptions options = ShortRun(120.0);
  options.odometry = OdometryNoiseOptions{0, 0, 0, 0, 0.05, 0.0, 0.0};
  const auto result = Simulate(Office(), {}, options);
  ASSERT_TRUE(result.ok());
  const RobotRun& run = result.value().robots.at(0);
  // With a 5 % scale error and no rotation error, the odometry path is the true path scaled.
  const Pose2 T_world_odom = run.T_world_odom;
  for (const Frame& f : run.frames) {
    const Eigen::Vector2d true_in_odom =
        (T_world_odom.Inverse() * *f.T_world_base_true).translation();
    EXPECT_NEAR((f.T_odom_base.translation() - 1.05 * true_in_odom).norm(), 0.0, 1e-6);
  }
}

TEST(SimulatorTest, SameSeedSameOutputDifferentSeedDifferent) {
  const auto a = Simulate(Office(), {}, ShortRun(60.0));
  const auto b = Simulate(Office(), {}, ShortRun(60.0));
  SimulationOptions other = ShortRun(60.0);
  other.seed = 2;
  const auto c = Simulate(Office(), {}, other);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  const auto& fa = a.value().robots[0].frames;
  const auto& fb = b.value().robots[0].frames;
  const auto& fc = c.value().robots[0].frames;
  ASSERT_EQ(fa.size(), fb.size());
  bool any_difference = false;
  for (std::size_t k = 0; k < fa.size(); ++k) {
    EXPECT_EQ(fa[k].time, fb[k].time);
    EXPECT_EQ(fa[k].scan.ranges, fb[k].scan.ranges);
    EXPECT_TRUE(IsApprox(fa[k].T_odom_base, fb[k].T_odom_base, 0.0, 0.0));
    any_difference = any_difference || fa[k].scan.ranges != fc[k].scan.ranges;
  }
  EXPECT_TRUE(any_difference);
}

TEST(SimulatorTest, SeveralRobotsStartApartNeverShareATimestampAndMeet) {
  SimulationOptions options = ShortRun(200.0);
  options.robots = 3;
  const auto result = Simulate(Office(), {}, options);
  ASSERT_TRUE(result.ok()) << result.error().ToString();
  const auto& robots = result.value().robots;
  ASSERT_EQ(robots.size(), 3U);
  std::set<Time> times;
  std::vector<eval::StampedPose> all_truth;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    EXPECT_TRUE(IsApprox(robots[i].frames.front().T_odom_base, Pose2()));
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GT(
          (robots[i].T_world_odom.translation() - robots[j].T_world_odom.translation()).norm(),
          5.0);
    }
    for (const Frame& f : robots[i].frames) {
      // No two scans of different robots within the evaluation tolerance.
      const auto near = times.lower_bound(f.time - std::chrono::milliseconds(2));
      EXPECT_TRUE(near == times.end() || *near > f.time + std::chrono::milliseconds(2));
      times.insert(f.time);
    }
    const auto truth = TruthOf(robots[i]);
    all_truth.insert(all_truth.end(), truth.begin(), truth.end());
  }
  const auto& between = result.value().between;
  ASSERT_GT(between.size(), 10U);
  auto robot_of = [&](Time t) {
    for (std::size_t i = 0; i < robots.size(); ++i) {
      for (const Frame& f : robots[i].frames) {
        if (f.time == t) {
          return static_cast<int>(i);
        }
      }
    }
    return -1;
  };
  for (std::size_t k = 0; k < between.size(); k += 7) {
    const int r1 = robot_of(between[k].t1);
    const int r2 = robot_of(between[k].t2);
    EXPECT_GE(r1, 0);
    EXPECT_GE(r2, 0);
    EXPECT_NE(r1, r2);
  }
  const auto metrics = eval::EvaluateRelations(between, all_truth, eval::EvalOptions{});
  EXPECT_EQ(metrics.used, static_cast<long>(between.size()));
  EXPECT_LT(metrics.translation.mean, 1e-9);
}

TEST(SimulatorTest, RouteThroughAWallIsRejected) {
  const World& world = Office();
  // From the south corridor straight north through the offices' walls.
  const std::vector<Eigen::Vector2d> route = {{8.0, 2.2}, {8.0, 13.6}, {2.2, 13.6}, {2.2, 2.2}};
  const auto result = Simulate(world, route, ShortRun(60.0));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(result.error().message.find("wall"), std::string::npos);
}

TEST(SimulatorTest, WorldWithoutRouteNeedsAWaypointsFile) {
  WorldBuilder builder(10.0, 10.0, 0.05);
  builder.Carve(1.0, 1.0, 9.0, 9.0);
  const auto result = Simulate(builder.Build("box", {}), {}, ShortRun(10.0));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidInput);
}

}  // namespace
}  // namespace gridslam::simulation
