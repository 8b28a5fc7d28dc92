#include "gridslam/distance_transform/euclidean_distance_transform.hpp"

#include <cmath>
#include <random>
#include <utility>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace gridslam::distance_transform {
namespace {

// Brute force: squared distance from every cell to every source.
std::vector<float> BruteForce(const std::vector<std::uint8_t>& src, int w, int h) {
  std::vector<float> out(src.size(), kInfinity);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      for (int q = 0; q < h; ++q) {
        for (int p = 0; p < w; ++p) {
          if (src[static_cast<std::size_t>(q * w + p)] != 0) {
            const auto d = static_cast<float>((i - p) * (i - p) + (j - q) * (j - q));
            float& o = out[static_cast<std::size_t>(j * w + i)];
            o = std::min(o, d);
          }
        }
      }
    }
  }
  return out;
}

std::vector<std::uint8_t> RandomGrid(int w, int h, double density, std::mt19937& rng) {
  std::bernoulli_distribution bit(density);
  std::vector<std::uint8_t> src(static_cast<std::size_t>(w * h));
  for (auto& s : src) {
    s = bit(rng) ? 1 : 0;
  }
  return src;
}

TEST(SquaredDistance1D, MatchesBruteForceOnSampledFunctions) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(0.0F, 30.0F);
  std::bernoulli_distribution finite(0.3);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 40;
    std::vector<float> f(static_cast<std::size_t>(n));
    for (auto& x : f) {
      x = finite(rng) ? std::round(value(rng)) : kInfinity;
    }
    std::vector<float> d(f.size());
    std::vector<int32_t> arg(f.size()), v(f.size());
    std::vector<float> z(f.size() + 1);
    SquaredDistance1D(f.data(), n, d.data(), arg.data(), v.data(), z.data());
    for (int q = 0; q < n; ++q) {
      float best = kInfinity;
      for (int p = 0; p < n; ++p) {
        best =
            std::min(best, static_cast<float>((q - p) * (q - p)) + f[static_cast<std::size_t>(p)]);
      }
      const auto uq = static_cast<std::size_t>(q);
      ASSERT_EQ(d[uq], best) << "trial " << trial << " q " << q;
      if (best < kInfinity) {
        const int p = arg[uq];
        ASSERT_GE(p, 0);
        EXPECT_EQ(static_cast<float>((q - p) * (q - p)) + f[static_cast<std::size_t>(p)], best);
      } else {
        EXPECT_EQ(arg[uq], -1);
      }
    }
  }
}

TEST(SquaredEuclideanDistanceTransform, EqualsBruteForceOnRandomGrids) {
  std::mt19937 rng(42);
  const double densities[] = {0.0, 0.002, 0.02, 0.1, 0.5, 1.0};
  for (int trial = 0; trial < 24; ++trial) {
    const int w = 1 + static_cast<int>(rng() % 37);
    const int h = 1 + static_cast<int>(rng() % 29);
    const auto src = RandomGrid(w, h, densities[trial % 6], rng);
    SquaredDistanceField field;
    SquaredEuclideanDistanceTransform(src.data(), w, h, field, /*with_nearest=*/true);
    const auto expected = BruteForce(src, w, h);
    for (std::size_t k = 0; k < src.size(); ++k) {
      ASSERT_EQ(field.squared[k], expected[k]) << "trial " << trial << " cell " << k;
      const int32_t n = field.nearest[k];
      if (expected[k] == kInfinity) {
        EXPECT_EQ(n, -1);
        continue;
      }
      ASSERT_GE(n, 0);
      ASSERT_NE(src[static_cast<std::size_t>(n)], 0) << "label is not a source";
      const int di = static_cast<int>(k) % w - n % w;
      const int dj = static_cast<int>(k) / w - n / w;
      EXPECT_EQ(static_cast<float>(di * di + dj * dj), expected[k]);
    }
  }
}

TEST(SquaredEuclideanDistanceTransform, TruncationKeepsDistancesBelowTheLimitExact) {
  std::mt19937 rng(3);
  const int w = 60;
  const int h = 45;
  const auto src = RandomGrid(w, h, 0.004, rng);
  const auto expected = BruteForce(src, w, h);
  SquaredDistanceField field;
  SquaredEuclideanDistanceTransform(src.data(), w, h, field, true, 6.5F);
  for (std::size_t k = 0; k < src.size(); ++k) {
    if (expected[k] <= 6.5F * 6.5F) {
      EXPECT_EQ(field.squared[k], expected[k]);
      EXPECT_GE(field.nearest[k], 0);
    } else {
      EXPECT_EQ(field.squared[k], kInfinity);
      EXPECT_EQ(field.nearest[k], -1);
    }
  }
}

