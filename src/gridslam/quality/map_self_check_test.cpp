#include "gridslam/quality/map_self_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "gridslam/grid/log_odds.hpp"
#include "gridslam/quality/local_confirmation.hpp"
#include "gridslam/quality/quality_image.hpp"
#include "gridslam/quality/self_check_room_testing.hpp"

namespace gridslam::quality {
namespace {

using testing::MakeRun;
using testing::SimRun;
using testing::TruePoses;

SelfCheckResult Check(const SimRun& run) {
  const fusion::FusionOptions fusion;
  const Grid2D<float> map = fusion::FuseScans(run.posed, fusion);
  SelfCheckOptions options;
  options.min_motion = 0.0;  // replay every scan
  return CheckMap(map, run.posed, fusion, options);
}

TEST(MapSelfCheck, ConsistentMapScoresNearOne) {
  const SelfCheckResult r = Check(MakeRun(0.0, 0.0));
  EXPECT_EQ(r.stats.scans, static_cast<long>(TruePoses().size()));
  EXPECT_GT(r.stats.returns, 20000);
  EXPECT_EQ(r.stats.outside, 0);
  EXPECT_GT(r.stats.Score(), 0.97);
  EXPECT_LT(r.stats.Contradiction(), 0.01);
  EXPECT_LT(r.stats.MeanDistance(), 0.03);
  EXPECT_FALSE(r.stats.Suspect(SelfCheckOptions{}));
}

TEST(MapSelfCheck, DoubleWallsFromAYawErrorLowerTheScore) {
  const double good = Check(MakeRun(0.0, 0.0)).stats.Score();
  const SelfCheckResult bad = Check(MakeRun(5.0 * std::numbers::pi / 180.0, 0.0));
  EXPECT_LT(bad.stats.Score(), good - 0.1);
  EXPECT_GT(bad.stats.Contradiction(), 0.05);
  EXPECT_GT(bad.stats.MeanDistance(), 0.05);
  EXPECT_TRUE(bad.stats.Suspect(SelfCheckOptions{}));
}

TEST(MapSelfCheck, TheScoreFallsAsTheErrorGrows) {
  double previous = 2.0;
  for (const double shift : {0.0, 0.1, 0.3, 0.6}) {
    const double score = Check(MakeRun(0.0, shift)).stats.Score();
    EXPECT_LT(score, previous) << "shift " << shift;
    previous = score;
  }
}

// The self-check as the mapper runs it: the returns their own stretch confirms, then the map.
SelfCheckResult CheckConfirmed(const SimRun& run) {
  const fusion::FusionOptions fusion;
  const Grid2D<float> map = fusion::FuseScans(run.posed, fusion);
  SelfCheckOptions options;
  options.min_motion = 0.0;
  const auto confirmed = LocalConfirmation(run.posed, fusion, options);
  return CheckMap(map, run.posed, fusion, options, &confirmed);
}

TEST(MapSelfCheck, PassersByLowerTheRawScoreButNotTheScore) {
  const SelfCheckResult clean = CheckConfirmed(MakeRun(0.0, 0.0));
  SimRun run = MakeRun(0.0, 0.0);
  // Every fourth scan of the way out sees someone 1 m ahead, over 20 beams, gone a moment later.
  for (std::size_t s = 2; s < 40; s += 4) {
    for (std::size_t k = 170; k <= 190; ++k) run.scans[s].ranges[k] = 1.0F;
  }
  const SelfCheckResult crowded = CheckConfirmed(run);
  EXPECT_LT(crowded.stats.RawScore(), clean.stats.RawScore() - 0.005);
  EXPECT_LT(crowded.stats.LocalScore(), clean.stats.LocalScore() - 0.005);
  EXPECT_NEAR(crowded.stats.Score(), clean.stats.Score(), 0.002);
  EXPECT_GT(crowded.stats.Score(), 0.97);
}

TEST(MapSelfCheck, ConfirmedReturnsStillSeeTheDoubleWalls) {
  const SelfCheckResult good = CheckConfirmed(MakeRun(0.0, 0.0));
  const SelfCheckResult bad = CheckConfirmed(MakeRun(5.0 * std::numbers::pi / 180.0, 0.0));
  EXPECT_GT(bad.stats.LocalScore(), 0.97);  // each leg agrees with itself
  EXPECT_LT(bad.stats.Score(), good.stats.Score() - 0.1);
  const SelfCheckResult shifted = CheckConfirmed(MakeRun(0.0, 0.3));
  EXPECT_LT(shifted.stats.Score(), good.stats.Score() - 0.1);
  EXPECT_TRUE(bad.stats.Suspect(SelfCheckOptions{}));
  EXPECT_FALSE(good.stats.Suspect(SelfCheckOptions{}));
}

TEST(MapSelfCheck, WithoutConfirmationEveryReturnCounts) {
  const SelfCheckResult r = Check(MakeRun(0.0, 0.3));
  EXPECT_EQ(r.stats.confirmed, r.stats.returns);
  EXPECT_EQ(r.stats.confirmed_agreeing, r.stats.agreeing);
  EXPECT_DOUBLE_EQ(r.stats.Score(), r.stats.RawScore());
  EXPECT_DOUBLE_EQ(r.stats.LocalScore(), 1.0);
}

TEST(MapSelfCheck, RangeBandsPartitionTheReturns) {
  // The room is 12 m x 6 m: its returns lie within 5 m or between 5 and 13 m, none beyond 20 m.
  const SelfCheckResult r = Check(MakeRun(0.0, 0.0));
  long returns = 0;
  long agreeing = 0;
  for (int b = 0; b < SelfCheckStats::kRangeBands; ++b) {
    returns += r.stats.band_returns[static_cast<std::size_t>(b)];
    agreeing += r.stats.band_agreeing[static_cast<std::size_t>(b)];
  }
  EXPECT_EQ(returns, r.stats.returns);
  EXPECT_EQ(agreeing, r.stats.agreeing);
  EXPECT_GT(r.stats.band_returns[0], 0);
  EXPECT_GT(r.stats.band_returns[1], 0);
  EXPECT_EQ(r.stats.band_returns[3], 0);
  EXPECT_DOUBLE_EQ(r.stats.BandScore(3), 1.0);
  EXPECT_GT(r.stats.BandScore(0), 0.97);
  EXPECT_EQ(SelfCheckStats::RangeBand(4.99), 0);
  EXPECT_EQ(SelfCheckStats::RangeBand(5.0), 1);
  EXPECT_EQ(SelfCheckStats::RangeBand(25.0), 3);
}

TEST(MapSelfCheck, SpacingSkipsScansOnTheCorrectedTrajectory) {
  const SimRun run = MakeRun(0.0, 0.0);
  const fusion::FusionOptions fusion;
  const Grid2D<float> map = fusion::FuseScans(run.posed, fusion);
  SelfCheckOptions options;
  options.min_motion = 0.5;     // every second pose (0.25 m apart)
  options.min_rotation = 10.0;  // the U-turn alone does not count
  const SelfCheckResult r = CheckMap(map, run.posed, fusion, options);
  EXPECT_EQ(r.stats.scans, 42);  // 41 poses per leg, spacing 0.5 m: 21 + 21 (the turn moves 1 m)
}

TEST(MapSelfCheck, HeatLayerMarksTheDisagreeingArea) {
  const SelfCheckResult bad = Check(MakeRun(0.0, 0.5));
  const SelfCheckOptions options;
  const TiledGrid<float> share = DisagreementShare(bad, options);
  // The far (left) wall is drawn twice 0.5 m apart after the shift; the right wall near the pivot
  // less so. Compare the share near the left wall with the share near the bottom-right corner.
  const MapLimits& l = share.Limits();
  float left = 0.0F;
  for (double y = -2.5; y <= 2.5; y += 0.05) {
    for (double x = -6.2; x <= -5.3; x += 0.05) {
      const Eigen::Array2i c = l.CellIndex({x, y});
      if (l.Contains(c)) left = std::max(left, share.Get(c));
    }
  }
  EXPECT_GT(left, 0.4);
  const SelfCheckResult good = Check(MakeRun(0.0, 0.0));
  const TiledGrid<float> good_share = DisagreementShare(good, options);
  float good_max = 0.0F;
  const Grid2D<float> good_dense = good_share.ToDense();
  for (const float v : good_dense.Cells()) good_max = std::max(good_max, v);
  EXPECT_LT(good_max, left);
  const SimRun run = MakeRun(0.0, 0.0);
  const fusion::FusionOptions fusion;
  const OccupancyImage map = fusion::ToOccupancy(fusion::FuseScans(run.posed, fusion), fusion);
  const cv::Mat image = RenderQualityImage(map, good_share);
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.rows, map.Height());
  EXPECT_EQ(image.cols, map.Width());
}

TEST(MapSelfCheck, HeatLayerIsAReflectedGaussianBlurWhateverTheThreads) {
  const SelfCheckResult bad = Check(MakeRun(0.0, 0.5));
  const SelfCheckOptions options;
  const TiledGrid<float> one = DisagreementShare(bad, options, 0.02F, 1);
  const TiledGrid<float> three = DisagreementShare(bad, options, 0.02F, 3);
  const Grid2D<float> a = one.ToDense();
  const Grid2D<float> b = three.ToDense();
  ASSERT_EQ(a.Cells().size(), b.Cells().size());
  EXPECT_TRUE(std::equal(a.Cells().begin(), a.Cells().end(), b.Cells().begin()));
  // The reference: OpenCV's blur of the whole grids, reflected at the edges (BORDER_REFLECT_101).
  const Grid2D<float> returns = bad.returns_per_cell.ToDense();
  const Grid2D<float> disagreeing = bad.disagreeing_per_cell.ToDense();
  const int w = returns.Width();
  const int h = returns.Height();
  cv::Mat r(h, w, CV_32F, const_cast<float*>(returns.Cells().data()));
  cv::Mat d(h, w, CV_32F, const_cast<float*>(disagreeing.Cells().data()));
  const double sigma = options.heat_radius / returns.Limits().Resolution();
  cv::Mat rb;
  cv::Mat db;
  cv::GaussianBlur(r, rb, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT_101);
  cv::GaussianBlur(d, db, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT_101);
  int compared = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const float rr = rb.at<float>(j, i);
      if (rr < 0.05F) {
        continue;  // near the 0.02 threshold the two summation orders may disagree
      }
      ++compared;
      const float expected = std::clamp(db.at<float>(j, i) / rr, 0.0F, 1.0F);
      ASSERT_NEAR(one.Get(i, j), expected, 1e-4) << "cell " << i << ", " << j;
    }
  }
  EXPECT_GT(compared, 1000);
}

