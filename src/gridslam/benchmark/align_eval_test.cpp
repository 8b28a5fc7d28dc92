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

// The default configuration, with a few negatives (key maps more than 20 m apart: the loop's
// opposite corners).
AlignEvalConfig TestConfig() {
  AlignEvalConfig config;
  config.eval.negatives = 60;
  return config;
}

TEST(AlignEval, FindsTheRevisitsOfASimulatedLoopWithoutFalseAccepts) {
  const SimulatedLog& log = Log();
  const AlignEvalConfig config = TestConfig();
  const auto report = RunAlignEval({log.frames, log.relations, log.truth}, config);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  const AlignEvalReport& r = report.value();
  const AlignEvalSummary& s = r.summary;
  EXPECT_EQ(r.frames, static_cast<long>(log.frames.size()));
  EXPECT_GT(r.selection.revisits, 20);
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
    EXPECT_GT(o.pair.truth_checks, 0);
    EXPECT_LE(o.pair.centre_distance, config.eval.max_centre_distance);
    EXPECT_EQ(o.correct,
              o.accepted && o.error_translation < 0.1 && o.error_rotation < DegToRad(1.0));
  }
  for (const PairOutcome& o : r.negatives) {
    EXPECT_GT(o.pair.centre_distance, config.eval.negative_min_distance);
    EXPECT_LT(o.pair.key_a, o.pair.key_b);
  }
}

// The truth of a pair, carried across the loop by the relation, must agree with the key maps'
// frames placed in the world by ground truth at other scans of the key maps (their first ones):
// both rest on the front end being locally consistent.
TEST(AlignEval, PairTruthAgreesWithGroundTruth) {
  const SimulatedLog& log = Log();
  AlignEvalConfig config = TestConfig();
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

// Where the front end disagrees with the short relations around a revisit, the revisit's truth is
// not trusted: corrupting every short relation by 0.3 m leaves no pair.
TEST(AlignEval, TruthCheckDropsPairsWhereTheFrontEndIsInaccurate) {
  const SimulatedLog& log = Log();
  const AlignEvalConfig config = TestConfig();
  const KeyMapCatalog catalog = KeyMapCatalog::Build(log.frames, config.front_end);
  const PositiveSelection clean = SelectPositives(catalog, log.relations, config.eval, false);
  ASSERT_GE(clean.pairs.size(), 5U);
  std::vector<eval::Relation> corrupted = log.relations;
  for (eval::Relation& relation : corrupted) {
    if (ToSeconds(relation.t2 - relation.t1) <= config.eval.truth_check_max_dt) {
      relation.T_1_2 = relation.T_1_2 * Pose2(0.3, 0.0, 0.0);
    }
  }
  const PositiveSelection dropped = SelectPositives(catalog, corrupted, config.eval, false);
  EXPECT_TRUE(dropped.pairs.empty());
  EXPECT_EQ(dropped.unreliable,
            clean.unreliable + clean.duplicates + static_cast<long>(clean.pairs.size()));
}

TEST(AlignEval, WindowsSeparateOnlyAfterTheRobotLeft) {
  const SimulatedLog& log = Log();
  AlignEvalConfig config = TestConfig();
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
