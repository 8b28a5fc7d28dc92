#include "gridslam/benchmark/align_eval.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"

namespace gridslam::benchmark {
namespace {

// A 24 x 14 m ring corridor (2.4 m wide) around a solid block, with niches and boxes at
// irregular places so that every stretch looks different; its tour follows the centreline.
simulation::World RingWorld() {
  simulation::WorldBuilder b(24.0, 14.0, 0.05);
  b.Carve(1.0, 1.0, 23.0, 3.4).Carve(1.0, 10.6, 23.0, 13.0);
  b.Carve(1.0, 1.0, 3.4, 13.0).Carve(20.6, 1.0, 23.0, 13.0);
  b.Carve(5.0, 0.4, 6.5, 1.0).Carve(13.0, 0.4, 13.8, 1.0).Carve(17.0, 3.4, 18.5, 4.2);
  b.Carve(8.0, 13.0, 10.5, 13.6).Carve(15.5, 10.0, 16.2, 10.6).Carve(23.0, 5.0, 23.6, 7.5);
  b.Carve(0.4, 8.0, 1.0, 9.0).Carve(3.4, 6.0, 4.0, 6.6);
  b.Fill(9.0, 1.0, 9.4, 1.5).Fill(20.6, 9.0, 21.0, 10.2).Fill(6.0, 12.6, 7.5, 13.0);
  b.Fill(1.0, 4.0, 1.3, 5.5).Fill(15.0, 3.0, 15.6, 3.4);
  return b.Build("ring", {{2.2, 2.2}, {21.8, 2.2}, {21.8, 11.8}, {2.2, 11.8}, {2.2, 2.2}});
}

struct SimulatedLog {
  std::vector<Frame> frames;
  std::vector<eval::Relation> relations;
  std::vector<eval::StampedPose> truth;
};

const SimulatedLog& Log() {
  static const SimulatedLog log = [] {
    simulation::SimulationOptions options;
    options.duration = 175.0;  // one lap and a third: the first corridors are driven twice
    options.seed = 3;
    const auto result = simulation::Simulate(RingWorld(), {}, options);
    GRIDSLAM_CHECK(result.ok()) << result.error().ToString();
    SimulatedLog out;
    const simulation::RobotRun& run = result.value().robots.at(0);
    out.frames = run.frames;
    out.relations = run.relations;
    for (const Frame& frame : run.frames) {
      out.truth.push_back({frame.time, *frame.T_world_base_true});
    }
    return out;
  }();
  return log;
}

// Small windows keep the test fast and let key maps 10 m apart be true negatives.
AlignEvalConfig SmallWindowConfig() {
  AlignEvalConfig config;
  config.front_end.local_map.size = 8.0;
  config.eval.max_centre_distance = 2.5;
  config.eval.negatives = 60;
  config.eval.negative_min_distance = 10.0;
  return config;
}

TEST(AlignEval, FindsTheRevisitsOfASimulatedLoopWithoutFalseAccepts) {
  const SimulatedLog& log = Log();
  const AlignEvalConfig config = SmallWindowConfig();
  const auto report = RunAlignEval({log.frames, log.relations, log.truth}, config);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  const AlignEvalReport& r = report.value();
  const AlignEvalSummary& s = r.summary;
  EXPECT_EQ(r.frames, static_cast<long>(log.frames.size()));
  EXPECT_GT(r.selection.revisits, 20);
  std::fprintf(stderr, "frames %zu relations %zu t %.1f keymaps %ld\n", log.frames.size(), log.relations.size(), ToSeconds(log.frames.back().time - log.frames.front().time), r.key_maps);
  for (std::size_t i = 0; i < log.truth.size(); i += 50) std::fprintf(stderr, "%.1f %.2f %.2f\n", ToSeconds(log.truth[i].time - log.truth[0].time), log.truth[i].pose.x(), log.truth[i].pose.y());
  ASSERT_GE(s.pairs, 5);
  EXPECT_EQ(s.pairs, static_cast<long>(r.positives.size()));
  EXPECT_GE(s.correct, (3 * s.pairs) / 4) << "recall " << s.recall;
  EXPECT_EQ(s.wrong, 0);
  EXPECT_LT(s.median_error_m, 0.05);
  EXPECT_LT(s.median_error_deg, 0.5);
  EXPECT_TRUE(r.negatives_from_ground_truth);
  EXPECT_EQ(s.negatives, 60);
  EXPECT_EQ(s.false_accepts, 0);
  EXPECT_GT(s.features_per_keymap, 5.0);
  EXPECT_GT(s.described, 0);
  for (const PairOutcome& o : r.positives) {
    EXPECT_NE(o.pair.key_a, o.pair.key_b);
    EXPECT_LE(o.pair.centre_distance, config.eval.max_centre_distance);
    EXPECT_EQ(o.correct, o.accepted && o.error_translation < 0.1 &&
                             o.error_rotation < DegToRad(1.0));
  }
  for (const PairOutcome& o : r.negatives) {
    EXPECT_GT(o.pair.centre_distance, 10.0);
    EXPECT_LT(o.pair.key_a, o.pair.key_b);
  }
}

// The truth of a pair, carried across the loop by the relation, must agree with the key maps'
// frames placed in the world by ground truth at other scans of the key maps (their first ones):
// both rest on the front end being locally consistent.
TEST(AlignEval, PairTruthAgreesWithGroundTruth) {
  const SimulatedLog& log = Log();
  AlignEvalConfig config = SmallWindowConfig();
  config.front_end.keymap.keep_scans = false;
  const KeyMapCatalog catalog = KeyMapCatalog::Build(log.frames, config.front_end);
  const PositiveSelection positives =
      SelectPositives(catalog, log.relations, config.eval, /*relations_in_laser_frame=*/false);
  ASSERT_GE(positives.pairs.size(), 5U);
  auto T_world_key = [&](int key_map) {
    // T_world_key = T_world_base * T_key_base^-1 at the key map's first scan.
    const int f = catalog.KeyMaps()[static_cast<std::size_t>(key_map)].first_frame;
    return *log.frames[static_cast<std::size_t>(f)].T_world_base_true *
           catalog.PoseInKeyMap(f, false).Inverse();
  };
  for (const TestPair& pair : positives.pairs) {
    const int f1 = catalog.FindFrame(pair.t1, 1e-6);
    ASSERT_GE(f1, 0);
    EXPECT_EQ(catalog.Frames()[static_cast<std::size_t>(f1)].key_map, pair.key_a);
    const Pose2 error =
        Between(Between(T_world_key(pair.key_a), T_world_key(pair.key_b)), pair.T_a_b_true);
    EXPECT_LT(error.translation().norm(), 0.05);
    EXPECT_LT(std::abs(error.theta()), DegToRad(0.5));
  }
}

TEST(AlignEval, WindowsSeparateOnlyAfterTheRobotLeft) {
  const SimulatedLog& log = Log();
  AlignEvalConfig config = SmallWindowConfig();
  const KeyMapCatalog catalog = KeyMapCatalog::Build(log.frames, config.front_end);
  ASSERT_GT(catalog.KeyMaps().size(), 20U);
  EXPECT_FALSE(catalog.WindowsSeparated(0, 1));
  EXPECT_FALSE(catalog.WindowsSeparated(3, 3));
  const int last = static_cast<int>(catalog.KeyMaps().size()) - 1;
  EXPECT_TRUE(catalog.WindowsSeparated(0, last));
  EXPECT_TRUE(catalog.WindowsSeparated(last, 0));
  // Every scan belongs to one key map, in order.
  int previous = 0;
  for (const FrameRecord& frame : catalog.Frames()) {
    EXPECT_GE(frame.key_map, previous);
    previous = frame.key_map;
  }
}

TEST(AlignEval, SummaryCountsAndMedians) {
  std::vector<PairOutcome> positives(4);
  positives[0].accepted = positives[0].correct = true;
  positives[0].error_translation = 0.02;
  positives[1].accepted = positives[1].correct = true;
  positives[1].error_translation = 0.04;
  positives[2].accepted = true;  // wrong
  positives[3].reason = matching::RejectReason::kTooFewInliers;
  std::vector<PairOutcome> negatives(2);
  negatives[1].accepted = true;
  const AlignEvalSummary s = Summarize(positives, negatives);
  EXPECT_EQ(s.pairs, 4);
  EXPECT_EQ(s.accepted, 3);
  EXPECT_EQ(s.correct, 2);
  EXPECT_EQ(s.wrong, 1);
  EXPECT_DOUBLE_EQ(s.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.recall, 0.5);
  EXPECT_DOUBLE_EQ(s.median_error_m, 0.03);
  EXPECT_EQ(s.negatives, 2);
  EXPECT_EQ(s.false_accepts, 1);
  EXPECT_EQ(s.rejected.at(matching::ToString(matching::RejectReason::kTooFewInliers)), 1);
  EXPECT_TRUE(std::isnan(Summarize({}, {}).precision));
}

}  // namespace
}  // namespace gridslam::benchmark
