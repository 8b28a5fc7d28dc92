#include "gridslam/matching/rigid_ransac.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace gridslam::matching {
namespace {

// n correspondences over a 10 m square, the first n_in of them inliers (noise `noise`), the
// others random; the order is shuffled. `truth` receives the inlier indices, sorted.
Correspondences Make(const Pose2& T_a_b, int n, int n_in, double noise, unsigned seed,
                     std::vector<int>* truth) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-5.0, 5.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) order[static_cast<std::size_t>(k)] = k;
  std::shuffle(order.begin(), order.end(), rng);
  Correspondences c;
  c.a.resize(static_cast<std::size_t>(n));
  c.b.resize(static_cast<std::size_t>(n));
  truth->clear();
  for (int k = 0; k < n; ++k) {
    const auto slot = static_cast<std::size_t>(order[static_cast<std::size_t>(k)]);
    c.b[slot] = Eigen::Vector2d(pos(rng), pos(rng));
    if (k < n_in) {
      c.a[slot] = T_a_b * c.b[slot] + noise * Eigen::Vector2d(gauss(rng), gauss(rng));
      truth->push_back(static_cast<int>(slot));
    } else {
      c.a[slot] = Eigen::Vector2d(pos(rng), pos(rng));
    }
  }
  std::sort(truth->begin(), truth->end());
  return c;
}

double TranslationError(const Pose2& x, const Pose2& y) {
  return (x.translation() - y.translation()).norm();
}
double AngleError(const Pose2& x, const Pose2& y) {
  return std::abs(NormalizeAngle(x.theta() - y.theta()));
}

int CountCommon(const std::vector<int>& x, const std::vector<int>& y) {
  std::vector<int> common;
  std::set_intersection(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(common));
  return static_cast<int>(common.size());
}

void ExpectRecovered(int n, int n_in, const RansacOptions& options) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (unsigned trial = 0; trial < 20; ++trial) {
    const Pose2 T_a_b(u(rng), u(rng), u(rng));
    std::vector<int> truth;
    const Correspondences c = Make(T_a_b, n, n_in, 0.02, 1000 + trial, &truth);
    const RansacResult r = EstimateRigidRansac(c, options);
    ASSERT_TRUE(r.found) << "trial " << trial;
    EXPECT_LT(TranslationError(r.T_a_b, T_a_b), 0.03) << "trial " << trial;
    EXPECT_LT(AngleError(r.T_a_b, T_a_b), DegToRad(0.5)) << "trial " << trial;
    EXPECT_EQ(CountCommon(r.inliers, truth), n_in) << "trial " << trial;
    EXPECT_LE(static_cast<int>(r.inliers.size()) - n_in, 2) << "trial " << trial;
  }
}

TEST(EstimateRigidRansac, RecoversAKnownTransformWithHalfOutliers) {
  RansacOptions options;
  options.exhaustive_max_matches = 0;  // random sampling
  ExpectRecovered(100, 50, options);
}

TEST(EstimateRigidRansac, RecoversAKnownTransformWith80PercentOutliers) {
  RansacOptions options;
  options.exhaustive_max_matches = 0;
  ExpectRecovered(150, 30, options);
  options.exhaustive_max_matches = 1000;  // and every pair
  ExpectRecovered(100, 20, options);
}

TEST(EstimateRigidRansac, AdaptiveCountStopsEarlyWithFewOutliers) {
  std::vector<int> truth;
  RansacOptions options;
  options.exhaustive_max_matches = 0;
  const Correspondences c = Make(Pose2(1.0, 0.0, 0.2), 100, 50, 0.02, 7, &truth);
  const RansacResult r = EstimateRigidRansac(c, options);
  ASSERT_TRUE(r.found);
  EXPECT_FALSE(r.exhaustive);
  EXPECT_LT(r.iterations, 100);  // log(0.001) / log(1 - 0.25) = 24 once the best is found
  const Correspondences c2 = Make(Pose2(1.0, 0.0, 0.2), 100, 3, 0.02, 7, &truth);
  EXPECT_EQ(EstimateRigidRansac(c2, options).iterations, options.max_iterations);
}

TEST(EstimateRigidRansac, ExhaustiveAndAdaptiveAgree) {
  for (unsigned seed = 0; seed < 10; ++seed) {
    std::vector<int> truth;
    const Pose2 T_a_b(-1.0, 2.0, 2.5);
    const Correspondences c = Make(T_a_b, 40, 16, 0.03, seed, &truth);
    RansacOptions exhaustive;
    exhaustive.exhaustive_max_matches = 40;
    RansacOptions adaptive = exhaustive;
    adaptive.exhaustive_max_matches = 39;
    const RansacResult e = EstimateRigidRansac(c, exhaustive);
    const RansacResult a = EstimateRigidRansac(c, adaptive);
    ASSERT_TRUE(e.found && a.found);
    EXPECT_TRUE(e.exhaustive);
    EXPECT_FALSE(a.exhaustive);
    EXPECT_EQ(e.iterations, 40 * 39 / 2);
    EXPECT_EQ(e.inliers, a.inliers) << "seed " << seed;
    EXPECT_TRUE(IsApprox(e.T_a_b, a.T_a_b, 1e-9, 1e-9)) << "seed " << seed;
  }
}

