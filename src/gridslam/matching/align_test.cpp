#include "gridslam/matching/align.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "gridslam/matching/internal/synthetic.hpp"

namespace gridslam::matching {
namespace {

using internal::MakeFeaturePair;

TEST(Align, RecoversTheTransformWithTheDocumentedConvention) {
  const Pose2 T_a_b(2.0, -1.0, 2.2);
  const auto pair = MakeFeaturePair(T_a_b, 200, 200, 60, 0.02, 1);
  const AlignResult r = Align(pair.a, pair.b, AlignOptions{}, nullptr);
  ASSERT_TRUE(r.accepted) << ToString(r.reason);
  EXPECT_EQ(r.reason, RejectReason::kNone);
  EXPECT_LT((r.T_a_b.translation() - T_a_b.translation()).norm(), 0.02);
  EXPECT_LT(std::abs(NormalizeAngle(r.T_a_b.theta() - T_a_b.theta())), DegToRad(0.3));
  EXPECT_GE(r.inliers.size(), 55U);
  // Points of b mapped by the result land on their partners in a: p_a = T_a_b * p_b.
  for (const int k : r.inliers) {
    const Match& m = r.matches[static_cast<std::size_t>(k)];
    EXPECT_LT((r.T_a_b * pair.b.points[static_cast<std::size_t>(m.index_b)] -
               pair.a.points[static_cast<std::size_t>(m.index_a)])
                  .norm(),
              0.1);
  }
  EXPECT_LT(r.rms_residual, 0.05);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(r.information).eigenvalues()(0), 0.0);
  EXPECT_FALSE(r.verified);
  // Aligning a to b gives the inverse.
  const AlignResult inverse = Align(pair.b, pair.a, AlignOptions{}, nullptr);
  ASSERT_TRUE(inverse.accepted);
  EXPECT_TRUE(IsApprox(inverse.T_a_b * r.T_a_b, Pose2(), 1e-6, 1e-6));
}

TEST(Align, DegenerateInputsAreRejectedWithoutCrashing) {
  const AlignOptions options;
  const FeatureSet empty;
  const auto pair = MakeFeaturePair(Pose2(1.0, 0.0, 0.5), 50, 50, 20, 0.0, 2);
  EXPECT_EQ(Align(empty, empty, options, nullptr).reason, RejectReason::kTooFewMatches);
  EXPECT_EQ(Align(pair.a, empty, options, nullptr).reason, RejectReason::kTooFewMatches);
  for (const std::size_t n : {0U, 1U, 2U, 5U}) {
    std::vector<Match> some(pair.truth.begin(), pair.truth.begin() + static_cast<long>(n));
    const AlignResult r = AlignMatches(pair.a, pair.b, some, options, nullptr);
    EXPECT_FALSE(r.accepted);
    EXPECT_EQ(r.reason, RejectReason::kTooFewMatches) << n;
  }
  // Two matches are enough when min_inliers allows it (and the spread check does not apply).
  AlignOptions two = options;
  two.min_inliers = 2;
  two.min_inlier_spread = 0.0;
  std::vector<Match> pair_of_two(pair.truth.begin(), pair.truth.begin() + 2);
  EXPECT_TRUE(AlignMatches(pair.a, pair.b, pair_of_two, two, nullptr).accepted);

  // All keypoints at one place: no hypothesis.
  auto same = pair;
  same.a.points.assign(same.a.points.size(), Eigen::Vector2d(1.0, 1.0));
  same.b.points.assign(same.b.points.size(), Eigen::Vector2d(-1.0, 2.0));
  const AlignResult identical = Align(same.a, same.b, options, nullptr);
  EXPECT_FALSE(identical.accepted);
  EXPECT_EQ(identical.reason, RejectReason::kNoHypothesis);

  // All keypoints on one line: the transform is found but rejected as degenerate.
  auto line = pair;
  for (auto& p : line.b.points) {
    p.y() = 0.5;
  }
  for (const Match& m : line.truth) {
    line.a.points[static_cast<std::size_t>(m.index_a)] =
        Pose2(1.0, 0.0, 0.5) * line.b.points[static_cast<std::size_t>(m.index_b)];
  }
  const AlignResult collinear = Align(line.a, line.b, options, nullptr);
  EXPECT_FALSE(collinear.accepted);
  EXPECT_EQ(collinear.reason, RejectReason::kDegenerateInliers);
  EXPECT_TRUE(IsApprox(collinear.T_a_b, Pose2(1.0, 0.0, 0.5), 1e-6, 1e-6));
}

TEST(Align, TooFewInliersAmongManyMatches) {
  const auto pair = MakeFeaturePair(Pose2(1.0, 0.0, 0.5), 100, 100, 4, 0.0, 3);
  std::vector<Match> matches(pair.truth.begin(), pair.truth.end());
  for (int k = 0; k < 20; ++k) {  // arbitrary pairings of unrelated features
    matches.push_back({k + 50, (7 * k + 3) % 100, 1.0F});
  }
  const AlignResult r = AlignMatches(pair.a, pair.b, matches, AlignOptions{}, nullptr);
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.reason, RejectReason::kTooFewInliers);
}

