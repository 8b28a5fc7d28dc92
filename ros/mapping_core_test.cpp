// The node's mapping core without ROS (mapping_core.hpp, frame_builder.hpp): frames as the bag
// reader builds them, topic odometry interpolated and waited for, every scan mapped in order
// exactly as the batch mapper maps the same frames, snapshots reported as maps, and Finish writing
// what `gridslam map` writes.
#include "mapping_core.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gridslam/io/map_io.hpp"
#include "gridslam/io/trajectory_io.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"

#include "frame_builder.hpp"
#include <unistd.h>

namespace gridslam::live {
namespace {

namespace fs = std::filesystem;

Transform3D ToTransform(const Pose2& pose) {
  Transform3D T;
  T.x = pose.x();
  T.y = pose.y();
  T.qz = std::sin(0.5 * pose.theta());
  T.qw = std::cos(0.5 * pose.theta());
  return T;
}

ScanInput ToInput(const Frame& frame) {
  ScanInput in;
  in.stamp_ns = frame.time.time_since_epoch().count();
  in.angle_min = static_cast<float>(frame.scan.angle_min);
  in.angle_increment = static_cast<float>(frame.scan.angle_increment);
  in.range_min = static_cast<float>(frame.scan.range_min);
  in.range_max = static_cast<float>(frame.scan.range_max);
  in.ranges = frame.scan.ranges;
  in.T_base_laser = ToTransform(frame.T_base_laser);
  return in;
}

std::vector<Frame> SimulatedFrames(double duration) {
  simulation::SimulationOptions sim;
  sim.seed = 1;
  sim.duration = duration;
  auto world = simulation::MakeBuiltinWorld("office", sim.resolution);
  EXPECT_TRUE(world.ok());
  auto simulated = simulation::Simulate(world.value(), {}, sim);
  EXPECT_TRUE(simulated.ok()) << simulated.error().ToString();
  return simulated.value().robots.at(0).frames;
}

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("gridslam_mapping_core_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

// Waits (up to 60 s) until `done` holds.
template <typename F>
bool WaitFor(F done) {
  for (int i = 0; i < 6000 && !done(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return done();
}

TEST(FrameBuilder, BuildsFramesAsTheBagReader) {
  io::CarmenOptions log;
  log.max_usable_range = 20.0;
  FrameBuilder tf(log, OdometrySource::kTf);
  ScanInput scan;
  scan.stamp_ns = 1'000'000'000;
  scan.angle_min = -1.0F;
  scan.angle_increment = 0.5F;
  scan.range_min = -1.0F;
  scan.range_max = 30.0F;
  scan.ranges = {1.0F, 2.0F, 25.0F};
  scan.T_base_laser = ToTransform(Pose2(0.2, 0.0, 0.1));
  bool clamped = true;
  EXPECT_FALSE(tf.Covers(scan.stamp_ns));
  EXPECT_FALSE(tf.Build(scan, &clamped).ok());  // before the first odometry sample
  tf.AddOdometry({scan.stamp_ns, ToTransform(Pose2(1.0, 2.0, 0.5)), std::nullopt});
  EXPECT_TRUE(tf.Covers(scan.stamp_ns));
  auto frame = tf.Build(scan, &clamped);
  ASSERT_TRUE(frame.ok()) << frame.error().ToString();
  EXPECT_FALSE(clamped);
  EXPECT_EQ(frame.value().time.time_since_epoch().count(), scan.stamp_ns);
  EXPECT_EQ(frame.value().corrected_time, frame.value().time);
  EXPECT_TRUE(frame.value().has_odometry);
  EXPECT_TRUE(IsApprox(frame.value().T_odom_base, Pose2(1.0, 2.0, 0.5), 1e-12, 1e-12));
  EXPECT_TRUE(IsApprox(frame.value().T_base_laser, Pose2(0.2, 0.0, 0.1), 1e-12, 1e-12));
  EXPECT_DOUBLE_EQ(frame.value().scan.range_max, 20.0);  // capped at log.max_usable_range
  EXPECT_DOUBLE_EQ(frame.value().scan.range_min, 0.0);
  EXPECT_FALSE(frame.value().scan.IsHit(2));

  log.laser_offset = {0.5, 0.0, 0.0};  // the YAML's mounting wins over TF
  FrameBuilder none(log, OdometrySource::kNone);
  frame = none.Build(scan, &clamped);
  ASSERT_TRUE(frame.ok());
  EXPECT_FALSE(frame.value().has_odometry);
  EXPECT_TRUE(IsApprox(frame.value().T_base_laser, Pose2(0.5, 0.0, 0.0), 1e-12, 1e-12));
  scan.ranges.clear();
  EXPECT_FALSE(none.Build(scan, &clamped).ok());  // no beams
}

// TF odometry ending in an intermediate frame (odom -> base_footprint), completed by the fixed
// base_footprint -> base_link, as the bag reader completes it.
TEST(FrameBuilder, CompletesOdometryThroughAFixedTransform) {
  FrameBuilder tf(io::CarmenOptions{}, OdometrySource::kTf);
  const Pose2 T_odom_footprint(1.0, 2.0, 0.5);
  const Pose2 T_footprint_base(0.1, 0.0, 0.2);
  tf.AddOdometry({1000, ToTransform(T_odom_footprint), ToTransform(T_footprint_base)});
  ScanInput scan;
  scan.stamp_ns = 1000;
  scan.angle_min = -1.0F;
  scan.angle_increment = 0.5F;
  scan.range_max = 30.0F;
  scan.ranges = {1.0F, 2.0F};
  bool clamped = true;
  auto frame = tf.Build(scan, &clamped);
  ASSERT_TRUE(frame.ok());
  EXPECT_FALSE(clamped);
  EXPECT_TRUE(
      IsApprox(frame.value().T_odom_base, T_odom_footprint * T_footprint_base, 1e-12, 1e-12));
}

TEST(FrameBuilder, InterpolatesTopicOdometryAtTheScanStamp) {
  FrameBuilder topic(io::CarmenOptions{}, OdometrySource::kTopic);
  ScanInput scan;
  scan.stamp_ns = 1'500'000'000;
  scan.angle_min = -1.0F;
  scan.angle_increment = 0.5F;
  scan.range_max = 30.0F;
  scan.ranges = {1.0F, 2.0F};
  bool clamped = false;
  EXPECT_FALSE(topic.Covers(scan.stamp_ns));
  EXPECT_FALSE(topic.Build(scan, &clamped).ok());  // before the first odometry sample
  topic.AddOdometry({2'000'000'000, ToTransform(Pose2(2.0, 0.0, 0.4)), std::nullopt});
  topic.AddOdometry({1'000'000'000, ToTransform(Pose2(1.0, 0.0, 0.2)), std::nullopt});  // late
  EXPECT_TRUE(topic.Covers(scan.stamp_ns));
  auto frame = topic.Build(scan, &clamped);
  ASSERT_TRUE(frame.ok());
  EXPECT_FALSE(clamped);
  EXPECT_TRUE(IsApprox(frame.value().T_odom_base, Pose2(1.5, 0.0, 0.3), 1e-9, 1e-9));
  scan.stamp_ns = 2'500'000'000;
  EXPECT_FALSE(topic.Covers(scan.stamp_ns));
  frame = topic.Build(scan, &clamped);
  ASSERT_TRUE(frame.ok());
  EXPECT_TRUE(clamped);  // after the newest sample: the newest
  EXPECT_TRUE(IsApprox(frame.value().T_odom_base, Pose2(2.0, 0.0, 0.4), 1e-9, 1e-9));
}

TEST(MappingCore, BadConfigurationIsAnError) {
  std::string error;
  CoreSettings settings;
  settings.config_path = "/nonexistent/gridslam.yaml";
  EXPECT_EQ(MappingCore::Create(settings, {}, &error), nullptr);
  EXPECT_NE(error.find("/nonexistent/gridslam.yaml"), std::string::npos) << error;
  settings.config_path.clear();
  settings.overrides = {"fusion.resolution=-1"};
  EXPECT_EQ(MappingCore::Create(settings, {}, &error), nullptr);
  EXPECT_NE(error.find("fusion.resolution"), std::string::npos) << error;
  settings.overrides = {"fusion.no_such_option=1"};
  EXPECT_EQ(MappingCore::Create(settings, {}, &error), nullptr);
  EXPECT_NE(error.find("no_such_option"), std::string::npos) << error;
}

// The core maps every scan in order, as the batch mapper maps the same frames: the same final
// trajectory; it reports a pose per scan, maps on the way, and writes the outputs.
TEST(MappingCore, MapsLikeTheBatchMapperAndWritesTheSessionOutputs) {
  const std::vector<Frame> simulated = SimulatedFrames(240.0);
  ASSERT_GT(simulated.size(), 1000U);
  const SlamOptions options;

  // The batch mapper on the frames the core builds from the same inputs (an odometry sample at
  // each scan's stamp).
  const auto odometry = [](const Frame& f) {
    return OdometryInput{f.time.time_since_epoch().count(), ToTransform(f.T_odom_base),
                         std::nullopt};
  };
  FrameBuilder builder(options.log, OdometrySource::kTf);
  pipeline::Mapper batch(options.Mapper(), 1);
  for (const Frame& f : simulated) {
    bool clamped = false;
    builder.AddOdometry(odometry(f));
    batch.AddFrame(0, builder.Build(ToInput(f), &clamped).value());
  }
  const pipeline::MapperResult expected = batch.Finish();

  std::mutex mutex;
  long poses = 0;
  std::vector<long> map_sizes;
  PlanarPose last_pose;
  CoreCallbacks callbacks;
  callbacks.on_pose = [&](std::int64_t /*stamp*/, const PlanarPose& pose) {
    const std::lock_guard<std::mutex> lock(mutex);
    ++poses;
    last_pose = pose;
  };
  callbacks.on_map = [&](const GridOutput& map, const std::vector<StampedPose>& path) {
    const std::lock_guard<std::mutex> lock(mutex);
    EXPECT_EQ(map.cells.size(),
              static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height));
    EXPECT_FALSE(path.empty());
    map_sizes.push_back(static_cast<long>(path.size()));
  };
  CoreSettings settings;
  settings.map_publish_period = 30.0;
  std::string error;
  auto core = MappingCore::Create(settings, callbacks, &error);
  ASSERT_NE(core, nullptr) << error;
  PlanarPose pose;
  EXPECT_FALSE(core->LatestPose(&pose));
  const fs::path dir = TempDir("session");
  std::string message;
  EXPECT_FALSE(core->SaveMap(dir.string(), &message));  // nothing mapped yet
  for (const Frame& f : simulated) {
    core->AddOdometry(odometry(f));
    core->AddScan(ToInput(f));
  }
  ASSERT_TRUE(WaitFor(
      [&] { return core->Progress().scans_mapped == static_cast<long>(simulated.size()); }));
  EXPECT_TRUE(core->LatestPose(&pose));
  ASSERT_TRUE(core->SaveMap(dir.string(), &message)) << message;
  auto saved = io::ReadMap((dir / "map.yaml").string());
  ASSERT_TRUE(saved.ok()) << saved.error().ToString();
  EXPECT_GT(saved.value().size(), 0U);

  ASSERT_TRUE(core->Finish(dir.string(), &message)) << message;
  const CoreProgress status = core->Progress();
  EXPECT_TRUE(status.finished);
  EXPECT_EQ(status.scans_received, static_cast<long>(simulated.size()));
  EXPECT_EQ(status.scans_dropped, 0);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    EXPECT_EQ(poses, static_cast<long>(simulated.size()));
    // 240 s at one map per 30 s of scan time (once the first key map is done), plus the final.
    EXPECT_GE(map_sizes.size(), 6U);
    EXPECT_EQ(map_sizes.back(), static_cast<long>(simulated.size()));
  }
  for (const char* name : {"map.pgm", "map.yaml", "map.png", "map_graph.png", "trajectory.txt",
                           "trajectory.tum", "graph.g2o", "config.yaml", "report.json"}) {
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  }
  auto trajectory = io::ReadTrajectory((dir / "trajectory.txt").string());
  ASSERT_TRUE(trajectory.ok()) << trajectory.error().ToString();
  ASSERT_EQ(trajectory.value().size(), expected.trajectories[0].size());
  for (std::size_t k = 0; k < trajectory.value().size(); ++k) {
    ASSERT_EQ(trajectory.value()[k].time, expected.trajectories[0][k].time) << k;
    ASSERT_TRUE(
        IsApprox(trajectory.value()[k].pose, expected.trajectories[0][k].T_map_base, 1e-5, 1e-5))
        << k;  // the file's precision
  }
  std::ifstream in(dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["frames"], static_cast<long>(simulated.size()));
  EXPECT_EQ(report["key_maps"], expected.stats.key_maps);
  EXPECT_EQ(report["closures"]["accepted"], expected.stats.accepted);
  EXPECT_EQ(report["node"]["odometry"], "tf");
  EXPECT_EQ(report["logs"][0]["log"], "gridslam_node");
  EXPECT_TRUE(report.contains("quality"));

  // After Finish: later scans are ignored, a second Finish writes the same result again.
  core->AddScan(ToInput(simulated.back()));
  EXPECT_EQ(core->Progress().scans_dropped, 1);
  EXPECT_TRUE(core->Finish(dir.string(), &message)) << message;
  fs::remove_all(dir);
}

// Topic odometry: a scan waits for a sample at or after its stamp, at most odom_wait; then it is
// mapped with the nearest sample (counted as clamped).
TEST(MappingCore, TopicOdometryWaitsForALaterSample) {
  const std::vector<Frame> simulated = SimulatedFrames(20.0);
  ASSERT_GT(simulated.size(), 20U);
  CoreSettings settings;
  settings.odometry = OdometrySource::kTopic;
  settings.odom_wait = 30.0;
  std::string error;
  auto core = MappingCore::Create(settings, {}, &error);
  ASSERT_NE(core, nullptr) << error;
  const auto odometry = [&](std::size_t k) {
    core->AddOdometry({simulated[k].time.time_since_epoch().count(),
                       ToTransform(simulated[k].T_odom_base), std::nullopt});
  };
  odometry(0);
  odometry(1);
  core->AddScan(ToInput(simulated[1]));
  core->AddScan(ToInput(simulated[2]));
  ASSERT_TRUE(WaitFor([&] { return core->Progress().scans_mapped == 1; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(core->Progress().scans_mapped, 1);  // the second waits for its odometry
  EXPECT_EQ(core->Progress().scans_queued, 1);
  odometry(3);
  ASSERT_TRUE(WaitFor([&] { return core->Progress().scans_mapped == 2; }));
  EXPECT_EQ(core->Progress().scans_without_odometry, 0);

  CoreSettings quick = settings;
  quick.odom_wait = 0.1;
  auto impatient = MappingCore::Create(quick, {}, &error);
  ASSERT_NE(impatient, nullptr) << error;
  impatient->AddOdometry({simulated[0].time.time_since_epoch().count(),
                          ToTransform(simulated[0].T_odom_base), std::nullopt});
  impatient->AddScan(ToInput(simulated[1]));
  ASSERT_TRUE(WaitFor([&] { return impatient->Progress().scans_mapped == 1; }));
  EXPECT_EQ(impatient->Progress().scans_without_odometry, 1);
  EXPECT_EQ(impatient->Progress().scans_received, 1);
}

}  // namespace
}  // namespace gridslam::live
