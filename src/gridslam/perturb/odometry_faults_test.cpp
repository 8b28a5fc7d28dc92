#include "gridslam/perturb/odometry_faults.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gridslam::perturb {
namespace {

/// `n` frames at 10 Hz; pose k = motion(k).
template <class Motion>
std::vector<Frame> MakeFrames(int n, Motion motion) {
  std::vector<Frame> frames(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    Frame& f = frames[static_cast<std::size_t>(k)];
    f.time = FromSeconds(1000.0 + 0.1 * k);
    f.corrected_time = f.time;
    f.T_odom_base = motion(k);
  }
  return frames;
}

std::vector<Frame> Straight(int n) {  // 1 m/s along x
  return MakeFrames(n, [](int k) { return Pose2(0.1 * k, 0.0, 0.0); });
}

TEST(OdometryFaults, NoFaultKeepsTheOdometry) {
  const auto frames = MakeFrames(50, [](int k) { return Pose2(0.1 * k, 0.02 * k, 0.03 * k); });
  const auto out = PerturbOdometry(frames, PerturbOptions{}, nullptr);
  ASSERT_EQ(out.size(), frames.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    EXPECT_TRUE(IsApprox(out[k], frames[k].T_odom_base));
  }
}

TEST(OdometryFaults, YawGlitchesJumpInOneStepAndTheOdometryCarriesOn) {
  const auto frames = Straight(2000);  // 200 s
  PerturbOptions options;
  options.glitch_period = 20.0;
  options.glitch_yaw_fraction = 1.0;
  std::vector<GlitchEvent> glitches;
  const auto out = PerturbOdometry(frames, options, &glitches);
  // A Poisson process of mean period 20 s over 200 s: about 10 (P(N < 3 or N > 25) < 1e-3).
  ASSERT_GE(glitches.size(), 3U);
  ASSERT_LE(glitches.size(), 25U);
  double heading = 0.0;
  std::size_t g = 0;
  for (std::size_t k = 1; k < out.size(); ++k) {
    const Pose2 step = Between(out[k - 1], out[k]);
    if (g < glitches.size() && glitches[g].frame == k) {
      EXPECT_EQ(glitches[g].kind, GlitchKind::kYaw);
      EXPECT_EQ(glitches[g].time, frames[k].time);
      const double deg = RadToDeg(std::abs(step.theta()));
      EXPECT_GE(deg, 25.0);
      EXPECT_LE(deg, 85.0);
      heading += step.theta();
      ++g;
    } else {
      EXPECT_NEAR(step.theta(), 0.0, 1e-12) << k;
    }
    // Every step still moves 0.1 m forward in the (jumped) robot frame.
    EXPECT_NEAR(step.x(), 0.1, 1e-9);
    EXPECT_NEAR(out[k].theta(), NormalizeAngle(heading), 1e-9);
  }
  EXPECT_EQ(g, glitches.size());
}

TEST(OdometryFaults, TranslationGlitchesHaveTheirSize) {
  const auto frames = Straight(2000);
  PerturbOptions options;
  options.glitch_period = 20.0;
  options.glitch_yaw_fraction = 0.0;
  std::vector<GlitchEvent> glitches;
  const auto out = PerturbOdometry(frames, options, &glitches);
  ASSERT_GE(glitches.size(), 3U);
  for (const GlitchEvent& e : glitches) {
    EXPECT_EQ(e.kind, GlitchKind::kTranslation);
    const Pose2 step = Between(out[e.frame - 1], out[e.frame]);
    const double jump = (step.translation() - Eigen::Vector2d(0.1, 0.0)).norm();
    EXPECT_GE(jump, 0.3 - 1e-9);
    EXPECT_LE(jump, 1.0 + 1e-9);
    EXPECT_NEAR(step.theta(), 0.0, 1e-12);
  }
}

TEST(OdometryFaults, SeedDecidesTheGlitches) {
  const auto frames = Straight(2000);
  PerturbOptions options;
  options.glitch_period = 20.0;
  std::vector<GlitchEvent> a, b, c;
  PerturbOdometry(frames, options, &a);
  PerturbOdometry(frames, options, &b);
  options.seed = 2;
  PerturbOdometry(frames, options, &c);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].frame, b[i].frame);
    EXPECT_TRUE(IsApprox(a[i].jump, b[i].jump));
  }
  bool differs = a.size() != c.size();
  for (std::size_t i = 0; !differs && i < a.size(); ++i) {
    differs = a[i].frame != c[i].frame;
  }
  EXPECT_TRUE(differs);
}

TEST(OdometryFaults, CalibrationScalesAndDrift) {
  PerturbOptions options;
  options.translation_scale = 0.96;
  auto out = PerturbOdometry(Straight(101), options, nullptr);
  EXPECT_NEAR(out.back().x(), 0.96 * 10.0, 1e-9);
  EXPECT_NEAR(out.back().y(), 0.0, 1e-9);

  options = {};
  options.rotation_scale = 1.03;
  const auto turning = MakeFrames(101, [](int k) { return Pose2(0.0, 0.0, 0.01 * k); });
  out = PerturbOdometry(turning, options, nullptr);
  EXPECT_NEAR(out.back().theta(), 1.03 * 1.0, 1e-9);

  options = {};
  options.yaw_drift = 0.01;  // rad/s, robot standing still for 10 s
  out =
      PerturbOdometry(MakeFrames(101, [](int) { return Pose2(2.0, 3.0, 0.5); }), options, nullptr);
  EXPECT_NEAR(out.back().theta(), 0.5 + 0.1, 1e-9);
  EXPECT_NEAR(out.back().x(), 2.0, 1e-9);
}

TEST(OdometryFaults, TimeJitterTakesTheOdometryAtTheWrongTime) {
  const auto frames = Straight(3000);
  PerturbOptions options;
  options.time_jitter = 0.05;  // at 1 m/s: 5 cm standard deviation along x
  const auto out = PerturbOdometry(frames, options, nullptr);
  double ss = 0.0;
  int n = 0;
  for (std::size_t k = 100; k + 100 < out.size(); ++k) {
    const double dx = out[k].x() - frames[k].T_odom_base.x();
    ss += dx * dx;
    ++n;
    EXPECT_NEAR(out[k].y(), 0.0, 1e-9);
  }
  const double sigma = std::sqrt(ss / n);
  EXPECT_GT(sigma, 0.04);
  EXPECT_LT(sigma, 0.06);
}

}  // namespace
}  // namespace gridslam::perturb
