#include "gridslam/features/surf_descriptor.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "gridslam/features/synthetic_keymap.hpp"

namespace gridslam::features {
namespace {

constexpr double kPi = std::numbers::pi;

double AngleDiff(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

// I = 128 + slope · ((x, y) − centre) · (cos φ, sin φ): the gradient points along φ.
cv::Mat Ramp(int size, double phi, double slope) {
  cv::Mat image(size, size, CV_8UC1);
  const double c = (size - 1) / 2.0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      image.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(
          128.0 + slope * ((x - c) * std::cos(phi) + (y - c) * std::sin(phi)));
    }
  }
  return image;
}

double Norm(const std::vector<float>& v) {
  double sum = 0.0;
  for (const float x : v) {
    sum += static_cast<double>(x) * x;
  }
  return std::sqrt(sum);
}

TEST(SurfDescriptorTest, OrientationOfARampIsItsGradientDirection) {
  for (const double deg : {0.0, 30.0, 90.0, 137.0, -120.0, 179.0}) {
    const double phi = deg * kPi / 180.0;
    const IntegralImage integral(Ramp(121, phi, 0.9));
    for (const float scale : {1.6F, 2.4F, 4.0F}) {
      const float theta = AssignOrientation(integral, 60.0F, 60.0F, scale);
      EXPECT_NEAR(AngleDiff(theta, phi), 0.0, 1.5 * kPi / 180.0) << deg << " " << scale;
    }
  }
}

TEST(SurfDescriptorTest, UnitNormAndLength) {
  cv::Mat noise(200, 200, CV_8UC1);
  cv::RNG rng(5);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  const IntegralImage integral(noise);
  std::vector<float> d64(kSurfDescriptorSize);
  std::vector<float> d128(kSurfExtendedDescriptorSize);
  // Inside, across the border, and at a scale whose window exceeds the image.
  for (const cv::Point3f p : {cv::Point3f(100, 100, 2), cv::Point3f(3, 190, 3),
                              cv::Point3f(100, 120, 20), cv::Point3f(0, 0, 1.2F)}) {
    ComputeSurfDescriptor(integral, p.x, p.y, p.z, 0.7F, false, d64.data());
    ComputeSurfDescriptor(integral, p.x, p.y, p.z, 0.7F, true, d128.data());
    EXPECT_NEAR(Norm(d64), 1.0, 1e-5);
    EXPECT_NEAR(Norm(d128), 1.0, 1e-5);
  }
}

TEST(SurfDescriptorTest, ExtendedSumsToTheStandardDescriptor) {
  const IntegralImage integral(MakeSyntheticKeyMap(200, 8));
  std::vector<float> d64(kSurfDescriptorSize);
  std::vector<float> d128(kSurfExtendedDescriptorSize);
  ComputeSurfDescriptor(integral, 97.3F, 88.6F, 3.1F, -2.0F, false, d64.data());
  ComputeSurfDescriptor(integral, 97.3F, 88.6F, 3.1F, -2.0F, true, d128.data());
  // Per sub-region: Σdx = Σdx(dy<0) + Σdx(dy≥0), Σ|dx| likewise, Σdy and Σ|dy| by the sign of dx.
  std::vector<float> merged(kSurfDescriptorSize);
  for (std::size_t r = 0; r < 16; ++r) {
    const float* e = d128.data() + 8 * r;
    merged[4 * r + 0] = e[0] + e[2];
    merged[4 * r + 1] = e[4] + e[6];
    merged[4 * r + 2] = e[1] + e[3];
    merged[4 * r + 3] = e[5] + e[7];
  }
  const double norm = Norm(merged);
  ASSERT_GT(norm, 0.0);
  for (int i = 0; i < kSurfDescriptorSize; ++i) {
    EXPECT_NEAR(merged[static_cast<std::size_t>(i)] / norm, d64[static_cast<std::size_t>(i)], 1e-5);
  }
}

TEST(SurfDescriptorTest, UprightRampDescriptorHasOnlyXResponses) {
  const IntegralImage integral(Ramp(121, 0.0, 0.9));
  std::vector<float> d(kSurfDescriptorSize);
  ComputeSurfDescriptor(integral, 60.0F, 60.0F, 2.0F, 0.0F, false, d.data());
  for (std::size_t r = 0; r < 16; ++r) {
    const float* v = d.data() + 4 * r;
    EXPECT_GT(v[0], 0.0F) << r;
    EXPECT_NEAR(v[0], v[2], 1e-6) << r;  // every dx positive
    EXPECT_NEAR(v[1], 0.0F, 1e-6) << r;
    EXPECT_NEAR(v[3], 0.0F, 1e-6) << r;
  }
  // Described at orientation 0 in the rotated frame of a ramp along 90°: the same descriptor.
  const IntegralImage rotated(Ramp(121, kPi / 2.0, 0.9));
  std::vector<float> e(kSurfDescriptorSize);
  ComputeSurfDescriptor(rotated, 60.0F, 60.0F, 2.0F, static_cast<float>(kPi / 2.0), false,
                        e.data());
  EXPECT_LT(cv::norm(cv::Mat(d), cv::Mat(e)), 0.02);
}

TEST(SurfDescriptorTest, FlatImageGivesZeros) {
  const IntegralImage integral(cv::Mat(80, 80, CV_8UC1, cv::Scalar(200)));
  EXPECT_EQ(AssignOrientation(integral, 40.0F, 40.0F, 2.0F), 0.0F);
  std::vector<float> d(kSurfDescriptorSize, 1.0F);
  ComputeSurfDescriptor(integral, 40.0F, 40.0F, 2.0F, 0.3F, false, d.data());
  EXPECT_EQ(Norm(d), 0.0);
}

TEST(SurfDescriptorTest, QuarterTurnRotatesOrientationAndKeepsDescriptor) {
  const cv::Mat image = MakeSyntheticKeyMap(240, 3);
  cv::Mat turned;
  cv::rotate(image, turned, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (H − 1 − y, x)
  const IntegralImage a(image);
  const IntegralImage b(turned);
  int checked = 0;
  // The sampling is exactly symmetric under the turn except where a sample falls on a pixel
  // centre (a tie between two wavelet placements): points and scales avoid that.
  for (const cv::Point2f p : {cv::Point2f(80.3719F, 95.6413F), cv::Point2f(150.8291F, 120.1937F),
                              cv::Point2f(121.4357F, 60.7123F)}) {
    for (const float scale : {2.1379F, 3.3721F, 5.2163F}) {
      const cv::Point2f q(239.0F - p.y, p.x);
      const float ta = AssignOrientation(a, p.x, p.y, scale);
      const float tb = AssignOrientation(b, q.x, q.y, scale);
      EXPECT_NEAR(AngleDiff(tb, ta + kPi / 2.0), 0.0, 1e-5);
      std::vector<float> da(kSurfDescriptorSize);
      std::vector<float> db(kSurfDescriptorSize);
      ComputeSurfDescriptor(a, p.x, p.y, scale, ta, false, da.data());
      ComputeSurfDescriptor(b, q.x, q.y, scale, tb, false, db.data());
      EXPECT_LT(cv::norm(cv::Mat(da), cv::Mat(db)), 1e-4) << p << " " << scale;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);
}

}  // namespace
}  // namespace gridslam::features
