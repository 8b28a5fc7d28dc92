// The front end on a long part of the real intel log (docs/formats.md §1.5) against the benchmark's
// relations (docs/design.md §3.1): with the default configuration it must beat the odometry on the
// local relations (t2 - t1 < 10 s), in translation and clearly in rotation, without fallbacks.
#include <gtest/gtest.h>

#include "gridslam/eval/relation_metric.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/scan_matching/front_end.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam {
namespace {

TEST(FrontEndIntegration, BeatsOdometryOnIntelsLocalRelations) {
  GRIDSLAM_REQUIRE_DATA();
  const auto log = testing::DataDir() / "logs" / "intel.reconstructed.clf";
  const auto relations_path = testing::DataDir() / "relations" / "intel.relations";
  auto frames = io::ReadCarmenLog(log.string(), io::CarmenOptions{});
  ASSERT_TRUE(frames.ok()) << frames.error().ToString();
  auto relations = io::ReadRelations(relations_path.string());
  ASSERT_TRUE(relations.ok()) << relations.error().ToString();

  constexpr std::size_t kScans = 8000;  // about 1600 s of the 2691 s log
  ASSERT_GT(frames.value().size(), kScans);
  scan_matching::FrontEnd front_end(scan_matching::FrontEndOptions{});
  std::vector<eval::StampedPose> estimate;
  std::vector<eval::StampedPose> odometry;
  long key_maps = 0;
  for (std::size_t k = 0; k < kScans; ++k) {
    const Frame& frame = frames.value()[k];
    const scan_matching::FrontEndStep step = front_end.AddFrame(frame);
    estimate.push_back({frame.time, step.T_odom_base});
    odometry.push_back({frame.time, frame.T_odom_base});
    key_maps += step.key_map ? 1 : 0;
  }
  const scan_matching::FrontEndStats& stats = front_end.Stats();
  EXPECT_EQ(stats.matched, static_cast<long>(kScans) - 1);
  EXPECT_GT(key_maps, 100);

  eval::EvalOptions local;
  local.max_dt = 10.0;
  const eval::RelationMetrics ours = eval::EvaluateRelations(relations.value(), estimate, local);
  const eval::RelationMetrics theirs = eval::EvaluateRelations(relations.value(), odometry, local);
  ASSERT_GT(ours.used, 800);
  ASSERT_EQ(ours.used, theirs.used);
  EXPECT_LT(ours.translation.mean, theirs.translation.mean);
  EXPECT_LT(ours.rotation_deg.mean, 0.5 * theirs.rotation_deg.mean);
  // The targets of the front end (docs/design.md §1.2), with a margin for platform differences.
  EXPECT_LT(ours.translation.mean, 0.025);
  EXPECT_LT(ours.rotation_deg.mean, 0.4);
  RecordProperty("front_end_translation_mean", std::to_string(ours.translation.mean));
  RecordProperty("front_end_rotation_mean_deg", std::to_string(ours.rotation_deg.mean));
}

}  // namespace
}  // namespace gridslam
