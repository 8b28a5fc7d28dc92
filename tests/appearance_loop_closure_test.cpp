// Loop closure without a prior (issue 7; docs/design.md §1.6): a single robot whose estimate is no
// use for finding its loops (the prior-based candidate search is switched off here) must still
// close them through the global appearance search, with no false closure wrecking the map: the
// error of the relations between revisits (at least 30 s apart, where only closed loops help; the
// front end alone is locally near exact in this world) must fall well below that of the same run
// without loop closure, and no relation may get worse on the whole.
#include <cstdio>

#include <gtest/gtest.h>

#include "gridslam/eval/relation_metric.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"

namespace gridslam {
namespace {

struct MapRun {
  eval::RelationMetrics metrics;
  eval::RelationMetrics revisits;  ///< Relations at least 30 s apart: what only loops fix.
  pipeline::MapperStats stats;
};

MapRun Map(const simulation::RobotRun& robot, const SlamOptions& options) {
  pipeline::Mapper mapper(options.Mapper(), 1);
  for (const Frame& frame : robot.frames) {
    mapper.AddFrame(0, frame);
  }
  const pipeline::MapperResult result = mapper.Finish();
  std::vector<eval::StampedPose> trajectory;
  for (const pipeline::TrajectoryPose& p : result.trajectories.front()) {
    trajectory.push_back({p.time, p.T_map_base});
  }
  eval::EvalOptions revisits;
  revisits.min_dt = 30.0;
  return {eval::EvaluateRelations(robot.relations, trajectory, {}),
          eval::EvaluateRelations(robot.relations, trajectory, revisits), mapper.Stats()};
}

TEST(AppearanceLoopClosure, ClosesASingleRobotsLoopsWithoutAPrior) {
  simulation::SimulationOptions sim;
  sim.seed = 3;
  auto world = simulation::MakeBuiltinWorld("office", sim.resolution);
  ASSERT_TRUE(world.ok());
  auto simulated = simulation::Simulate(world.value(), {}, sim);
  ASSERT_TRUE(simulated.ok()) << simulated.error().ToString();
  const simulation::RobotRun& robot = simulated.value().robots.front();

  SlamOptions no_closures;
  no_closures.loop_closure.enabled = false;
  const MapRun open_loop = Map(robot, no_closures);

  // No prior-based candidates at all (a tiny search radius is not enough: key maps sit on the
  // window's cell lattice, so an accurate front end revisits some centres exactly).
  SlamOptions appearance_only;
  appearance_only.loop_closure.max_candidates = 0;
  const MapRun closed = Map(robot, appearance_only);

  EXPECT_EQ(closed.stats.candidates, 0) << "the prior-based search was meant to be off";
  EXPECT_GT(closed.stats.appearance_queries, 10);
  EXPECT_GT(closed.stats.accepted, 5);
  ASSERT_GT(closed.metrics.used, 100);
  ASSERT_GT(closed.revisits.used, 20);
  EXPECT_LT(closed.revisits.translation.mean, 0.5 * open_loop.revisits.translation.mean)
      << "open loop " << open_loop.revisits.translation.mean << " m";
  EXPECT_LT(closed.metrics.translation.mean, open_loop.metrics.translation.mean);
  EXPECT_LT(closed.metrics.rotation_deg.mean, 0.5);  // the front end alone is within 0.1 deg
  std::printf(
      "open loop %.4f m %.3f deg (revisits %.4f m); appearance only %.4f m %.3f deg "
      "(revisits %.4f m), %ld closures\n",
      open_loop.metrics.translation.mean, open_loop.metrics.rotation_deg.mean,
      open_loop.revisits.translation.mean, closed.metrics.translation.mean,
      closed.metrics.rotation_deg.mean, closed.revisits.translation.mean, closed.stats.accepted);
}

}  // namespace
}  // namespace gridslam