TEST(MapSelfCheck, QualityImageIsTheSameFromEitherMapAndWhateverTheThreads) {
  const SimRun run = MakeRun(0.0, 0.5);
  const fusion::FusionOptions fusion;
  const Grid2D<float> log_odds = fusion::FuseScans(run.posed, fusion);
  const SelfCheckResult bad = CheckMap(log_odds, run.posed, fusion, SelfCheckOptions{});
  const TiledGrid<float> share = DisagreementShare(bad, SelfCheckOptions{});
  const OccupancyImage map = fusion::ToOccupancy(log_odds, fusion);
  const cv::Mat one = RenderQualityImage(map, share, 1);
  const cv::Mat three =
      RenderQualityImage(TiledGrid<float>::FromDense(log_odds, kUnknownLogOdds), fusion, share, 3);
  ASSERT_EQ(one.size(), three.size());
  EXPECT_EQ(cv::norm(one, three, cv::NORM_INF), 0.0);
  // Every pixel: the map's grey, blended towards red by twice the share (row 0 at the top).
  int red = 0;
  for (int j = 0; j < map.Height(); ++j) {
    for (int i = 0; i < map.Width(); ++i) {
      const signed char v = map(i, j);
      const double g = v == kOccupiedCell ? 0.0 : (v == kFreeCell ? 255.0 : 205.0);
      const float s = share.Get(i, j);
      const double a = s > 0.0F ? std::min(1.0, 2.0 * s) : 0.0;
      const cv::Vec3b expected(static_cast<std::uint8_t>((1.0 - a) * g),
                               static_cast<std::uint8_t>((1.0 - a) * g),
                               static_cast<std::uint8_t>((1.0 - a) * g + a * 255.0));
      ASSERT_EQ(one.at<cv::Vec3b>(map.Height() - 1 - j, i), expected) << i << ", " << j;
      red += a > 0.5 ? 1 : 0;
    }
  }
  EXPECT_GT(red, 10);
}

