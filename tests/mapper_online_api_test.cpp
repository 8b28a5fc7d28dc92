// The Mapper's online API on a simulated run (docs/online_api.md): the current pose is the
// newest corrected pose, the events account for every key map and loop edge, and a snapshot
// taken at the end shows the walls of the final map.
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"

namespace gridslam {
namespace {

using pipeline::MapperEvent;

TEST(MapperOnlineApi, PoseEventsAndSnapshotsFollowTheMapper) {
  simulation::SimulationOptions sim;
  sim.seed = 1;
  auto world = simulation::MakeBuiltinWorld("office", sim.resolution);
  ASSERT_TRUE(world.ok());
  auto simulated = simulation::Simulate(world.value(), {}, sim);
  ASSERT_TRUE(simulated.ok()) << simulated.error().ToString();
  const std::vector<Frame>& frames = simulated.value().robots.at(0).frames;

  const SlamOptions options;
  pipeline::Mapper mapper(options.Mapper(), 1);
  EXPECT_FALSE(mapper.CurrentPose(0).has_value());
  long key_maps = 0;
  long accepted = 0;
  long snapshots = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    mapper.AddFrame(0, frames[f]);
    for (const MapperEvent& e : mapper.DrainEvents()) {
      key_maps += e.kind == MapperEvent::Kind::kKeyMapAdded ? 1 : 0;
      accepted += e.kind == MapperEvent::Kind::kClosureAccepted ? 1 : 0;
      EXPECT_EQ(e.time, frames[f].time);
    }
    if (f % 400 == 399) {
      const pipeline::MapSnapshot snapshot = mapper.Snapshot();
      ++snapshots;
      ASSERT_EQ(snapshot.trajectories.at(0).size(), f + 1);
      const std::optional<Pose2> pose = mapper.CurrentPose(0);
      ASSERT_TRUE(pose.has_value());
      EXPECT_TRUE(IsApprox(*pose, snapshot.trajectories[0].back().T_map_base, 1e-9, 1e-9));
      EXPECT_TRUE(IsApprox(*pose, mapper.MapToOdom(0) * frames[f].T_odom_base, 1e-9, 1e-9));
      EXPECT_EQ(mapper.MapComponent(0), 0);
    }
  }
  ASSERT_GT(snapshots, 2);
  EXPECT_EQ(key_maps, mapper.Stats().key_maps);
  EXPECT_EQ(accepted, mapper.Stats().accepted);
  EXPECT_GT(accepted, 0);

  const pipeline::MapperResult result = mapper.Finish();
  const pipeline::MapSnapshot last = mapper.Snapshot();
  ASSERT_EQ(last.maps.size(), 1U);
  // The final map's walls are walls of the snapshot too (within a cell).
  const OccupancyImage final_map = fusion::ToOccupancy(result.maps[0], options.fusion);
  const OccupancyImage snapshot_map = fusion::ToOccupancy(last.maps[0], options.fusion);
  long walls = 0;
  long found = 0;
  for (int j = 0; j < final_map.Height(); ++j) {
    for (int i = 0; i < final_map.Width(); ++i) {
      if (final_map(i, j) != kOccupiedCell) {
        continue;
      }
      ++walls;
      const Eigen::Vector2d p = final_map.Limits().CellCenter({i, j});
      bool near = false;
      for (int dj = -1; dj <= 1 && !near; ++dj) {
        for (int di = -1; di <= 1 && !near; ++di) {
          const Eigen::Array2i c = snapshot_map.Limits().CellIndex(p) + Eigen::Array2i(di, dj);
          near = snapshot_map.Limits().Contains(c) && snapshot_map.at(c) == kOccupiedCell;
        }
      }
      found += near ? 1 : 0;
    }
  }
  ASSERT_GT(walls, 1000);
  std::printf("walls of the final map in the snapshot: %ld of %ld\n", found, walls);
  EXPECT_GT(static_cast<double>(found), 0.8 * static_cast<double>(walls));
}

}  // namespace
}  // namespace gridslam
