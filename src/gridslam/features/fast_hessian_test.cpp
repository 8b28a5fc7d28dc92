#include "gridslam/features/fast_hessian.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "gridslam/features/synthetic_keymap.hpp"

namespace gridslam::features {
namespace {

// Kernels written out pixel by pixel from the lobe description of docs/method.md §2.2
// (independent of the integral-image code): Dyy = three stacked (2l−1) × l lobes +1, −2, +1; Dxx
// its transpose; Dxy four l × l lobes around a one-pixel cross, + top-left and bottom-right.
struct Kernels {
  cv::Mat dxx, dyy, dxy;  // CV_32F, L × L, centre at (b, b)
};

Kernels MakeKernels(int filter_size) {
  const int size = filter_size;
  const int l = size / 3;
  const int b = (size - 1) / 2;
  Kernels k{cv::Mat::zeros(size, size, CV_32F), cv::Mat::zeros(size, size, CV_32F),
            cv::Mat::zeros(size, size, CV_32F)};
  for (int v = -b; v <= b; ++v) {
    for (int u = -b; u <= b; ++u) {
      if (std::abs(u) <= l - 1) {  // width 2l − 1
        k.dyy.at<float>(v + b, u + b) = std::abs(v) <= (l - 1) / 2 ? -2.0F : 1.0F;
        k.dxx.at<float>(u + b, v + b) = k.dyy.at<float>(v + b, u + b);
      }
      if (u != 0 && v != 0 && std::abs(u) <= l && std::abs(v) <= l) {
        k.dxy.at<float>(v + b, u + b) = (u > 0) == (v > 0) ? 1.0F : -1.0F;
      }
    }
  }
  return k;
}

float Apply(const cv::Mat& image, const cv::Mat& kernel, int x, int y) {
  const int b = kernel.rows / 2;
  double sum = 0.0;
  for (int v = 0; v < kernel.rows; ++v) {
    for (int u = 0; u < kernel.cols; ++u) {
      sum += kernel.at<float>(v, u) * image.at<std::uint8_t>(y - b + v, x - b + u);
    }
  }
  return static_cast<float>(sum / (255.0 * kernel.rows * kernel.rows));
}

TEST(FastHessianTest, FilterSizesAreThePapers) {
  const int expected[4][4] = {
      {9, 15, 21, 27}, {15, 27, 39, 51}, {27, 51, 75, 99}, {51, 99, 147, 195}};
  for (int o = 0; o < 4; ++o) {
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(FilterSize(o, i), expected[o][i]) << o << ", " << i;
    }
  }
  EXPECT_FLOAT_EQ(ScaleOfSize(9.0F), 1.2F);
}

TEST(FastHessianTest, NineByNineKernelMatchesOpenCvTable) {
  // OpenCV's 9-grid lobes [x1, y1, x2, y2) with weights (docs/method.md §2.2).
  const int dyy[3][5] = {{2, 0, 7, 3, 1}, {2, 3, 7, 6, -2}, {2, 6, 7, 9, 1}};
  const int dxy[4][5] = {{1, 1, 4, 4, 1}, {5, 1, 8, 4, -1}, {1, 5, 4, 8, -1}, {5, 5, 8, 8, 1}};
  cv::Mat expected_yy = cv::Mat::zeros(9, 9, CV_32F);
  cv::Mat expected_xy = cv::Mat::zeros(9, 9, CV_32F);
  for (const auto& lobe : dyy) {
    expected_yy(cv::Rect(lobe[0], lobe[1], lobe[2] - lobe[0], lobe[3] - lobe[1])) = lobe[4];
  }
  for (const auto& lobe : dxy) {
    expected_xy(cv::Rect(lobe[0], lobe[1], lobe[2] - lobe[0], lobe[3] - lobe[1])) = lobe[4];
  }
  const Kernels k = MakeKernels(9);
  EXPECT_EQ(cv::norm(k.dyy, expected_yy, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(k.dxx, cv::Mat(expected_yy.t()), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(k.dxy, expected_xy, cv::NORM_INF), 0.0);
}

TEST(FastHessianTest, BoxHessianMatchesExplicitKernels) {
  std::mt19937 rng(11);
  cv::Mat image(260, 240, CV_8UC1);
  std::uniform_int_distribution<int> value(0, 255);
  for (std::uint8_t& pixel : cv::Mat_<std::uint8_t>(image)) {
    pixel = static_cast<std::uint8_t>(value(rng));
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 2.0);
  const IntegralImage integral(image);
  for (const int size : {9, 15, 21, 27, 39, 51, 75, 99, 147, 195}) {
    const Kernels k = MakeKernels(size);
    const int b = (size - 1) / 2;
    std::uniform_int_distribution<int> ux(b, 240 - 1 - b);
    std::uniform_int_distribution<int> uy(b, 260 - 1 - b);
    for (int trial = 0; trial < 5; ++trial) {
      const int x = ux(rng);
      const int y = uy(rng);
      const BoxHessian h = ComputeBoxHessian(integral, x, y, size);
      const float tol = 1e-5F;
      EXPECT_NEAR(h.dxx, Apply(image, k.dxx, x, y), tol) << size;
      EXPECT_NEAR(h.dyy, Apply(image, k.dyy, x, y), tol) << size;
      EXPECT_NEAR(h.dxy, Apply(image, k.dxy, x, y), tol) << size;
      EXPECT_FLOAT_EQ(h.Det(), h.dxx * h.dyy - 0.81F * h.dxy * h.dxy);
    }
  }
}

cv::Mat GaussianBlob(int size, double cx, double cy, double sigma, double amplitude) {
  cv::Mat image(size, size, CV_8UC1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      image.at<std::uint8_t>(y, x) =
          cv::saturate_cast<std::uint8_t>(128.0 + amplitude * std::exp(-r2 / (2 * sigma * sigma)));
    }
  }
  return image;
}

// A Gaussian blob of std σ: the detector finds one keypoint at its centre, at the filter size
// where the area-normalised box response peaks (brute force over every filter size at the
// centre pixel), with the sign of the Laplacian of a bright (−1) or dark (+1) blob.
TEST(FastHessianTest, BlobPeaksAtTheRightScaleAndPosition) {
  for (const double sigma : {3.0, 4.0, 6.0, 9.0, 13.0}) {
    for (const double amplitude : {110.0, -110.0}) {
      const int size = 300;
      const double cx = 150.0;
      const double cy = 140.0;
      const cv::Mat image = GaussianBlob(size, cx, cy, sigma, amplitude);
      const IntegralImage integral(image);
      int best_size = 0;
      float best_det = 0.0F;
      for (int l = 3; 3 * l <= 195; l += 2) {
        const float det = ComputeBoxHessian(integral, 150, 140, 3 * l).Det();
        if (det > best_det) {
          best_det = det;
          best_size = 3 * l;
        }
      }
      SurfOptions options;
      const std::vector<cv::KeyPoint> keypoints = DetectFastHessian(integral, options);
      ASSERT_FALSE(keypoints.empty()) << sigma;
      const cv::KeyPoint& kp = keypoints.front();
      EXPECT_NEAR(kp.pt.x, cx, 0.1) << sigma;
      EXPECT_NEAR(kp.pt.y, cy, 0.1) << sigma;
      // Within 20%: the third octave interpolates between filter sizes 24 apart.
      EXPECT_NEAR(kp.size / static_cast<float>(best_size), 1.0, 0.2) << sigma;
      // Box filters respond to a Gaussian blob most strongly at s ≈ 0.7σ (not σ, as ideal
      // Gaussian derivatives would): check that the scale follows σ.
      EXPECT_NEAR(ScaleOfSize(kp.size) / sigma, 0.72, 0.07) << sigma;
      EXPECT_EQ(kp.class_id, amplitude > 0 ? -1 : 1) << sigma;
      EXPECT_GT(kp.response, options.hessian_threshold);
      EXPECT_NEAR(kp.response, best_det, 0.2 * best_det);
      EXPECT_EQ(kp.angle, -1.0F);
      for (std::size_t i = 1; i < keypoints.size(); ++i) {
        EXPECT_LE(keypoints[i].response, keypoints[i - 1].response);
      }
    }
  }
}

TEST(FastHessianTest, SubPixelPositionFollowsTheBlob) {
  for (const double dx : {0.0, 0.25, 0.5, 0.75}) {
    const double cx = 120.0 + dx;
    const double cy = 131.0 - dx / 2.0;
    const IntegralImage integral(GaussianBlob(240, cx, cy, 2.5, 100.0));
    const std::vector<cv::KeyPoint> keypoints = DetectFastHessian(integral, SurfOptions{});
    ASSERT_FALSE(keypoints.empty());
    EXPECT_NEAR(keypoints.front().pt.x, cx, 0.1) << dx;
    EXPECT_NEAR(keypoints.front().pt.y, cy, 0.1) << dx;
  }
}

TEST(FastHessianTest, NothingOnFlatTinyOrBelowThreshold) {
  SurfOptions options;
  EXPECT_TRUE(DetectFastHessian(IntegralImage(cv::Mat(100, 100, CV_8UC1, cv::Scalar(77))), options)
                  .empty());
  EXPECT_TRUE(
      DetectFastHessian(IntegralImage(cv::Mat(8, 8, CV_8UC1, cv::Scalar(7))), options).empty());
  EXPECT_TRUE(DetectFastHessian(IntegralImage(), options).empty());
  const IntegralImage blob(GaussianBlob(120, 60, 60, 4.0, 100.0));
  options.hessian_threshold = 1.0;
  EXPECT_TRUE(DetectFastHessian(blob, options).empty());
}

TEST(FastHessianTest, RefittingFindsAtLeastAsManyKeypoints) {
  // Two blobs close together make offsets above half a sample; refitting keeps such keypoints.
  cv::Mat image = GaussianBlob(200, 90.0, 100.0, 5.0, 60.0);
  image += GaussianBlob(200, 104.0, 100.0, 3.0, 60.0) - cv::Scalar(128);
  const IntegralImage integral(image);
  SurfOptions options;
  const std::size_t single = DetectFastHessian(integral, options).size();
  options.interpolation_steps = 3;
  EXPECT_GE(DetectFastHessian(integral, options).size(), single);
}

// The keypoints of two synthetic key maps (positions, sizes, responses, octaves, Laplacian signs,
// FNV-1a of their bits) as the detector before the speed-ups of issue 19 gave them: those must not
// change the results at all.
TEST(FastHessianTest, BitForBitAsBeforeTheSpeedUps) {
  const std::pair<std::uint32_t, std::pair<std::size_t, std::uint64_t>> expected[] = {
      {3, {55, 0x3689bcf886e8c074ULL}}, {4, {81, 0x3cd6157cb5990092ULL}}};
  for (const auto& [seed, count_hash] : expected) {
    const IntegralImage integral(MakeSyntheticKeyMap(240, seed));
    const std::vector<cv::KeyPoint> keypoints = DetectFastHessian(integral, SurfOptions{});
    std::uint64_t hash = 1469598103934665603ULL;
    const auto mix = [&](std::uint32_t bits) { hash = (hash ^ bits) * 1099511628211ULL; };
    for (const cv::KeyPoint& kp : keypoints) {
      mix(std::bit_cast<std::uint32_t>(kp.pt.x));
      mix(std::bit_cast<std::uint32_t>(kp.pt.y));
      mix(std::bit_cast<std::uint32_t>(kp.size));
      mix(std::bit_cast<std::uint32_t>(kp.response));
      mix(static_cast<std::uint32_t>(kp.octave));
      mix(static_cast<std::uint32_t>(kp.class_id));
    }
    EXPECT_EQ(keypoints.size(), count_hash.first) << seed;
    EXPECT_EQ(hash, count_hash.second) << seed;
  }
}

}  // namespace
}  // namespace gridslam::features
