// The mapper's threads do not change its results (issue 19; compute.threads): a run with one
// thread and a run with two give the same trajectories, graph, closures, joins, events and maps,
// bit for bit, on simulated worlds with one robot and with two robots that must be joined; and
// asking for the online state after every frame (which waits for the worker each time) changes
// nothing either. Also: the key-map cache size does not change the results.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/pipeline/frame_interleaver.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"

namespace gridslam {
namespace {

struct MappedRun {
  pipeline::MapperResult result;
  std::vector<pipeline::MapperEvent> events;
  std::vector<Pose2> poses;  ///< CurrentPose after every frame (when asked).
};

std::vector<std::vector<Frame>> Simulated(const char* world_name, int robots, double duration,
                                          int seed) {
  simulation::SimulationOptions sim;
  sim.robots = robots;
  sim.duration = duration;
  sim.seed = seed;
  auto world = simulation::MakeBuiltinWorld(world_name, sim.resolution);
  EXPECT_TRUE(world.ok());
  auto simulated = simulation::Simulate(world.value(), {}, sim);
  EXPECT_TRUE(simulated.ok()) << simulated.error().ToString();
  std::vector<std::vector<Frame>> logs;
  for (const simulation::RobotRun& run : simulated.value().robots) {
    logs.push_back(run.frames);
  }
  return logs;
}

MappedRun Map(const std::vector<std::vector<Frame>>& logs, int threads, bool ask_every_frame,
              int key_map_cache = 64) {
  SlamOptions options;
  options.compute.threads = threads;
  options.compute.key_map_cache = key_map_cache;
  pipeline::Mapper mapper(options.Mapper(), static_cast<int>(logs.size()));
  MappedRun run;
  std::vector<pipeline::FrameSource> sources;
  for (const std::vector<Frame>& frames : logs) {
    sources.push_back(pipeline::FramesOf(frames));
  }
  EXPECT_TRUE(pipeline::InterleaveFrames(std::move(sources), [&](int robot, const Frame& frame) {
                mapper.AddFrame(robot, frame);
                if (ask_every_frame) {
                  run.poses.push_back(mapper.CurrentPose(robot).value_or(Pose2()));
                  const std::vector<pipeline::MapperEvent> events = mapper.DrainEvents();
                  run.events.insert(run.events.end(), events.begin(), events.end());
                }
              }).ok());
  run.result = mapper.Finish();
  const std::vector<pipeline::MapperEvent> events = mapper.DrainEvents();
  run.events.insert(run.events.end(), events.begin(), events.end());
  return run;
}

bool Same(const Pose2& a, const Pose2& b) {
  return a.x() == b.x() && a.y() == b.y() && a.theta() == b.theta();
}

void ExpectSameMaps(const TiledGrid<float>& a, const TiledGrid<float>& b) {
  ASSERT_EQ(a.Width(), b.Width());
  ASSERT_EQ(a.Height(), b.Height());
  ASSERT_EQ(a.Limits().Origin(), b.Limits().Origin());
  ASSERT_EQ(a.NumAllocatedTiles(), b.NumAllocatedTiles());
  for (int tj = 0; tj < a.TilesY(); ++tj) {
    for (int ti = 0; ti < a.TilesX(); ++ti) {
      const float* ta = a.Tile(ti, tj);
      const float* tb = b.Tile(ti, tj);
      ASSERT_EQ(ta == nullptr, tb == nullptr);
      if (ta != nullptr) {
        ASSERT_EQ(std::memcmp(ta, tb, sizeof(float) * TiledGrid<float>::kTileCells), 0)
            << "tile " << ti << " " << tj;
      }
    }
  }
}

void ExpectSameResults(const MappedRun& a, const MappedRun& b) {
  const pipeline::MapperResult& ra = a.result;
  const pipeline::MapperResult& rb = b.result;
  ASSERT_EQ(ra.trajectories.size(), rb.trajectories.size());
  for (std::size_t r = 0; r < ra.trajectories.size(); ++r) {
    ASSERT_EQ(ra.trajectories[r].size(), rb.trajectories[r].size());
    for (std::size_t k = 0; k < ra.trajectories[r].size(); ++k) {
      ASSERT_EQ(ra.trajectories[r][k].time, rb.trajectories[r][k].time);
      ASSERT_TRUE(Same(ra.trajectories[r][k].T_map_base, rb.trajectories[r][k].T_map_base))
          << "robot " << r << " scan " << k;
    }
  }
  ASSERT_EQ(ra.graph.num_vertices(), rb.graph.num_vertices());
  for (int v = 0; v < static_cast<int>(ra.graph.num_vertices()); ++v) {
    EXPECT_EQ(ra.graph.vertex(v).id, rb.graph.vertex(v).id);
    EXPECT_TRUE(Same(ra.graph.vertex(v).T_map_v, rb.graph.vertex(v).T_map_v)) << "vertex " << v;
  }
  ASSERT_EQ(ra.graph.num_edges(), rb.graph.num_edges());
  for (int e = 0; e < static_cast<int>(ra.graph.num_edges()); ++e) {
    EXPECT_TRUE(Same(ra.graph.edge(e).T_i_j, rb.graph.edge(e).T_i_j)) << "edge " << e;
  }
  ASSERT_EQ(ra.closures.size(), rb.closures.size());
  for (std::size_t c = 0; c < ra.closures.size(); ++c) {
    EXPECT_EQ(ra.closures[c].from, rb.closures[c].from);
    EXPECT_EQ(ra.closures[c].to, rb.closures[c].to);
    EXPECT_EQ(ra.closures[c].outcome, rb.closures[c].outcome);
    EXPECT_TRUE(Same(ra.closures[c].T_from_to, rb.closures[c].T_from_to));
  }
  ASSERT_EQ(ra.joins.size(), rb.joins.size());
  for (std::size_t j = 0; j < ra.joins.size(); ++j) {
    EXPECT_EQ(ra.joins[j].time, rb.joins[j].time);
    EXPECT_EQ(ra.joins[j].vertex_a, rb.joins[j].vertex_a);
    EXPECT_EQ(ra.joins[j].vertex_b, rb.joins[j].vertex_b);
  }
  EXPECT_EQ(ra.component_of_robot, rb.component_of_robot);
  EXPECT_EQ(ra.stats.key_maps, rb.stats.key_maps);
  EXPECT_EQ(ra.stats.accepted, rb.stats.accepted);
  EXPECT_EQ(ra.stats.verified, rb.stats.verified);
  EXPECT_EQ(ra.stats.candidates, rb.stats.candidates);
  EXPECT_EQ(ra.stats.appearance_candidates, rb.stats.appearance_candidates);
  EXPECT_EQ(ra.stats.verification_alignments, rb.stats.verification_alignments);
  EXPECT_EQ(ra.stats.verified_loops, rb.stats.verified_loops);
  EXPECT_EQ(ra.stats.frames, rb.stats.frames);
  EXPECT_EQ(ra.stats.chi2_final, rb.stats.chi2_final);
  ASSERT_EQ(ra.maps.size(), rb.maps.size());
  for (std::size_t c = 0; c < ra.maps.size(); ++c) {
    ExpectSameMaps(ra.maps[c], rb.maps[c]);
  }
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t e = 0; e < a.events.size(); ++e) {
    EXPECT_EQ(a.events[e].kind, b.events[e].kind) << "event " << e;
    EXPECT_EQ(a.events[e].time, b.events[e].time) << "event " << e;
    EXPECT_EQ(a.events[e].vertex, b.events[e].vertex) << "event " << e;
    EXPECT_EQ(a.events[e].other, b.events[e].other) << "event " << e;
  }
}

TEST(MapperThreads, OneRobotSameResultsWithOneAndTwoThreads) {
  const auto logs = Simulated("office", 1, 0.0, 1);
  const MappedRun one = Map(logs, 1, false);
  const MappedRun two = Map(logs, 2, false);
  EXPECT_GT(one.result.stats.accepted, 0);
  ExpectSameResults(one, two);
}

TEST(MapperThreads, AskingAfterEveryFrameChangesNothing) {
  const auto logs = Simulated("office", 1, 300.0, 2);
  const MappedRun one = Map(logs, 1, true);
  const MappedRun two = Map(logs, 2, true);
  ExpectSameResults(one, two);
  ASSERT_EQ(one.poses.size(), two.poses.size());
  for (std::size_t k = 0; k < one.poses.size(); ++k) {
    ASSERT_TRUE(Same(one.poses[k], two.poses[k])) << "frame " << k;
  }
  // Without the questions: the same results (the events then come at the end, the same ones).
  const MappedRun quiet = Map(logs, 2, false);
  ExpectSameResults(two, quiet);
}

TEST(MapperThreads, TwoRobotsJoinTheSameWayWithOneAndTwoThreads) {
  const auto logs = Simulated("office", 2, 0.0, 3);
  const MappedRun one = Map(logs, 1, false);
  const MappedRun two = Map(logs, 2, false);
  EXPECT_EQ(one.result.joins.size(), 1U);
  ExpectSameResults(one, two);
}

TEST(MapperThreads, TheKeyMapCacheSizeChangesNothing) {
  const auto logs = Simulated("office", 1, 0.0, 1);
  const MappedRun large = Map(logs, 1, false, 1000);
  const MappedRun small = Map(logs, 2, false, 1);
  EXPECT_GT(small.result.stats.geometry_recomputed, large.result.stats.geometry_recomputed);
  ExpectSameResults(large, small);
}

}  // namespace
}  // namespace gridslam
