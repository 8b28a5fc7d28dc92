#include "gridslam/loop_closure/prior_search.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/loop_closure/grid_refinement.hpp"

namespace gridslam::loop_closure {
namespace {

constexpr double kResolution = 0.05;

// An irregular room (walls, a slanted wall, two pillars) in a 12 m grid.
Grid2D<std::uint8_t> Room() {
  Grid2D<std::uint8_t> obstacles(MapLimits(kResolution, Eigen::Vector2d(-6.0, -6.0), 240, 240), 0);
  for (int k = 30; k < 210; ++k) {
    obstacles(k, 30) = 1;
    obstacles(30, k) = 1;
    obstacles(k, 209) = 1;
    obstacles(209, k / 2 + 105) = 1;
  }
  for (int i = 100; i < 112; ++i) {
    for (int j = 70; j < 75; ++j) {
      obstacles(i, j) = 1;
      obstacles(j + 80, i + 30) = 1;
    }
  }
  return obstacles;
}

// A corridor: two long parallel walls, nothing along them.
Grid2D<std::uint8_t> Corridor() {
  Grid2D<std::uint8_t> obstacles(MapLimits(kResolution, Eigen::Vector2d(-6.0, -6.0), 240, 240), 0);
  for (int i = 0; i < 240; ++i) {
    obstacles(i, 100) = 1;
    obstacles(i, 140) = 1;
  }
  return obstacles;
}

std::vector<Eigen::Vector2d> PointsSeenFrom(const Grid2D<std::uint8_t>& obstacles,
                                            const Pose2& T_a_b) {
  std::vector<Eigen::Vector2d> points_b;
  for (int j = 0; j < obstacles.Height(); ++j) {
    for (int i = 0; i < obstacles.Width(); ++i) {
      if (obstacles(i, j) != 0) {
        points_b.push_back(T_a_b.Inverse() * obstacles.Limits().CellCenter({i, j}));
      }
    }
  }
  return points_b;
}

TEST(PriorSearch, FindsATransformFarOutsideTheRefinementBasin) {
  const Grid2D<std::uint8_t> obstacles = Room();
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
  const Pose2 T_a_b(0.4, -0.3, 0.2);
  const std::vector<Eigen::Vector2d> points_b = PointsSeenFrom(obstacles, T_a_b);
  // The prediction is 1.6 m and 3 degrees off.
  const Pose2 prior = Pose2(1.3, -0.9, 0.0) * T_a_b * Pose2(0.0, 0.0, -0.05);
  const PriorSearchOptions options;
  const PriorSearchResult result = SearchAroundPrior(points_b, distance, prior, 2.5, 0.1, options);
  ASSERT_TRUE(result.ok) << result.score << " " << result.rival;
  // The best pose of the grid is within half a step of the truth per axis ...
  EXPECT_LT((result.T_a_b.translation() - T_a_b.translation()).norm(),
            0.75 * options.linear_step * std::sqrt(2.0));
  EXPECT_LT(std::abs(NormalizeAngle(result.T_a_b.theta() - T_a_b.theta())),
            0.75 * options.angular_step);
  EXPECT_GT(result.score, 0.7);
  EXPECT_LT(result.rival, options.max_ambiguity * result.score);
  EXPECT_GT(result.poses, 1000);
  // ... inside the basin of the refinement on the distance field.
  RefinementOptions refinement;
  refinement.max_distance = 0.5;
  const RefinementResult refined =
      RefineOnDistanceField(points_b, distance, result.T_a_b, refinement);
  ASSERT_TRUE(refined.ok);
  EXPECT_LT((refined.T_a_b.translation() - T_a_b.translation()).norm(), 0.01);
  EXPECT_LT(std::abs(NormalizeAngle(refined.T_a_b.theta() - T_a_b.theta())), 0.002);
}

TEST(PriorSearch, RefusesAPoseTheWindowDoesNotHold) {
  const Grid2D<std::uint8_t> obstacles = Room();
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
  const Pose2 T_a_b(0.4, -0.3, 0.2);
  const std::vector<Eigen::Vector2d> points_b = PointsSeenFrom(obstacles, T_a_b);
  const Pose2 prior = Pose2(1.3, -0.9, 0.0) * T_a_b;
  const PriorSearchResult result =
      SearchAroundPrior(points_b, distance, prior, 0.5, 0.1, PriorSearchOptions{});
  EXPECT_FALSE(result.ok) << result.score;
}

// A corridor is a ridge: every pose along it scores as well as the truth. Without ridge
// closures it is refused as ambiguous; with them it is accepted, with the axis along the
// corridor, and the offset across it and the heading measured.
TEST(PriorSearch, ACorridorIsARidgeAlongItsAxis) {
  const Grid2D<std::uint8_t> obstacles = Corridor();
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
  const Pose2 T_a_b(0.5, 0.1, 0.03);
  std::vector<Eigen::Vector2d> points_b = PointsSeenFrom(obstacles, T_a_b);
  // b saw only the middle part of the corridor.
  std::erase_if(points_b, [](const Eigen::Vector2d& p) { return std::abs(p.x()) > 3.0; });
  // The prediction is 1 m off along the corridor, 0.6 m across it and 0.06 rad.
  const Pose2 prior = Pose2(1.0, -0.6, 0.0) * T_a_b * Pose2(0.0, 0.0, -0.06);
  PriorSearchOptions refuse;
  refuse.ridge_closures = false;
  const PriorSearchResult refused = SearchAroundPrior(points_b, distance, prior, 2.5, 0.1, refuse);
  EXPECT_GT(refused.score, 0.9);
  EXPECT_FALSE(refused.ok) << refused.score << " " << refused.rival;
  EXPECT_FALSE(refused.ridge);

  const PriorSearchOptions options;
  for (const bool exhaustive : {false, true}) {
    const PriorSearchResult result =
        exhaustive ? SearchAroundPriorExhaustive(points_b, distance, prior, 2.5, 0.1, options)
                   : SearchAroundPrior(points_b, distance, prior, 2.5, 0.1, options);
    ASSERT_TRUE(result.ok) << exhaustive << ": " << result.score << " " << result.off_ridge;
    EXPECT_TRUE(result.ridge);
    EXPECT_GT(result.rival, options.max_ambiguity * result.score);
    EXPECT_LE(result.off_ridge, options.max_ambiguity * result.score);
    EXPECT_NEAR(std::abs(result.ridge_axis.x()), 1.0, 1e-9) << result.ridge_axis.transpose();
    EXPECT_NEAR(result.ridge_axis.norm(), 1.0, 1e-12);
    // Across the corridor and in rotation, the best pose of the grid is within a step.
    EXPECT_LT(std::abs(result.T_a_b.y() - T_a_b.y()), options.linear_step);
    EXPECT_LT(std::abs(NormalizeAngle(result.T_a_b.theta() - T_a_b.theta())), options.angular_step);
  }
}

// Two identical corridors side by side: the rival across is a second place, not a ridge.
TEST(PriorSearch, RefusesParallelCorridorsAsAmbiguous) {
  Grid2D<std::uint8_t> obstacles = Corridor();
  for (int i = 0; i < 240; ++i) {
    obstacles(i, 160) = 1;
    obstacles(i, 200) = 1;
  }
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
  const Pose2 T_a_b(0.5, 0.0, 0.0);
  std::vector<Eigen::Vector2d> points_b = PointsSeenFrom(obstacles, T_a_b);
  // b saw the first corridor only.
  std::erase_if(points_b, [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d q = T_a_b * p;
    return std::abs(p.x()) > 3.0 || q.y() > 1.1;
  });
  const Pose2 prior = Pose2(0.4, 1.4, 0.0) * T_a_b;
  for (const bool exhaustive : {false, true}) {
    const PriorSearchResult result =
        exhaustive ? SearchAroundPriorExhaustive(points_b, distance, prior, 3.5, 0.1, {})
                   : SearchAroundPrior(points_b, distance, prior, 3.5, 0.1, {});
    EXPECT_GT(result.score, 0.9) << exhaustive;
    EXPECT_FALSE(result.ok) << exhaustive << ": " << result.score << " " << result.off_ridge;
    EXPECT_FALSE(result.ridge) << exhaustive;
    EXPECT_GT(result.off_ridge, 0.85 * result.score) << exhaustive;
  }
}

// Branch and bound finds the exhaustive search's best score to the last bit (its leaves sum the
// same numbers in the same order), and the same verdict, over random predictions and windows up
// to 8 m and 0.3 rad, in a room and in a corridor, while scoring a fraction of the lattice.
TEST(PriorSearch, BranchAndBoundFindsTheExhaustiveBest) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> offset(-1.0, 1.0);
  const PriorSearchOptions options;
  long scored = 0;
  long poses = 0;
  int accepted = 0;
  int ridges = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const Grid2D<std::uint8_t> obstacles = trial % 3 == 2 ? Corridor() : Room();
    const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
    const Pose2 T_a_b(0.5 * offset(random), 0.5 * offset(random), 0.3 * offset(random));
    std::vector<Eigen::Vector2d> points_b = PointsSeenFrom(obstacles, T_a_b);
    const double keep = 2.0 + 3.0 * (offset(random) + 1.0);  // b saw part of a's area
    std::erase_if(points_b, [keep](const Eigen::Vector2d& p) { return p.norm() > keep; });
    const double window_xy = 1.0 + 3.5 * (offset(random) + 1.0);
    const double window_theta = 0.05 + 0.125 * (offset(random) + 1.0);
    const Pose2 prior = Pose2(window_xy * 0.7 * offset(random), window_xy * 0.7 * offset(random),
                              window_theta * 0.7 * offset(random)) *
                        T_a_b;
    const PriorSearchResult fast =
        SearchAroundPrior(points_b, distance, prior, window_xy, window_theta, options);
    const PriorSearchResult exhaustive =
        SearchAroundPriorExhaustive(points_b, distance, prior, window_xy, window_theta, options);
    ASSERT_EQ(fast.poses, exhaustive.poses) << trial;
    EXPECT_EQ(fast.ok, exhaustive.ok)
        << trial << ": " << exhaustive.score << " " << exhaustive.rival;
    EXPECT_EQ(fast.ridge, exhaustive.ridge) << trial;
    ridges += exhaustive.ridge ? 1 : 0;
    if (fast.ridge && exhaustive.ridge) {
      EXPECT_NEAR(std::abs(fast.ridge_axis.dot(exhaustive.ridge_axis)), 1.0, 1e-9) << trial;
    }
    if (exhaustive.score >= options.min_score) {
      EXPECT_EQ(fast.score, exhaustive.score) << trial;
    } else {
      EXPECT_LT(fast.score, options.min_score) << trial;
    }
    if (exhaustive.ok) {
      ++accepted;
      EXPECT_TRUE(fast.T_a_b.translation().isApprox(exhaustive.T_a_b.translation(), 1e-9) &&
                  std::abs(fast.T_a_b.theta() - exhaustive.T_a_b.theta()) < 1e-9)
          << trial;
    }
    scored += fast.scored;
    poses += fast.poses;
  }
  EXPECT_GE(accepted, 8);
  EXPECT_GE(ridges, 1);
  EXPECT_LT(scored, poses / 4);
}

