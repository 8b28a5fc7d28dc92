// The project's four real logs (docs/formats.md §1.5) read with the right scan counts, beam counts
// and angles; relation timestamps match scan timestamps exactly; intel's timestamp repair lowers
// the odometry error on short relations.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "gridslam/eval/relation_metric.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

std::string Log(const std::string& name) { return (testing::DataDir() / "logs" / name).string(); }
std::string Relations(const std::string& name) {
  return (testing::DataDir() / "relations" / name).string();
}

std::vector<Frame> Read(const std::string& name, CarmenStats* stats = nullptr,
                        CarmenOptions options = {}) {
  auto frames = ReadCarmenLog(Log(name), options, stats);
  EXPECT_TRUE(frames.ok()) << (frames.ok() ? "" : frames.error().ToString());
  return frames.ok() ? std::move(frames.value()) : std::vector<Frame>{};
}

void ExpectGeometry(const std::vector<Frame>& frames, std::size_t beams, double min_deg,
                    double step_deg) {
  for (const Frame& f : frames) {
    ASSERT_EQ(f.scan.size(), beams);
    ASSERT_NEAR(RadToDeg(f.scan.angle_min), min_deg, 1e-4);
    ASSERT_NEAR(RadToDeg(f.scan.angle_increment), step_deg, 1e-4);
  }
}

/// Every relation timestamp is the printed timestamp of a scan.
void ExpectRelationTimesMatch(const std::vector<Frame>& frames, const std::string& relations) {
  auto rel = ReadRelations(Relations(relations));
  ASSERT_TRUE(rel.ok());
  std::set<Time> times;
  for (const Frame& f : frames) {
    times.insert(f.time);
  }
  long missing = 0;
  for (const auto& r : rel.value()) {
    missing += (times.count(r.t1) == 0) + (times.count(r.t2) == 0);
  }
  EXPECT_EQ(missing, 0);
}

eval::RelationMetrics OdometryMetrics(const std::vector<Frame>& frames, const std::string& rel,
                                      double max_dt) {
  std::vector<eval::StampedPose> traj;
  for (const Frame& f : frames) {
    traj.push_back({f.time, f.T_odom_base});
  }
  eval::EvalOptions options;
  options.max_dt = max_dt;
  return eval::EvaluateRelations(ReadRelations(Relations(rel)).value(), traj, options);
}

TEST(CarmenIntegration, Intel) {
  GRIDSLAM_REQUIRE_DATA();
  CarmenStats stats;
  const auto frames = Read("intel.reconstructed.clf", &stats);
  ASSERT_EQ(frames.size(), 13631U);
  EXPECT_EQ(stats.odometry, 26915);
  ExpectGeometry(frames, 180, -90.0, 1.0);
  ExpectRelationTimesMatch(frames, "intel.relations");
  // About a tenth of all times were printed unpadded; repairing them improves odometry.
  EXPECT_GT(stats.repaired_timestamps, 3000);
  const auto repaired = OdometryMetrics(frames, "intel.relations", 5.0);
  CarmenOptions raw_options;
  raw_options.repair_timestamps = false;
  const auto raw = OdometryMetrics(Read("intel.reconstructed.clf", nullptr, raw_options),
                                   "intel.relations", 5.0);
  EXPECT_EQ(repaired.used, raw.used);
  EXPECT_LT(repaired.translation.mean, raw.translation.mean - 0.005);
  EXPECT_LT(repaired.rotation_deg.mean, raw.rotation_deg.mean - 0.1);
  for (const Frame& f : frames) {
    ASSERT_EQ(f.scan.range_max, 80.0);
  }
}

TEST(CarmenIntegration, Fr079) {
  GRIDSLAM_REQUIRE_DATA();
  CarmenStats stats;
  const auto frames = Read("fr079.reconstructed.clf", &stats);
  ASSERT_EQ(frames.size(), 4934U);
  EXPECT_EQ(stats.repaired_timestamps, 0);  // padded times: nothing to repair
  ExpectGeometry(frames, 360, -90.0, 0.5);
  ExpectRelationTimesMatch(frames, "fr079.relations");
}

TEST(CarmenIntegration, FrClinicInterleaved) {
  GRIDSLAM_REQUIRE_DATA();
  const auto frames = Read("fr-clinic.reconstructed.clf");
  ASSERT_EQ(frames.size(), 6917U);
  std::map<long, int> phases;  // start angle in quarter degrees -> lines
  for (const Frame& f : frames) {
    const long quarter = std::lround(RadToDeg(f.scan.angle_min) * 4.0);
    ++phases[quarter];
    EXPECT_EQ(f.scan.size(), quarter == -360 ? 181U : 180U);
    EXPECT_NEAR(RadToDeg(f.scan.angle_increment), 1.0, 1e-4);
  }
  EXPECT_EQ(phases, (std::map<long, int>{{-360, 1748}, {-359, 1709}, {-358, 1725}, {-357, 1735}}));
  ExpectRelationTimesMatch(frames, "fr-clinic.relations");
}

TEST(CarmenIntegration, Fr101FlaserWithParamOffset) {
  GRIDSLAM_REQUIRE_DATA();
  CarmenStats stats;
  const auto frames = Read("fr101.carmen.log", &stats);
  ASSERT_EQ(frames.size(), 4758U);
  EXPECT_EQ(stats.params, 168);
  ExpectGeometry(frames, 360, -90.0, 0.5);
  for (const Frame& f : frames) {
    ASSERT_TRUE(IsApprox(f.T_base_laser, Pose2(-0.04, 0.0, 0.0)));
  }
  EXPECT_GT(frames[100].scan.CountHits(), 100U);
  // Without the PARAM lines, each FLASER's two poses give the same mounting.
  const auto dir = testing::MakeTempDir("fr101");
  const std::string copy = (dir / "no_param.log").string();
  {
    std::ifstream in(Log("fr101.carmen.log"));
    std::ofstream out(copy);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("PARAM", 0) != 0) {
        out << line << "\n";
      }
    }
  }
  auto derived = ReadCarmenLog(copy, {});
  ASSERT_TRUE(derived.ok());
  ASSERT_EQ(derived.value().size(), frames.size());
  for (const Frame& g : derived.value()) {
    ASSERT_TRUE(IsApprox(g.T_base_laser, Pose2(-0.04, 0.0, 0.0), 2e-5, 1e-5))
        << g.T_base_laser.x() << " " << g.T_base_laser.y() << " " << g.T_base_laser.theta();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace gridslam::io
