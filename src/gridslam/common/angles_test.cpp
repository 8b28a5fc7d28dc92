#include "gridslam/common/angles.hpp"

#include <random>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

TEST(Angles, NormalizesIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(NormalizeAngle(0.5), 0.5);
  EXPECT_DOUBLE_EQ(NormalizeAngle(std::numbers::pi), -std::numbers::pi);
  EXPECT_DOUBLE_EQ(NormalizeAngle(-std::numbers::pi), -std::numbers::pi);
  EXPECT_NEAR(NormalizeAngle(3.0 * std::numbers::pi + 0.1), -std::numbers::pi + 0.1, 1e-12);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> dist(-100.0, 100.0);
  for (int i = 0; i < 10000; ++i) {
    const double a = dist(rng);
    const double n = NormalizeAngle(a);
    EXPECT_GE(n, -std::numbers::pi);
    EXPECT_LT(n, std::numbers::pi);
    EXPECT_NEAR(std::remainder(a - n, 2.0 * std::numbers::pi), 0.0, 1e-9);
  }
}

TEST(Angles, ConvertsDegrees) {
  EXPECT_DOUBLE_EQ(RadToDeg(DegToRad(37.0)), 37.0);
  EXPECT_DOUBLE_EQ(DegToRad(180.0), std::numbers::pi);
}

}  // namespace
}  // namespace gridslam
