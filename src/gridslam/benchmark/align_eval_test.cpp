#include "gridslam/benchmark/align_eval.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "gridslam/simulation/simulator.hpp"
#include "gridslam/simulation/world.hpp"

namespace gridslam::benchmark {
namespace {

// The simulator's office world, driven around its south-west block of offices (a 23 x 11 m loop
// past open doors and furniture) for a lap and a half: the first corridors are seen twice.
const std::vector<Eigen::Vector2d>& Loop() {
  static const std::vector<Eigen::Vector2d> loop = {
      {2.2, 2.2}, {25.0, 2.2}, {25.0, 13.6}, {2.2, 13.6}, {2.2, 2.2}};
  return loop;
}

struct SimulatedLog {
  std::vector<Frame> frames;
  std::vector<eval::Relation> relations;
  std::vector<eval::StampedPose> truth;
};

const SimulatedLog& Log() {
  static const SimulatedLog log = [] {
    simulation::SimulationOptions options;
    options.duration = 200.0;
    options.seed = 3;
    const auto world = simulation::MakeBuiltinWorld("office", 0.05);
    GRIDSLAM_CHECK(world.ok()) << world.error().ToString();
    const auto result = simulation::Simulate(world.value(), Loop(), options);
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
  config.eval.negatives = 60;
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
  std::fprintf(stderr, "pairs %ld correct %ld unreliable %ld unchecked %ld shared %ld\n", s.pairs, s.correct, r.selection.unreliable, r.selection.unchecked, r.selection.shared);
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
    if (o.accepted && !o.correct) std::fprintf(stderr, "wrong %d %d err %.3f %.3f agree %.3f spread %.3f n %d checks %d %.3f %.3f\n", o.pair.key_a, o.pair.key_b, o.error_translation, RadToDeg(o.error_rotation), o.agreement, o.pair.truth_spread_translation, o.pair.relations, o.pair.truth_checks, o.pair.truth_error_translation, RadToDeg(o.pair.truth_error_rotation));
    if (!o.accepted) std::fprintf(stderr, "rejected %d %d %s d %.2f feat %d %d\n", o.pair.key_a, o.pair.key_b, matching::ToString(o.reason), o.pair.centre_distance, o.features_a, o.features_b);
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
    std::fprintf(stderr, "pair %d %d err %.3f %.3f f1 %d f2 %d\n", pair.key_a, pair.key_b, error.translation().norm(), RadToDeg(error.theta()), f1, catalog.FindFrame(pair.t2, 1e-6));
    for (int k : {pair.key_a, pair.key_b}) {
      const auto& km = catalog.KeyMaps()[static_cast<std::size_t>(k)];
      const auto& fa = catalog.Frames()[static_cast<std::size_t>(km.first_frame)];
      const auto& fb = catalog.Frames()[static_cast<std::size_t>(km.last_frame)];
      const Pose2 fe = Between(fa.T_odom_base, fb.T_odom_base);
      const Pose2 gt = Between(*log.frames[static_cast<std::size_t>(km.first_frame)].T_world_base_true, *log.frames[static_cast<std::size_t>(km.last_frame)].T_world_base_true);
      const Pose2 od = Between(log.frames[static_cast<std::size_t>(km.first_frame)].T_odom_base, log.frames[static_cast<std::size_t>(km.last_frame)].T_odom_base);
      std::fprintf(stderr, "key %d frames %d-%d travel %.2f fe-gt %.3f %.3f odo-gt %.3f\n", k, km.first_frame, km.last_frame, fb.travel - fa.travel, Between(gt, fe).translation().norm(), RadToDeg(Between(gt, fe).theta()), Between(gt, od).translation().norm());
    }
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
  std::vector<PairOutcome> negatives(3);
  negatives[1].accepted = negatives[1].gross = true;
  negatives[2].accepted = true;  // near the truth: not a false accept
  const AlignEvalSummary s = Summarize(positives, negatives);
  EXPECT_EQ(s.pairs, 4);
  EXPECT_EQ(s.accepted, 3);
  EXPECT_EQ(s.correct, 2);
  EXPECT_EQ(s.wrong, 1);
  EXPECT_DOUBLE_EQ(s.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.recall, 0.5);
  EXPECT_DOUBLE_EQ(s.median_error_m, 0.03);
  EXPECT_EQ(s.negatives, 3);
  EXPECT_EQ(s.negatives_accepted, 2);
  EXPECT_EQ(s.false_accepts, 1);
  EXPECT_EQ(s.rejected.at(matching::ToString(matching::RejectReason::kTooFewInliers)), 1);
  EXPECT_TRUE(std::isnan(Summarize({}, {}).precision));
}

}  // namespace
}  // namespace gridslam::benchmark