// The second search covers the drift the arbiter allows (5 %), the first the usual one (2 %);
// both stop at the cap, so past it there is no second search.
TEST(PriorSearch, TheWideWindowCoversTheArbitersDriftUpToTheCap) {
  const PriorSearchOptions options;
  EXPECT_NEAR(options.WindowXy(100.0), 2.0, 1e-12);
  EXPECT_NEAR(options.WideWindowXy(100.0), 5.0, 1e-12);
  EXPECT_NEAR(options.WideWindowXy(1000.0), options.max_window_xy, 1e-12);
  EXPECT_NEAR(options.WindowXy(1000.0), options.max_window_xy, 1e-12);
  PriorSearchOptions none;
  none.wide_window_per_m = 0.0;
  EXPECT_EQ(none.WideWindowXy(100.0), 0.0);
  none.wide_window_per_m = -0.1;
  EXPECT_FALSE(none.Validate().ok());
}

// The cells a bound reads: a point's block cell clipped to the grid when the block's span
// reaches the grid, else the zero cell past the grid's end (width * height).
TEST(PriorSearch, BlockCellsClipsToTheGridOrReadsTheZeroCell) {
  constexpr int kWidth = 10;
  constexpr int kHeight = 7;
  constexpr int kZero = kWidth * kHeight;
  const std::vector<int> ci{3, -2, -4, 12, 9, 10, 0, -1};
  const std::vector<int> cj{2, 1, 1, 0, 6, 0, -2, -1};
  std::vector<int> cells(ci.size());
  // A block reaching 3 cells, moved by (1, 0): starts at x = 4, -1, -3, 13, 10, 11, 1, 0.
  internal::BlockCells(ci, cj, 1, 0, 3, kWidth, kHeight, cells);
  EXPECT_EQ(cells, (std::vector<int>{2 * kWidth + 4, 1 * kWidth + 0, kZero, kZero, kZero, kZero,
                                     0 * kWidth + 1, 0 * kWidth + 0}));
  // A leaf reaches one cell: a point left of or below the grid reads the zero cell.
  internal::BlockCells(ci, cj, 0, 0, 1, kWidth, kHeight, cells);
  EXPECT_EQ(cells, (std::vector<int>{2 * kWidth + 3, kZero, kZero, kZero, 6 * kWidth + 9, kZero,
                                     kZero, kZero}));

  // Against the branches it replaces, on random points around the grid.
  std::mt19937 random(5);
  std::uniform_int_distribution<int> coordinate(-40, 40);
  std::vector<int> xs(301);
  std::vector<int> ys(xs.size());
  for (std::size_t k = 0; k < xs.size(); ++k) {
    xs[k] = coordinate(random);
    ys[k] = coordinate(random);
  }
  cells.resize(xs.size());
  for (const int reach : {1, 4, 16, 64}) {
    for (const int shift : {-20, 0, 9}) {
      internal::BlockCells(xs, ys, shift, 2 * shift, reach, kWidth, kHeight, cells);
      for (std::size_t k = 0; k < xs.size(); ++k) {
        const int i = xs[k] + shift;
        const int j = ys[k] + 2 * shift;
        const bool hits = i < kWidth && j < kHeight && i + reach > 0 && j + reach > 0;
        EXPECT_EQ(cells[k], hits ? std::max(j, 0) * kWidth + std::max(i, 0) : kZero)
            << reach << " " << shift << " " << k;
      }
    }
  }
}

