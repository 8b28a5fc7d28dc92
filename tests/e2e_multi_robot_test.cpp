// End to end, several robots (issue 8; docs/design.md §1.9): robots with unknown relative starts
// are mapped together by the Mapper, which must join them into one map by itself (appearance
// search, verified and mutually consistent matches), and the benchmark relations between robots,
// which only a correct join can satisfy, must score about as well as those within each robot. Two
// (400 s) and three (the whole tour) simulated robots in the office world, whose repeated rooms
// and symmetric corridors invite false joins, and the start of the intel log cut into two
// robots by `gridslam split`'s code (log_split.hpp), written as logs and read back.
#include <algorithm>
#include <optional>
#include <ostream>

#include <gtest/gtest.h>

#include "gridslam/eval/relation_metric.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/multi_robot/log_split.hpp"
#include "gridslam/multi_robot/piece_log.hpp"
#include "gridslam/multi_robot/relation_split.hpp"
#include "gridslam/pipeline/frame_interleaver.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam {
namespace {

constexpr Duration kTolerance = std::chrono::milliseconds(1);

/// Maps the robots' frames interleaved by (corrected) time, as `gridslam map` does.
pipeline::MapperResult MapTogether(const std::vector<std::vector<Frame>>& robots) {
  pipeline::Mapper mapper(SlamOptions{}.Mapper(), static_cast<int>(robots.size()));
  std::vector<pipeline::FrameSource> sources;
  for (const std::vector<Frame>& frames : robots) {
    sources.push_back(pipeline::FramesOf(frames));
  }
  EXPECT_TRUE(pipeline::InterleaveFrames(std::move(sources), [&](int robot, const Frame& frame) {
                mapper.AddFrame(robot, frame);
              }).ok());
  return mapper.Finish();
}

struct Scores {
  eval::RelationMetrics within;
  eval::RelationMetrics between;
};

/// Scores the relations on the robots' trajectories of one merged map, each timestamp in the
/// trajectory of the robot `index` gives it.
Scores Score(const pipeline::MapperResult& result, const multi_robot::RobotIndex& index,
             const std::vector<eval::Relation>& within,
             const std::vector<eval::Relation>& between) {
  std::vector<std::vector<eval::StampedPose>> trajectories;
  for (const auto& trajectory : result.trajectories) {
    trajectories.emplace_back();
    for (const pipeline::TrajectoryPose& p : trajectory) {
      trajectories.back().push_back({p.time, p.T_map_base});
    }
  }
  const auto combined = multi_robot::CombineTrajectories(trajectories, index, kTolerance);
  return {eval::EvaluateRelations(within, combined, {}),
          eval::EvaluateRelations(between, combined, {})};
}

double Median(const eval::RelationMetrics& m) {
  std::vector<double> e;
  for (const eval::RelationError& r : m.errors) {
    e.push_back(r.translation);
  }
  std::nth_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2), e.end());
  return e[e.size() / 2];
}

void ExpectOneMap(const pipeline::MapperResult& result) {
  const std::size_t robots = result.trajectories.size();
  EXPECT_EQ(result.joins.size(), robots - 1);
  for (std::size_t r = 0; r < robots; ++r) {
    EXPECT_EQ(result.component_of_robot[r], 0) << "robot " << r << " not joined";
  }
  EXPECT_EQ(result.maps.size(), 1U);
}

struct OfficeRun {
  int robots = 2;
  double duration = 0.0;  ///< 0: the whole tour.
  int seed = 3;
};

void PrintTo(const OfficeRun& run, std::ostream* os) {
  *os << run.robots << " robots, " << run.duration << " s, seed " << run.seed;
}

class SimulatedRobots : public ::testing::TestWithParam<OfficeRun> {};