// The transform's integer row pass and the float envelope of SquaredDistance1D give the same
// distances and the same nearest sources, bit for bit (the mapper's and the front end's results
// depend on them), truncated or not, on sparse and dense grids of many shapes (dense random
// grids are full of ties between equidistant sources).
TEST(SquaredEuclideanDistanceTransform, IntegerAndFloatEnvelopesGiveTheSameDistancesAndLabels) {
  std::mt19937 rng(11);
  long cells = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int w = std::uniform_int_distribution<int>(1, 320)(rng);
    const int h = std::uniform_int_distribution<int>(1, 320)(rng);
    const double density = std::pow(10.0, std::uniform_real_distribution<double>(-4.0, -0.3)(rng));
    std::bernoulli_distribution source(density);
    std::vector<std::uint8_t> src(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (auto& c : src) {
      c = source(rng) ? 1 : 0;
    }
    const float max_distance =
        trial % 3 == 0 ? kInfinity : std::uniform_real_distribution<float>(0.5F, 60.0F)(rng);
    for (const bool labels : {false, true}) {
      SquaredDistanceField fast;
      SquaredDistanceField reference;
      SquaredEuclideanDistanceTransform(src.data(), w, h, fast, labels, max_distance);
      SquaredEuclideanDistanceTransformFloat(src.data(), w, h, reference, labels, max_distance);
      ASSERT_EQ(fast.squared.size(), reference.squared.size());
      ASSERT_EQ(fast.nearest.size(), reference.nearest.size());
      for (std::size_t k = 0; k < fast.squared.size(); ++k) {
        ASSERT_EQ(fast.squared[k], reference.squared[k])
            << "trial " << trial << " " << w << "x" << h << " cell " << k;
      }
      for (std::size_t k = 0; k < fast.nearest.size(); ++k) {
        ASSERT_EQ(fast.nearest[k], reference.nearest[k])
            << "trial " << trial << " " << w << "x" << h << " cell " << k;
      }
    }
    cells += static_cast<long>(src.size());
  }
  EXPECT_GT(cells, 1'000'000);
}

// A band of rows (what the matching field recomputes around a change) holds the numbers of the
// same rows of the whole transform, labels included, whatever the band, the truncation and the
// grid.
TEST(SquaredEuclideanDistanceTransform, RowsAreThoseOfTheWholeTransform) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 200; ++trial) {
    const int w = std::uniform_int_distribution<int>(1, 120)(rng);
    const int h = std::uniform_int_distribution<int>(1, 120)(rng);
    const double density = std::pow(10.0, std::uniform_real_distribution<double>(-3.0, -0.3)(rng));
    const std::vector<std::uint8_t> src = RandomGrid(w, h, density, rng);
    const float max_distance =
        trial % 3 == 0 ? kInfinity : std::uniform_real_distribution<float>(0.5F, 30.0F)(rng);
    int row0 = std::uniform_int_distribution<int>(0, h)(rng);
    int row1 = std::uniform_int_distribution<int>(0, h)(rng);
    if (row0 > row1) {
      std::swap(row0, row1);
    }
    for (const bool labels : {false, true}) {
      SquaredDistanceField whole;
      SquaredDistanceField band;
      SquaredEuclideanDistanceTransform(src.data(), w, h, whole, labels, max_distance);
      SquaredEuclideanDistanceTransformRows(src.data(), w, h, row0, row1, band, labels,
                                            max_distance);
      ASSERT_EQ(band.width, w);
      ASSERT_EQ(band.height, row1 - row0);
      const auto offset = static_cast<std::size_t>(row0) * static_cast<std::size_t>(w);
      ASSERT_EQ(band.squared.size(), static_cast<std::size_t>(row1 - row0) * w);
      ASSERT_EQ(band.nearest.size(), labels ? band.squared.size() : 0);
      for (std::size_t k = 0; k < band.squared.size(); ++k) {
        ASSERT_EQ(band.squared[k], whole.squared[offset + k])
            << "trial " << trial << " " << w << "x" << h << " rows " << row0 << "-" << row1;
      }
      for (std::size_t k = 0; k < band.nearest.size(); ++k) {
        ASSERT_EQ(band.nearest[k], whole.nearest[offset + k])
            << "trial " << trial << " " << w << "x" << h << " rows " << row0 << "-" << row1;
      }
    }
  }
}

TEST(DistanceTransformCells, AgreesWithOpenCvPrecise) {
  std::mt19937 rng(11);
  cv::Mat image(64, 80, CV_8U);
  std::bernoulli_distribution obstacle(0.03);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      image.at<std::uint8_t>(r, c) = obstacle(rng) ? 0 : 255;
    }
  }
  const cv::Mat ours = DistanceTransformCells(image);
  cv::Mat theirs;
  cv::distanceTransform(image, theirs, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  ASSERT_EQ(ours.type(), CV_32F);
  EXPECT_LT(cv::norm(ours, theirs, cv::NORM_INF), 1e-4);
}

TEST(DistanceTransformMetres, ScalesByResolutionAndReportsNoSourceAsInfinity) {
  Grid2D<std::uint8_t> grid(MapLimits(0.05, Eigen::Vector2d(1.0, -2.0), 10, 8), 0);
  Grid2D<float> empty = DistanceTransformMetres(grid);
  EXPECT_EQ(empty(3, 3), kInfinity);
  grid(2, 3) = 1;
  const Grid2D<float> d = DistanceTransformMetres(grid);
  EXPECT_FLOAT_EQ(d(2, 3), 0.0F);
  EXPECT_NEAR(d(5, 7), 0.05 * 5.0, 1e-6);  // (3, 4) cells away
  EXPECT_NEAR(d.Limits().Origin().x(), 1.0, 1e-12);
}

TEST(DistanceToImage, ClampsAtTheFixedMaximum) {
  cv::Mat d = (cv::Mat_<float>(1, 4) << 0.0F, 0.5F, 1.0F, 7.0F);
  const cv::Mat image = DistanceToImage(d, 1.0);
  EXPECT_EQ(image.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(image.at<std::uint8_t>(0, 1), 128);
  EXPECT_EQ(image.at<std::uint8_t>(0, 2), 255);
  EXPECT_EQ(image.at<std::uint8_t>(0, 3), 255);
}

}  // namespace
}  // namespace gridslam::distance_transform