TEST(PriorSearch, MaxIntoKeepsTheLargerOfEachPair) {
  std::vector<float> out{0.0F, 0.5F, 1.0F, 0.25F, 0.75F};
  const std::vector<float> in{0.1F, 0.5F, 0.0F, 0.3F, 0.7F, 9.0F};
  internal::MaxInto(out, in);  // in's last value is past out's end: not read
  EXPECT_EQ(out, (std::vector<float>{0.1F, 0.5F, 1.0F, 0.3F, 0.75F}));
  internal::MaxInto(std::span<float>(out).first(2), std::span<const float>(in).subspan(4));
  EXPECT_EQ(out, (std::vector<float>{0.7F, 9.0F, 1.0F, 0.3F, 0.75F}));
}

TEST(PriorSearch, MaxOfKeepsTheLargerOfEachPair) {
  const std::vector<float> a{0.0F, 0.5F, 1.0F, 0.25F};
  const std::vector<float> b{0.1F, 0.5F, 0.0F, 0.3F, 9.0F};
  std::vector<float> out(a.size());
  internal::MaxOf(out, a, b);  // b's last value is past out's end: not read
  EXPECT_EQ(out, (std::vector<float>{0.1F, 0.5F, 1.0F, 0.3F}));
}

TEST(PriorSearch, ShiftedMaxPairsEachValueWithTheOneShiftFurtherOn) {
  const std::vector<float> in{0.2F, 0.9F, 0.1F, 0.4F, 0.3F};
  std::vector<float> out(in.size());
  internal::ShiftedMax(out, in, 2);
  EXPECT_EQ(out, (std::vector<float>{0.2F, 0.9F, 0.3F, 0.4F, 0.3F}));
  internal::ShiftedMax(out, in, 0);
  EXPECT_EQ(out, in);
  internal::ShiftedMax(out, in, 7);  // beyond the end: every value alone
  EXPECT_EQ(out, in);
}

