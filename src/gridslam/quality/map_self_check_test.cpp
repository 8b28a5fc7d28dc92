#include "gridslam/quality/map_self_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "gridslam/grid/log_odds.hpp"
#include "gridslam/quality/quality_image.hpp"

namespace gridslam::quality {
namespace {

// A closed rectangular room [-6, 6] x [-3, 3] with a 2 m pillar wall at x = 0, y in [1, 3].
// Returns the range along the ray from `o` in direction `d` (unit) to the first wall.
double RayRange(const Eigen::Vector2d& o, const Eigen::Vector2d& d) {
  double best = std::numeric_limits<double>::infinity();
  const auto hit_x = [&](double x, double y_lo, double y_hi) {
    if (std::abs(d.x()) < 1e-12) return;
    const double t = (x - o.x()) / d.x();
    const double y = o.y() + t * d.y();
    if (t > 1e-9 && y >= y_lo && y <= y_hi) best = std::min(best, t);
  };
  const auto hit_y = [&](double y, double x_lo, double x_hi) {
    if (std::abs(d.y()) < 1e-12) return;
    const double t = (y - o.y()) / d.y();
    const double x = o.x() + t * d.x();
    if (t > 1e-9 && x >= x_lo && x <= x_hi) best = std::min(best, t);
  };
  hit_x(-6.0, -3.0, 3.0);
  hit_x(6.0, -3.0, 3.0);
  hit_y(-3.0, -6.0, 6.0);
  hit_y(3.0, -6.0, 6.0);
  hit_x(0.0, 1.0, 3.0);
  return best;
}

// A 360-beam scan of the room from the true pose `T_world_laser`.
LaserScan RoomScan(const Pose2& T_world_laser) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi;
  scan.angle_increment = 2.0 * std::numbers::pi / 360.0;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  for (int k = 0; k < 360; ++k) {
    const double a = T_world_laser.theta() + scan.Angle(static_cast<std::size_t>(k));
    scan.ranges.push_back(static_cast<float>(
        RayRange(T_world_laser.translation(), Eigen::Vector2d(std::cos(a), std::sin(a)))));
  }
  return scan;
}

// The robot drives along y = -1.5 to the right, then back along y = -0.5 (true poses).
std::vector<Pose2> TruePoses() {
  std::vector<Pose2> poses;
  for (double x = -5.0; x <= 5.0; x += 0.25) poses.emplace_back(x, -1.5, 0.0);
  for (double x = 5.0; x >= -5.0; x -= 0.25) poses.emplace_back(x, -0.5, std::numbers::pi);
  return poses;
}

struct SimRun {
  std::vector<LaserScan> scans;
  std::vector<fusion::PosedScan> posed;
};

// Scans from the true poses, placed at the estimated poses: the way back is estimated with a
// yaw error `yaw` [rad] about the turning point and an offset `shift` [m] along y.
SimRun MakeRun(double yaw, double shift) {
  const std::vector<Pose2> truth = TruePoses();
  SimRun run;
  run.scans.reserve(truth.size());
  for (const Pose2& p : truth) run.scans.push_back(RoomScan(p));
  const std::size_t half = truth.size() / 2;
  const Pose2 pivot(5.0, -1.0, 0.0);
  const Pose2 error = pivot * Pose2(0.0, shift, yaw) * pivot.Inverse();
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const Pose2 estimate = k < half ? truth[k] : error * truth[k];
    run.posed.push_back({estimate, Pose2(), &run.scans[k]});
  }
  return run;
}

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
  a.returns = 10;
  a.agreeing = 9;
  a.contradicting = 1;
  a.distance_sum = 0.5;
  SelfCheckStats b;
  b.returns = 30;
  b.agreeing = 15;
  b.contradicting = 3;
  b.distance_sum = 1.5;
  a.Merge(b);
  EXPECT_EQ(a.returns, 40);
  EXPECT_DOUBLE_EQ(a.Score(), 24.0 / 40.0);
  EXPECT_DOUBLE_EQ(a.Contradiction(), 4.0 / 40.0);
  EXPECT_DOUBLE_EQ(a.MeanDistance(), 2.0 / 40.0);
  SelfCheckOptions options;
  options.suspect_below = 0.6;
  EXPECT_FALSE(a.Suspect(options));
  options.suspect_below = 0.61;
  EXPECT_TRUE(a.Suspect(options));
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
}

}  // namespace
}  // namespace gridslam::quality