TEST(SelfCheckStats, SharesAndMerge) {
  SelfCheckStats a;
  EXPECT_DOUBLE_EQ(a.Score(), 1.0);
  EXPECT_DOUBLE_EQ(a.Contradiction(), 0.0);
  EXPECT_DOUBLE_EQ(a.RawScore(), 1.0);
  EXPECT_DOUBLE_EQ(a.LocalScore(), 1.0);
  a.returns = 10;
  a.agreeing = 9;
  a.confirmed = 10;
  a.confirmed_agreeing = 9;
  a.contradicting = 1;
  a.distance_sum = 0.5;
  SelfCheckStats b;
  b.returns = 30;
  b.agreeing = 15;
  b.confirmed = 20;
  b.confirmed_agreeing = 15;
  b.contradicting = 3;
  b.distance_sum = 1.5;
  a.Merge(b);
  EXPECT_EQ(a.returns, 40);
  EXPECT_EQ(a.confirmed, 30);
  EXPECT_DOUBLE_EQ(a.RawScore(), 24.0 / 40.0);
  EXPECT_DOUBLE_EQ(a.LocalScore(), 30.0 / 40.0);
  EXPECT_DOUBLE_EQ(a.Score(), 24.0 / 30.0);
  EXPECT_DOUBLE_EQ(a.Contradiction(), 4.0 / 40.0);
  EXPECT_DOUBLE_EQ(a.MeanDistance(), 2.0 / 40.0);
  SelfCheckOptions options;
  options.suspect_below = 0.75;  // score 0.8, local score 0.75
  EXPECT_FALSE(a.Suspect(options));
  options.suspect_below = 0.76;
  EXPECT_TRUE(a.Suspect(options));
}

