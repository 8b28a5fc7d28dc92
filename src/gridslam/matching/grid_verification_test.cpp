#include "gridslam/matching/grid_verification.hpp"

#include <gtest/gtest.h>

#include "gridslam/matching/internal/synthetic.hpp"

namespace gridslam::matching {
namespace {

using internal::CorridorWorld;
using internal::MakeKeyMap;
using internal::SyntheticKeyMap;

// Two key maps of a corridor whose north side repeats every 4 m, the second 4.1 m further east
// and rotated by 0.3 rad.
class CorridorPair : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto world = CorridorWorld();
    map_a_ = new SyntheticKeyMap(MakeKeyMap(world, T_w_a_));
    map_b_ = new SyntheticKeyMap(MakeKeyMap(world, T_w_b_));
  }
  static void TearDownTestSuite() {
    delete map_a_;
    delete map_b_;
  }
  static VerificationInput Input() {
    return {map_b_->obstacles, &map_a_->distance, map_a_->obstacles, &map_b_->distance};
  }
  // The true T_a_b with b displaced by (dx, dy, dtheta) in a's frame.
  static Pose2 Perturbed(double dx, double dy, double dtheta) {
    return T_w_a_.Inverse() * Pose2(dx, dy, 0.0) * T_w_b_ * Pose2(0.0, 0.0, dtheta);
  }
  static inline const Pose2 T_w_a_{0.0, 0.2, 0.0};
  static inline const Pose2 T_w_b_{4.1, -0.1, 0.3};
  static inline SyntheticKeyMap* map_a_ = nullptr;
  static inline SyntheticKeyMap* map_b_ = nullptr;
};

TEST_F(CorridorPair, AcceptsTheTrueTransform) {
  const VerificationResult r =
      VerifyAlignment(Between(T_w_a_, T_w_b_), Input(), VerificationOptions{});
  EXPECT_TRUE(r.accepted);
  EXPECT_TRUE(r.reverse_checked);
  EXPECT_GT(r.agreement, 0.95);
  EXPECT_LT(r.contradiction, 0.02);
  EXPECT_GT(r.overlap, 150);
  EXPECT_EQ(r.overlap, std::min(r.forward.overlap, r.reverse.overlap));
}

TEST_F(CorridorPair, ToleratesACellOfError) {
  EXPECT_TRUE(VerifyAlignment(Perturbed(0.04, -0.03, 0.005), Input(), {}).accepted);
}

TEST_F(CorridorPair, RejectsTheLookAlikeOneCorridorPeriodAway) {
  for (const double shift : {-4.0, 4.0}) {
    const VerificationResult r = VerifyAlignment(Perturbed(shift, 0.0, 0.0), Input(), {});
    EXPECT_FALSE(r.accepted) << "shift " << shift;
    EXPECT_TRUE(r.enough_overlap) << "shift " << shift;  // rejected by the grids, not overlap
    EXPECT_GT(r.contradiction, 0.12) << "shift " << shift;
  }
}

TEST_F(CorridorPair, RejectsSmallButWrongOffsets) {
  EXPECT_FALSE(VerifyAlignment(Perturbed(0.0, 0.5, 0.0), Input(), {}).accepted);
  EXPECT_FALSE(VerifyAlignment(Perturbed(0.0, 0.0, 0.1), Input(), {}).accepted);
}

TEST_F(CorridorPair, NoOverlapIsRejected) {
  const VerificationResult r = VerifyAlignment(Perturbed(40.0, 0.0, 0.0), Input(), {});
  EXPECT_FALSE(r.accepted);
  EXPECT_FALSE(r.enough_overlap);
  EXPECT_EQ(r.forward.overlap, 0);
}

TEST_F(CorridorPair, ReverseOnlyWhenGivenAndEnabled) {
  VerificationInput forward_only{map_b_->obstacles, &map_a_->distance, {}, nullptr};
  EXPECT_FALSE(VerifyAlignment(Between(T_w_a_, T_w_b_), forward_only, {}).reverse_checked);
  VerificationOptions options;
  options.check_reverse = false;
  EXPECT_FALSE(VerifyAlignment(Between(T_w_a_, T_w_b_), Input(), options).reverse_checked);
}

TEST_F(CorridorPair, SubsamplingKeepsTheVerdict) {
  VerificationOptions options;
  options.max_points = 100;
  options.min_overlap_points = 20;
  const VerificationResult r = VerifyAlignment(Between(T_w_a_, T_w_b_), Input(), options);
  EXPECT_LE(r.forward.points, 100);
  EXPECT_TRUE(r.accepted);
  EXPECT_FALSE(VerifyAlignment(Perturbed(-4.0, 0.0, 0.0), Input(), options).accepted);
}

TEST(GridVerification, UnknownCellsAreOutsideTheOverlap) {
  const MapLimits limits(0.1, Eigen::Vector2d(-1.0, -1.0), 20, 20);
  OccupancyImage occupancy(limits, kUnknownCell);
  occupancy(5, 5) = kOccupiedCell;
  occupancy(6, 5) = kFreeCell;
  Grid2D<float> distance(limits, 0.5F);
  distance(5, 5) = 0.0F;
  MarkUnknownCells(occupancy, &distance);
  EXPECT_EQ(distance(5, 5), 0.0F);
  EXPECT_EQ(distance(6, 5), 0.5F);
  EXPECT_LT(distance(0, 0), 0.0F);

  const std::vector<Eigen::Vector2d> points = OccupiedCellCenters(occupancy);
  ASSERT_EQ(points.size(), 1U);
  EXPECT_TRUE(points[0].isApprox(limits.CellCenter({5, 5})));

  const std::vector<Eigen::Vector2d> probe = {limits.CellCenter({5, 5}),
                                              limits.CellCenter({6, 5}),
                                              limits.CellCenter({15, 15}),
                                              {50.0, 0.0}};
  const AgreementScore s = ScoreAgreement(probe, Pose2(), distance, VerificationOptions{});
  EXPECT_EQ(s.points, 4);
  EXPECT_EQ(s.overlap, 2);
  EXPECT_EQ(s.agreeing, 1);
  EXPECT_EQ(s.contradicting, 1);
  EXPECT_EQ(ScoreAgreement({}, Pose2(), distance, {}).overlap, 0);
}

}  // namespace
}  // namespace gridslam::matching