TEST(EstimateRigidRansac, RefinementBeatsTheBestTwoPointHypothesis) {
  double hyp_t = 0.0;
  double hyp_r = 0.0;
  double ref_t = 0.0;
  double ref_r = 0.0;
  const int trials = 40;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<int> truth;
    const Pose2 T_a_b(0.5 * trial, -1.0, 0.1 * trial);
    const Correspondences c =
        Make(T_a_b, 60, 30, 0.05, 500U + static_cast<unsigned>(trial), &truth);
    const RansacResult r = EstimateRigidRansac(c, RansacOptions{});
    ASSERT_TRUE(r.found);
    hyp_t += TranslationError(r.T_a_b_hypothesis, T_a_b);
    hyp_r += AngleError(r.T_a_b_hypothesis, T_a_b);
    ref_t += TranslationError(r.T_a_b, T_a_b);
    ref_r += AngleError(r.T_a_b, T_a_b);
  }
  EXPECT_LT(ref_t, 0.6 * hyp_t);
  EXPECT_LT(ref_r, 0.6 * hyp_r);
  EXPECT_LT(ref_t / trials, 0.03);
}

TEST(EstimateRigidRansac, DeterministicForAGivenSeed) {
  std::vector<int> truth;
  const Correspondences c = Make(Pose2(0.3, 0.4, -1.0), 120, 40, 0.03, 3, &truth);
  RansacOptions options;
  const RansacResult r1 = EstimateRigidRansac(c, options);
  const RansacResult r2 = EstimateRigidRansac(c, options);
  EXPECT_EQ(r1.iterations, r2.iterations);
  EXPECT_EQ(r1.inliers, r2.inliers);
  EXPECT_EQ(r1.T_a_b.ToVector(), r2.T_a_b.ToVector());
}

TEST(EstimateRigidRansac, DegenerateInputsFindNothing) {
  Correspondences c;
  EXPECT_FALSE(EstimateRigidRansac(c, {}).found);  // 0
  c.a.emplace_back(1.0, 1.0);
  c.b.emplace_back(0.0, 0.0);
  EXPECT_FALSE(EstimateRigidRansac(c, {}).found);  // 1
  c.a.emplace_back(1.0, 1.1);                      // 2, closer than min_pair_separation
  c.b.emplace_back(0.0, 0.1);
  EXPECT_FALSE(EstimateRigidRansac(c, {}).found);
  c.a.assign(30, Eigen::Vector2d(2.0, 2.0));  // all identical
  c.b.assign(30, Eigen::Vector2d(1.0, 1.0));
  EXPECT_FALSE(EstimateRigidRansac(c, {}).found);
  // Two well separated matches: the exact transform, both inliers.
  c.a = {{1.0, 0.0}, {1.0, 2.0}};
  c.b = {{0.0, 0.0}, {2.0, 0.0}};
  const RansacResult two = EstimateRigidRansac(c, {});
  ASSERT_TRUE(two.found);
  EXPECT_EQ(two.inliers.size(), 2U);
  EXPECT_TRUE(IsApprox(two.T_a_b, Pose2(1.0, 0.0, M_PI / 2), 1e-9, 1e-9));
  // Lengths that differ by more than two inlier radii cannot both be inliers.
  c.a = {{1.0, 0.0}, {1.0, 3.0}};
  EXPECT_FALSE(EstimateRigidRansac(c, {}).found);
}

TEST(EstimateRigidRansac, OrientationCheckVetoesInconsistentHypotheses) {
  std::vector<int> truth;
  const Pose2 T_a_b(1.0, 1.0, 0.7);
  Correspondences c = Make(T_a_b, 30, 30, 0.01, 11, &truth);
  c.rotation.assign(30, 0.7 + 0.1);
  EXPECT_TRUE(EstimateRigidRansac(c, {}).found);
  c.rotation.assign(30, 0.7 + 1.0);  // keypoint orientations say another rotation
  EXPECT_FALSE(EstimateRigidRansac(c, {}).found);
  RansacOptions off;
  off.max_orientation_difference = 0.0;
  EXPECT_TRUE(EstimateRigidRansac(c, off).found);
}

}  // namespace
}  // namespace gridslam::matching
