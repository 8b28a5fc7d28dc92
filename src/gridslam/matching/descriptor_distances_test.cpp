#include "gridslam/matching/descriptor_distances.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace gridslam::matching {
namespace {

cv::Mat RandomRows(int rows, int cols, int type, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat m(rows, cols, type);
  if (type == CV_32F) {
    rng.fill(m, cv::RNG::UNIFORM, -1.0, 1.0);
  } else {
    rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  }
  return m;
}

TEST(DescriptorDistances, SquaredEuclideanAgreesWithTheNorm) {
  const cv::Mat a = RandomRows(37, 64, CV_32F, 1);
  const cv::Mat b = RandomRows(301, 64, CV_32F, 2);
  const RowMajorMatrixXf d = SquaredEuclideanDistances(a, b);
  ASSERT_EQ(d.rows(), a.rows);
  ASSERT_EQ(d.cols(), b.rows);
  for (int i = 0; i < a.rows; ++i) {
    for (int j = 0; j < b.rows; ++j) {
      const double expected = cv::norm(a.row(i), b.row(j), cv::NORM_L2SQR);
      EXPECT_NEAR(d(i, j), expected, 1e-4 * (1.0 + expected)) << i << ", " << j;
    }
  }
}

TEST(DescriptorDistances, SquaredEuclideanOfIdenticalRowsIsZeroNotNegative) {
  const cv::Mat a = RandomRows(5, 64, CV_32F, 3);
  const RowMajorMatrixXf d = SquaredEuclideanDistances(a, a);
  for (int i = 0; i < a.rows; ++i) {
    EXPECT_GE(d(i, i), 0.0F);
    EXPECT_LT(d(i, i), 1e-4F);
  }
}

TEST(DescriptorDistances, SquaredEuclideanOfNonContinuousRows) {
  const cv::Mat big = RandomRows(20, 80, CV_32F, 4);
  const cv::Mat a = big(cv::Rect(8, 0, 64, 10));  // not continuous
  const cv::Mat b = big(cv::Rect(8, 10, 64, 10));
  const RowMajorMatrixXf d = SquaredEuclideanDistances(a, b);
  EXPECT_NEAR(d(3, 7), cv::norm(a.row(3), b.row(7), cv::NORM_L2SQR), 1e-4);
}

TEST(DescriptorDistances, HammingCountsDifferingBits) {
  // 61 bytes: seven 64-bit words and a 5-byte tail.
  const cv::Mat a = RandomRows(9, 61, CV_8U, 5);
  const cv::Mat b = RandomRows(13, 61, CV_8U, 6);
  const RowMajorMatrixXf d = HammingDistances(a, b);
  for (int i = 0; i < a.rows; ++i) {
    for (int j = 0; j < b.rows; ++j) {
      EXPECT_EQ(d(i, j), static_cast<float>(cv::norm(a.row(i), b.row(j), cv::NORM_HAMMING)));
    }
  }
}

TEST(DescriptorDistancesDeathTest, MixedTypesAreRefused) {
  const cv::Mat a = RandomRows(2, 8, CV_32F, 7);
  const cv::Mat b = RandomRows(2, 8, CV_8U, 8);
  EXPECT_DEATH((void)SquaredEuclideanDistances(a, b), "float descriptors");
  EXPECT_DEATH((void)HammingDistances(a, b), "binary descriptors");
}

}  // namespace
}  // namespace gridslam::matching
