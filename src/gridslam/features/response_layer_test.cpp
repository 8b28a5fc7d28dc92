#include "gridslam/features/internal/response_layer.hpp"

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace gridslam::features::internal {
namespace {

cv::Mat SmoothNoise(int width, int height, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(0, 255);
  cv::Mat image(height, width, CV_8UC1);
  for (std::uint8_t& pixel : cv::Mat_<std::uint8_t>(image)) {
    pixel = static_cast<std::uint8_t>(value(rng));
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.5);
  return image;
}

// The row loops (vectorised, also as an AVX2 clone) give the per-pixel formula's det(H_approx)
// at every sample where the filter fits, and only there.
TEST(ResponseLayerTest, ComputeMatchesPerPixelHessian) {
  const IntegralImage integral(SmoothNoise(131, 97, 1));
  for (const int step : {1, 2, 4, 8}) {
    for (const int size : {9, 15, 27, 51}) {
      ResponseLayer layer;
      layer.Compute(integral, size, step);
      const int b = (size - 1) / 2;
      EXPECT_GE(layer.k0() * step - b, 0);
      EXPECT_LT((layer.k0() - 1) * step - b, 0);
      EXPECT_LE(layer.k1() * step + b, 130);
      EXPECT_GT((layer.k1() + 1) * step + b, 130);
      EXPECT_LE(layer.m1() * step + b, 96);
      EXPECT_GT((layer.m1() + 1) * step + b, 96);
      for (int m = layer.m0(); m <= layer.m1(); ++m) {
        for (int k = layer.k0(); k <= layer.k1(); ++k) {
          const float expected = HessianAt(integral, k * step, m * step, Geometry(size)).Det();
          ASSERT_NEAR(layer.At(k, m), expected, 1e-6F * (1.0F + std::abs(expected)))
              << size << " " << step << " " << k << " " << m;
        }
      }
    }
  }
}

// Every step's rows give bit for bit the same responses at the same pixels: the unit-step rows
// (from per-column differences, vectorised), the dense rows of steps 2 to 4 and the strided rows
// of step 8 (the per-sample box sums) compute the same integer sums and the same float operations.
TEST(ResponseLayerTest, EveryStepGivesTheSameBits) {
  const IntegralImage integral(SmoothNoise(157, 83, 3));
  for (const int size : {9, 15, 27, 51}) {
    ResponseLayer unit;
    unit.Compute(integral, size, 1);
    for (const int step : {2, 3, 4, 8}) {
      ResponseLayer layer;
      layer.Compute(integral, size, step);
      for (int m = layer.m0(); m <= layer.m1(); ++m) {
        for (int k = layer.k0(); k <= layer.k1(); ++k) {
          ASSERT_EQ(std::bit_cast<std::uint32_t>(layer.At(k, m)),
                    std::bit_cast<std::uint32_t>(unit.At(k * step, m * step)))
              << size << " " << step << " " << k << " " << m;
        }
      }
    }
  }
}

TEST(ResponseLayerTest, SubsampleEqualsComputeAtTheDoubleStep) {
  const IntegralImage integral(SmoothNoise(120, 140, 2));
  for (const int size : {15, 27}) {
    ResponseLayer fine;
    fine.Compute(integral, size, 1);
    ResponseLayer coarse;
    coarse.Subsample(fine, integral.width(), integral.height(), 2);
    ResponseLayer direct;
    direct.Compute(integral, size, 2);
    ASSERT_EQ(coarse.k0(), direct.k0());
    ASSERT_EQ(coarse.k1(), direct.k1());
    ASSERT_EQ(coarse.m0(), direct.m0());
    ASSERT_EQ(coarse.m1(), direct.m1());
    for (int m = direct.m0(); m <= direct.m1(); ++m) {
      for (int k = direct.k0(); k <= direct.k1(); ++k) {
        ASSERT_EQ(coarse.At(k, m), direct.At(k, m));
      }
    }
  }
}

// RowCandidates sets exactly the bits of the samples passing the row tests, written out one by one:
// full and partial chunks, plateaus (equal neighbours) and values at the threshold.
TEST(ResponseLayerTest, RowCandidatesAreTheRowTests) {
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> level(0, 6);  // few levels: many equal neighbours
  std::vector<float> row(kCandidateChunk + 2);
  for (int trial = 0; trial < 200; ++trial) {
    for (float& v : row) {
      v = 0.25F * static_cast<float>(level(rng));
    }
    const int count = trial % 2 == 0 ? kCandidateChunk : trial % kCandidateChunk;
    const float threshold = 0.25F * static_cast<float>(trial % 5);
    const std::uint64_t bits = RowCandidates(row.data(), 1, count, threshold);
    for (int j = 0; j < kCandidateChunk; ++j) {
      const auto k = static_cast<std::size_t>(1 + j);
      const bool expected =
          j < count && row[k] > threshold && row[k] > row[k - 1] && row[k] >= row[k + 1];
      EXPECT_EQ(((bits >> j) & 1U) != 0, expected) << trial << " " << j;
    }
  }
}

}  // namespace
}  // namespace gridslam::features::internal
