#include "gridslam/features/surf_descriptor.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "gridslam/features/internal/angle_order.hpp"
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

// The bits of the orientation and of both descriptors (FNV-1a of their floats' bits) at points
// inside and across the border, as the implementation before the speed-ups of issue 19 gave them:
// those must not change the results at all.
TEST(SurfDescriptorTest, BitForBitAsBeforeTheSpeedUps) {
  struct Expected {
    float x, y, scale;
    std::uint32_t angle_bits;
    std::uint64_t hash64, hash128;
  };
  const Expected expected[] = {
      {80.3719F, 95.6413F, 2.1379F, 0x3ef5d335, 0xaa8fa68fcc8f5eb3ULL, 0x4c3dac9c95855fb9ULL},
      {150.8291F, 120.1937F, 5.2163F, 0x403f95b8, 0x63a2d292c2e37c28ULL, 0xaf2d6c61085c4afcULL},
      {121.4357F, 60.7123F, 3.3721F, 0x3f3df1a2, 0x30d82ed844b1d9d8ULL, 0xa3e99086def83979ULL},
      {2.5F, 100.25F, 2.0F, 0xc04165c0, 0x3e9b0b3b3f378f77ULL, 0x19929adfc19654eaULL},
      {237.75F, 3.125F, 4.5F, 0xbfc7a7a6, 0x2dfe9183a6eb6f6cULL, 0x97869c65d45dc0feULL},
      {60.0F, 60.0F, 12.0F, 0x4045dd27, 0xa2382f34e68efc63ULL, 0xb79b6113ca03541bULL},
  };
  const IntegralImage integral(MakeSyntheticKeyMap(240, 3));
  const auto hash = [](const std::vector<float>& d) {
    std::uint64_t h = 1469598103934665603ULL;
    for (const float v : d) {
      h = (h ^ std::bit_cast<std::uint32_t>(v)) * 1099511628211ULL;
    }
    return h;
  };
  for (const Expected& e : expected) {
    const float angle = AssignOrientation(integral, e.x, e.y, e.scale);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(angle), e.angle_bits) << e.x << " " << e.y;
    std::vector<float> d64(kSurfDescriptorSize);
    std::vector<float> d128(kSurfExtendedDescriptorSize);
    ComputeSurfDescriptor(integral, e.x, e.y, e.scale, angle, false, d64.data());
    ComputeSurfDescriptor(integral, e.x, e.y, e.scale, angle, true, d128.data());
    EXPECT_EQ(hash(d64), e.hash64) << e.x << " " << e.y;
    EXPECT_EQ(hash(d128), e.hash128) << e.x << " " << e.y;
  }
}

// Distinct angles: the order std::sort gives, clustered or spread, inside [−π, π] or not.
TEST(AngleOrderTest, DistinctAnglesInTheSortedOrder) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> spread(-3.1415927F, 3.1415927F);
  std::normal_distribution<float> cluster(0.7F, 0.001F);
  std::uniform_real_distribution<float> wide(-50.0F, 50.0F);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = trial % internal::kMaxAngleKeys;
    std::vector<float> angle(static_cast<std::size_t>(n));
    for (float& a : angle) {
      a = trial % 3 == 0 ? spread(rng) : (trial % 3 == 1 ? cluster(rng) : wide(rng));
    }
    std::vector<int> expected(angle.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      expected[k] = static_cast<int>(k);
    }
    std::sort(expected.begin(), expected.end(), [&](int a, int b) {
      return angle[static_cast<std::size_t>(a)] < angle[static_cast<std::size_t>(b)];
    });
    if (std::adjacent_find(expected.begin(), expected.end(), [&](int a, int b) {
          return angle[static_cast<std::size_t>(a)] == angle[static_cast<std::size_t>(b)];
        }) != expected.end()) {
      continue;  // a tie drawn by chance
    }
    std::vector<std::uint8_t> order(angle.size());
    ASSERT_TRUE(internal::OrderByAngle(angle.data(), n, order.data())) << trial;
    EXPECT_TRUE(std::equal(order.begin(), order.end(), expected.begin())) << trial;
  }
}

// Equal angles: reported, and the order is still ascending with the ties in index order.
TEST(AngleOrderTest, TiesAreReported) {
  const std::vector<float> angle = {0.5F, -1.0F, 0.5F, 3.0F, -1.0F, 0.25F};
  std::vector<std::uint8_t> order(angle.size());
  EXPECT_FALSE(internal::OrderByAngle(angle.data(), static_cast<int>(angle.size()), order.data()));
  EXPECT_EQ(order, (std::vector<std::uint8_t>{1, 4, 5, 0, 2, 3}));
  const float one = 1.0F;
  std::uint8_t single = 7;
  EXPECT_TRUE(internal::OrderByAngle(&one, 1, &single));
  EXPECT_EQ(single, 0);
  EXPECT_TRUE(internal::OrderByAngle(nullptr, 0, nullptr));
}

}  // namespace
}  // namespace gridslam::features