TEST(SelfCheckStats, VerdictJudgesTheScoreThenTheLocalScore) {
  const SelfCheckOptions options;  // suspect_below 0.8
  SelfCheckStats s;
  EXPECT_EQ(s.Verdict(options), SelfCheckVerdict::kConsistent);
  s.returns = 100;
  s.agreeing = 85;
  s.confirmed = 90;
  s.confirmed_agreeing = 81;  // score 0.9, local score 0.9
  EXPECT_EQ(s.Verdict(options), SelfCheckVerdict::kConsistent);
  EXPECT_FALSE(s.Suspect(options));
  s.confirmed_agreeing = 70;  // score 0.78
  EXPECT_EQ(s.Verdict(options), SelfCheckVerdict::kContradicted);
  s.confirmed = 70;  // local score 0.7, score 1: what is confirmed agrees, but too little is
  EXPECT_EQ(s.Verdict(options), SelfCheckVerdict::kUnconfirmed);
  EXPECT_TRUE(s.Suspect(options));
  EXPECT_EQ(ToString(SelfCheckVerdict::kUnconfirmed), "unconfirmed");
  EXPECT_EQ(ToString(SelfCheckVerdict::kContradicted), "contradicted");
  EXPECT_EQ(ToString(SelfCheckVerdict::kConsistent), "consistent");
}

TEST(SelfCheckOptions, ValidateRejectsBadValues) {
  EXPECT_TRUE(SelfCheckOptions{}.Validate().ok());
  SelfCheckOptions o;
  o.agreement_distance = 0.0;
  EXPECT_FALSE(o.Validate().ok());
  o = SelfCheckOptions{};
  o.distance_clamp = 0.05;
  EXPECT_FALSE(o.Validate().ok());
  o = SelfCheckOptions{};
  o.suspect_below = 1.5;
  EXPECT_FALSE(o.Validate().ok());
  o = SelfCheckOptions{};
  o.min_motion = -1.0;
  EXPECT_FALSE(o.Validate().ok());
  o = SelfCheckOptions{};
  o.local_travel = -1.0;
  EXPECT_FALSE(o.Validate().ok());
  o.local_travel = 0.0;  // off
  EXPECT_TRUE(o.Validate().ok());
}

}  // namespace
}  // namespace gridslam::quality