TEST(PriorSearch, TruncatedScoresFallFromOneOnObstaclesToZeroAtTheTruncation) {
  const std::vector<float> distance{0.0F, 0.15F, 0.3F, 0.45F, -1.0F};
  std::vector<float> score(distance.size(), 9.0F);
  internal::TruncatedScores(distance, static_cast<float>(1.0 / 0.3), score);
  EXPECT_EQ(score[0], 1.0F);
  EXPECT_EQ(score[1], 1.0F - 0.15F * static_cast<float>(1.0 / 0.3));
  EXPECT_EQ(score[2], 0.0F);
  EXPECT_EQ(score[3], 0.0F);  // beyond the truncation
  EXPECT_EQ(score[4], 0.0F);  // unknown
}

TEST(PriorSearch, FirstStepAtLeastIsTheFirstLatticeStepReachingTheBound) {
  EXPECT_EQ(internal::FirstStepAtLeast(5, 4, 0), 0);
  EXPECT_EQ(internal::FirstStepAtLeast(0, 4, 0), 0);
  EXPECT_EQ(internal::FirstStepAtLeast(-1, 4, 0), 1);
  EXPECT_EQ(internal::FirstStepAtLeast(-4, 4, 0), 1);
  EXPECT_EQ(internal::FirstStepAtLeast(-5, 4, 0), 2);
  EXPECT_EQ(internal::FirstStepAtLeast(3, 4, 10), 2);  // 3, 7, 11
  EXPECT_EQ(internal::FirstStepAtLeast(2, 4, 10), 2);  // 2, 6, 10
  EXPECT_EQ(internal::FirstStepAtLeast(-7, 1, 3), 10);
  // Far below the bound: no overflow.
  EXPECT_EQ(internal::FirstStepAtLeast(std::numeric_limits<int>::min(), 1, 100),
            std::numeric_limits<int>::max());
  for (int start = -30; start <= 30; ++start) {
    for (const int step : {1, 3, 4}) {
      int u = 0;
      while (start + u * step < 7) {
        ++u;
      }
      EXPECT_EQ(internal::FirstStepAtLeast(start, step, 7), u) << start << " " << step;
    }
  }
}

}  // namespace
}  // namespace gridslam::loop_closure