TEST_P(SimulatedRobots, JoinIntoOneMapWithBetweenErrorsLikeWithin) {
  const OfficeRun run_options = GetParam();
  simulation::SimulationOptions options;
  options.robots = run_options.robots;
  options.duration = run_options.duration;
  options.seed = run_options.seed;
  auto world = simulation::MakeBuiltinWorld("office", options.resolution);
  ASSERT_TRUE(world.ok());
  auto simulated = simulation::Simulate(world.value(), {}, options);
  ASSERT_TRUE(simulated.ok()) << simulated.error().ToString();
  std::vector<std::vector<Frame>> logs;
  std::vector<eval::Relation> within;
  std::vector<std::pair<Time, int>> index;
  for (std::size_t r = 0; r < simulated.value().robots.size(); ++r) {
    const simulation::RobotRun& run = simulated.value().robots[r];
    logs.push_back(run.frames);
    within.insert(within.end(), run.relations.begin(), run.relations.end());
    for (const Frame& f : run.frames) {
      index.emplace_back(f.time, static_cast<int>(r));
    }
  }
  const pipeline::MapperResult result = MapTogether(logs);
  ExpectOneMap(result);
  const Scores s = Score(result, multi_robot::RobotIndex(index), within, simulated.value().between);
  ASSERT_GT(s.between.used, 20);
  EXPECT_EQ(s.between.missing, 0);
  // Unjoined or misjoined robots give errors of metres between them.
  EXPECT_LT(Median(s.between), 2.0 * Median(s.within) + 0.05)
      << "within " << s.within.translation.mean << " m, between " << s.between.translation.mean;
  EXPECT_LT(s.between.translation.mean, 3.0 * s.within.translation.mean + 0.1);
  EXPECT_LT(s.between.rotation_deg.mean, 3.0 * s.within.rotation_deg.mean + 1.0);
}

INSTANTIATE_TEST_SUITE_P(
    Office, SimulatedRobots,
    // Seed 2, three robots: a 180-degree aliasing of two corridors, matched by key maps 4 m
    // apart on both paths, once joined robots 0 and 2 (docs/multi_robot.md).
    ::testing::Values(OfficeRun{2, 400.0, 3}, OfficeRun{3, 0.0, 3}, OfficeRun{3, 0.0, 2}),
    [](const ::testing::TestParamInfo<OfficeRun>& run) {
      return std::to_string(run.param.robots) + "Robots" +
             std::to_string(static_cast<int>(run.param.duration)) + "sSeed" +
             std::to_string(run.param.seed);
    });

TEST(SplitRealLog, PiecesOfIntelMergeBackIntoOneMap) {
  GRIDSLAM_REQUIRE_DATA();
  const auto log = testing::DataDir() / "logs" / "intel.reconstructed.clf";
  auto frames = io::ReadCarmenLog(log.string(), io::CarmenOptions{});
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  frames.value().resize(4000);  // the first ~12 minutes: the lab and its corridors, twice
  auto plan = multi_robot::PlanSplit(frames.value(), 2, 1, multi_robot::SplitOptions{});
  ASSERT_TRUE(plan.ok());
  const auto dir = testing::MakeTempDir("e2e_multi_robot");
  std::vector<std::vector<Frame>> logs;
  std::vector<std::pair<Time, int>> home;
  for (std::size_t i = 0; i < plan.value().pieces.size(); ++i) {
    const std::string path = (dir / ("robot_" + std::to_string(i) + ".clf")).string();
    const auto piece = multi_robot::PieceFrames(frames.value(), plan.value().pieces[i]);
    ASSERT_TRUE(multi_robot::WritePieceLog(path, piece, "e2e").ok());
    auto read = io::ReadCarmenLog(path, io::CarmenOptions{});
    ASSERT_TRUE(read.ok());
    logs.push_back(std::move(read).value());
  }
  for (std::size_t k = 0; k < frames.value().size(); ++k) {
    home.emplace_back(frames.value()[k].time, plan.value().home[k]);
  }
  auto relations =
      io::ReadRelations((testing::DataDir() / "relations" / "intel.relations").string());
  ASSERT_TRUE(relations.ok());
  const multi_robot::RobotIndex index(home);
  const multi_robot::RelationSplit split =
      multi_robot::SplitRelations(relations.value(), index, 2, kTolerance);

  const pipeline::MapperResult result = MapTogether(logs);
  ExpectOneMap(result);
  const Scores s = Score(result, index, split.within, split.between);
  ASSERT_GT(s.between.used, 20);
  ASSERT_GT(s.within.used, 100);
  // intel whole, one robot: about 0.02 m and 0.25 deg.
  EXPECT_LT(s.within.translation.mean, 0.05);
  EXPECT_LT(s.between.translation.mean, 0.05);
  EXPECT_LT(s.between.rotation_deg.mean, 1.0);
  EXPECT_LT(s.between.translation.mean, 2.0 * s.within.translation.mean + 0.01);
}

}  // namespace
}  // namespace gridslam
