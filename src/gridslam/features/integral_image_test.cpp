#include "gridslam/features/integral_image.hpp"

#include <random>
#include <utility>

#include <gtest/gtest.h>

namespace gridslam::features {
namespace {

cv::Mat RandomImage(int width, int height, std::mt19937& rng) {
  cv::Mat image(height, width, CV_8UC1);
  std::uniform_int_distribution<int> value(0, 255);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(value(rng));
    }
  }
  return image;
}

std::int64_t BruteForceSum(const cv::Mat& image, int x0, int y0, int x1, int y1) {
  std::int64_t sum = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      sum += image.at<std::uint8_t>(y, x);
    }
  }
  return sum;
}

TEST(IntegralImageTest, TableMatchesBruteForce) {
  std::mt19937 rng(42);
  const cv::Mat image = RandomImage(37, 23, rng);
  const IntegralImage integral(image);
  ASSERT_EQ(integral.width(), 37);
  ASSERT_EQ(integral.height(), 23);
  EXPECT_EQ(integral.stride(), 38);
  for (int y = 0; y <= 23; ++y) {
    for (int x = 0; x <= 37; ++x) {
      ASSERT_EQ(integral.At(x, y), BruteForceSum(image, 0, 0, x, y)) << x << ", " << y;
    }
  }
}

TEST(IntegralImageTest, BoxSumsMatchBruteForce) {
  std::mt19937 rng(7);
  const cv::Mat image = RandomImage(120, 90, rng);
  const IntegralImage integral(image);
  std::uniform_int_distribution<int> ux(0, 120);
  std::uniform_int_distribution<int> uy(0, 90);
  for (int trial = 0; trial < 2000; ++trial) {
    int x0 = ux(rng);
    int x1 = ux(rng);
    int y0 = uy(rng);
    int y1 = uy(rng);
    if (x0 > x1) {
      std::swap(x0, x1);
    }
    if (y0 > y1) {
      std::swap(y0, y1);
    }
    ASSERT_EQ(integral.BoxSum(x0, y0, x1, y1), BruteForceSum(image, x0, y0, x1, y1));
  }
}

TEST(IntegralImageTest, LargestSupportedValuesDoNotOverflow) {
  const cv::Mat image(400, 400, CV_8UC1, cv::Scalar(255));
  const IntegralImage integral(image);
  EXPECT_EQ(integral.BoxSum(0, 0, 400, 400), 255 * 400 * 400);
}

TEST(IntegralImageTest, ClippedBoxMeanUsesThePartInside) {
  std::mt19937 rng(3);
  const cv::Mat image = RandomImage(50, 40, rng);
  const IntegralImage integral(image);
  int area = 0;
  const float mean = integral.ClippedBoxMean(-5, 30, 10, 55, &area);
  EXPECT_EQ(area, 10 * 10);
  EXPECT_FLOAT_EQ(mean, static_cast<float>(BruteForceSum(image, 0, 30, 10, 40)) / 100.0F);
  EXPECT_FLOAT_EQ(integral.ClippedBoxMean(60, 0, 70, 10, &area), 0.0F);
  EXPECT_EQ(area, 0);
}

TEST(IntegralImageTest, ComputeReusesAndEmptyImage) {
  IntegralImage integral;
  EXPECT_TRUE(integral.empty());
  integral.Compute(cv::Mat(5, 4, CV_8UC1, cv::Scalar(2)));
  EXPECT_EQ(integral.BoxSum(0, 0, 4, 5), 40);
  integral.Compute(cv::Mat(0, 0, CV_8UC1));
  EXPECT_TRUE(integral.empty());
}

// Compute() on a table holding another image's sums (larger, smaller, another shape) writes every
// entry: the zero first row and column too.
TEST(IntegralImageTest, RecomputedTableMatchesBruteForce) {
  std::mt19937 rng(7);
  IntegralImage integral(cv::Mat(40, 50, CV_8UC1, cv::Scalar(255)));
  for (const auto& [width, height] : {std::pair{17, 29}, std::pair{50, 3}, std::pair{61, 44}}) {
    const cv::Mat image = RandomImage(width, height, rng);
    integral.Compute(image);
    for (int y = 0; y <= height; ++y) {
      for (int x = 0; x <= width; ++x) {
        ASSERT_EQ(integral.At(x, y), BruteForceSum(image, 0, 0, x, y)) << x << ", " << y;
      }
    }
  }
}

}  // namespace
}  // namespace gridslam::features