class AlignCorridor : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto world = internal::CorridorWorld();
    map_a_ = new internal::SyntheticKeyMap(internal::MakeKeyMap(world, T_w_a_));
    map_b_ = new internal::SyntheticKeyMap(internal::MakeKeyMap(world, T_w_b_));
  }
  static void TearDownTestSuite() {
    delete map_a_;
    delete map_b_;
  }
  static VerificationInput Input() {
    return {map_b_->obstacles, &map_a_->distance, map_a_->obstacles, &map_b_->distance};
  }
  static inline const Pose2 T_w_a_{0.0, 0.2, 0.0};
  static inline const Pose2 T_w_b_{4.1, -0.1, 0.3};
  static inline internal::SyntheticKeyMap* map_a_ = nullptr;
  static inline internal::SyntheticKeyMap* map_b_ = nullptr;
};

TEST_F(AlignCorridor, VerificationAcceptsTheTruthAndRejectsTheLookAlike) {
  const Pose2 T_a_b = Between(T_w_a_, T_w_b_);
  const VerificationInput input = Input();
  const auto good = MakeFeaturePair(T_a_b, 150, 150, 40, 0.02, 4);
  const AlignResult accepted = Align(good.a, good.b, AlignOptions{}, &input);
  ASSERT_TRUE(accepted.accepted) << ToString(accepted.reason);
  EXPECT_TRUE(accepted.verified);
  EXPECT_GT(accepted.agreement, 0.9);
  EXPECT_GT(accepted.overlap, 100);
  EXPECT_TRUE(IsApprox(accepted.T_a_b, T_a_b, 0.03, DegToRad(0.5)));

  // Features that vote for the look-alike one corridor period (4 m) away.
  const Pose2 T_look_alike = T_w_a_.Inverse() * Pose2(-4.0, 0.0, 0.0) * T_w_b_;
  const auto aliased = MakeFeaturePair(T_look_alike, 150, 150, 40, 0.02, 5);
  const AlignResult rejected = Align(aliased.a, aliased.b, AlignOptions{}, &input);
  EXPECT_FALSE(rejected.accepted);
  EXPECT_EQ(rejected.reason, RejectReason::kGridDisagreement);
  EXPECT_TRUE(IsApprox(rejected.T_a_b, T_look_alike, 0.03, DegToRad(0.5)));
  // Without the verification the look-alike would have been accepted.
  AlignOptions unverified;
  unverified.verification.enabled = false;
  EXPECT_TRUE(Align(aliased.a, aliased.b, unverified, &input).accepted);

  // A transform that leaves the key maps apart: too little overlap.
  const auto apart = MakeFeaturePair(Pose2(30.0, 0.0, 0.0), 150, 150, 40, 0.02, 6);
  EXPECT_EQ(Align(apart.a, apart.b, AlignOptions{}, &input).reason,
            RejectReason::kTooLittleOverlap);
}

TEST(AlignOptions, ValidateRejectsBadValues) {
  AlignOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.min_inliers = 1;
  EXPECT_FALSE(options.Validate().ok());
  options = AlignOptions{};
  options.ransac.confidence = 1.0;
  EXPECT_FALSE(options.Validate().ok());
  options = AlignOptions{};
  options.verification.min_agreement = 1.5;
  EXPECT_FALSE(options.Validate().ok());
  options = AlignOptions{};
  options.descriptors.max_ratio = 0.0;
  EXPECT_FALSE(options.Validate().ok());
}

}  // namespace
}  // namespace gridslam::matching
