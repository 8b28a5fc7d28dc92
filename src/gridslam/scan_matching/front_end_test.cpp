#include "gridslam/scan_matching/front_end.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "gridslam/scan_matching/internal/synthetic_world.hpp"

namespace gridslam::scan_matching {
namespace {

using internal::SimulateScan;
using internal::TestWorld;

// True robot poses from `start`: turn in place towards each waypoint, then drive to it (4 cm,
// <= 0.08 rad per frame).
std::vector<Pose2> Drive(const Pose2& start, const std::vector<Eigen::Vector2d>& waypoints) {
  std::vector<Pose2> poses = {start};
  for (const Eigen::Vector2d& target : waypoints) {
    while (true) {
      const Pose2& p = poses.back();
      const Eigen::Vector2d d = target - p.translation();
      if (d.norm() < 0.04) {
        break;
      }
      const double turn = NormalizeAngle(std::atan2(d.y(), d.x()) - p.theta());
      if (std::abs(turn) > 0.05) {
        poses.emplace_back(p.translation(), p.theta() + std::clamp(turn, -0.08, 0.08));
      } else {
        poses.emplace_back(p.translation() + 0.04 * d.normalized(), p.theta() + turn);
      }
    }
  }
  return poses;
}

std::vector<Pose2> DriveThroughTheWorld() {
  return Drive(Pose2(2.0, 1.0, 0.0), {{8.5, 1.5},
                                      {8.8, 3.7},
                                      {14.5, 3.8},
                                      {9.0, 3.7},
                                      {5.0, 5.5},
                                      {1.5, 3.0},
                                      {2.0, 1.2},
                                      {6.0, 1.0}});
}

// Frames with a mounted laser (0.1 m ahead) and odometry that overestimates turns by 5 % and
// distances by 2 %, plus noise.
std::vector<Frame> MakeFrames(const std::vector<Pose2>& truth,
                              const std::vector<internal::Segment>& world = TestWorld()) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  const Pose2 T_base_laser(0.1, 0.0, 0.0);
  std::vector<Frame> frames;
  Pose2 odometry = truth.front();
  for (std::size_t k = 0; k < truth.size(); ++k) {
    if (k > 0) {
      const Pose2 step = Between(truth[k - 1], truth[k]);
      odometry = odometry * Pose2(1.02 * step.x() + 0.002 * noise(rng), 0.002 * noise(rng),
                                  1.05 * step.theta() + 0.002 * noise(rng));
    }
    Frame frame;
    frame.time = FromSeconds(1000.0 + 0.1 * static_cast<double>(k));
    frame.corrected_time = frame.time;
    frame.T_odom_base = odometry;
    frame.T_base_laser = T_base_laser;
    frame.scan =
        SimulateScan(world, truth[k] * T_base_laser, 181, 30.0, 0.01, static_cast<unsigned>(k));
    frames.push_back(std::move(frame));
  }
  return frames;
}

// Mean translational and rotational error of the relative poses over `span` frames.
std::pair<double, double> RelativeError(const std::vector<Pose2>& truth,
                                        const std::vector<Pose2>& estimate, std::size_t span) {
  double translation = 0.0;
  double rotation = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k + span < truth.size(); k += span) {
    const Pose2 error =
        Between(Between(truth[k], truth[k + span]), Between(estimate[k], estimate[k + span]));
    translation += error.translation().norm();
    rotation += std::abs(error.theta());
    ++n;
  }
  return {translation / static_cast<double>(n), rotation / static_cast<double>(n)};
}

TEST(FrontEnd, BeatsOdometryAndHandsOutEveryScanInOneKeyMap) {
  const std::vector<Pose2> truth = DriveThroughTheWorld();
  ASSERT_GT(truth.size(), 500U);
  const std::vector<Frame> frames = MakeFrames(truth);
  FrontEndOptions options;
  options.keymap.size = 8.0;
  FrontEnd front_end(options);
  std::vector<Pose2> estimate;
  std::vector<Pose2> odometry;
  std::vector<keymap::KeyMap> keys;
  for (const Frame& frame : frames) {
    FrontEndStep step = front_end.AddFrame(frame);
    EXPECT_EQ(step.time, frame.time);
    estimate.push_back(step.T_odom_base);
    odometry.push_back(frame.T_odom_base);
    if (step.key_map) {
      keys.push_back(std::move(*step.key_map));
    }
  }
  if (auto last = front_end.Finish()) {
    keys.push_back(std::move(*last));
  }
  const FrontEndStats& stats = front_end.Stats();
  EXPECT_EQ(stats.frames, static_cast<long>(frames.size()));
  EXPECT_EQ(stats.matched, stats.frames - 1);
  EXPECT_EQ(stats.fallback_few_points + stats.fallback_empty_map + stats.fallback_rejected, 0);

  // Over 2 s (20 frames) the front end is far better than the odometry, in both parts.
  const auto [odometry_xy, odometry_theta] = RelativeError(truth, odometry, 20);
  const auto [estimate_xy, estimate_theta] = RelativeError(truth, estimate, 20);
  EXPECT_LT(estimate_xy, 0.02);
  EXPECT_LT(estimate_theta, DegToRad(0.4));
  EXPECT_LT(estimate_xy, 0.5 * odometry_xy);
  EXPECT_LT(estimate_theta, 0.2 * odometry_theta);
  // Over the whole drive the drift stays small.
  const Pose2 end_error =
      Between(Between(truth.front(), truth.back()), Between(estimate.front(), estimate.back()));
  EXPECT_LT(end_error.translation().norm(), 0.15);

  // Key maps: every scan exactly once, in order, with T_odom_key * T_key_scan = its pose.
  ASSERT_GE(keys.size(), 10U);
  EXPECT_EQ(stats.key_maps, static_cast<long>(keys.size()));
  std::size_t index = 0;
  for (const keymap::KeyMap& key : keys) {
    EXPECT_EQ(key.log_odds.Width(), options.keymap.NumCells(0.05));
    for (const keymap::KeyMapScan& scan : key.scans) {
      ASSERT_LT(index, estimate.size());
      EXPECT_EQ(scan.time, frames[index].time);
      EXPECT_TRUE(IsApprox(key.T_odom_key * scan.T_key_scan, estimate[index], 1e-9, 1e-9));
      ++index;
    }
  }
  EXPECT_EQ(index, frames.size());
}

// A hall of 44 m x 36 m with two pillars: from the drive in its middle every wall and pillar is
// 13 m or more away, beyond the key-map window's half side (12.5 m).
std::vector<internal::Segment> FarWalledHall() {
  std::vector<internal::Segment> w;
  auto box = [&w](double x0, double y0, double x1, double y1) {
    w.push_back({{x0, y0}, {x1, y0}});
    w.push_back({{x1, y0}, {x1, y1}});
    w.push_back({{x1, y1}, {x0, y1}});
    w.push_back({{x0, y1}, {x0, y0}});
  };
  box(-18.013, -15.979, 26.013, 20.021);
  box(-10.987, 14.021, -9.987, 15.021);
  box(16.013, -11.979, 17.013, -10.979);
  return w;
}

TEST(FrontEnd, AHallWhoseWallsAreAllFarAwayIsStillMatched) {
  const std::vector<Pose2> truth =
      Drive(Pose2(0.0, 0.0, 0.0), {{6.0, 0.0}, {6.0, 4.0}, {0.0, 4.0}, {0.0, 0.5}});
  ASSERT_GT(truth.size(), 400U);
  const std::vector<Frame> frames = MakeFrames(truth, FarWalledHall());
  auto run = [&](const FrontEndOptions& options) {
    FrontEnd front_end(options);
    std::vector<Pose2> estimate;
    for (const Frame& frame : frames) {
      estimate.push_back(front_end.AddFrame(frame).T_odom_base);
    }
    return std::make_pair(front_end.Stats(), estimate);
  };
  // The default matching window holds every return inserted: each scan is matched, and the drive
  // comes out better than its odometry.
  const auto [stats, estimate] = run(FrontEndOptions{});
  EXPECT_EQ(stats.matched, stats.frames - 1);
  std::vector<Pose2> odometry;
  for (const Frame& frame : frames) {
    odometry.push_back(frame.T_odom_base);
  }
  const auto [odometry_xy, odometry_theta] = RelativeError(truth, odometry, 20);
  const auto [estimate_xy, estimate_theta] = RelativeError(truth, estimate, 20);
  EXPECT_LT(estimate_xy, 0.5 * odometry_xy);
  EXPECT_LT(estimate_theta, 0.2 * odometry_theta);
  // Matched against the key-map window alone, the scans find nothing to match.
  FrontEndOptions small;
  small.local_map.matching_size = small.local_map.size;
  const auto [small_stats, small_estimate] = run(small);
  EXPECT_EQ(small_stats.matched, 0);
}

// The drive's end pose relative to its start, estimated against the truth.
double EndError(const std::vector<Pose2>& truth, const std::vector<Pose2>& estimate) {
  return Between(Between(truth.front(), truth.back()), Between(estimate.front(), estimate.back()))
      .translation()
      .norm();
}

// Odometry that jumps in one step (a glitch) and carries on from the jumped pose.
void InjectGlitch(std::vector<Frame>* frames, std::size_t at, const Pose2& jump) {
  const Pose2 T_jumped_odom =
      (*frames)[at].T_odom_base * jump * (*frames)[at].T_odom_base.Inverse();
  for (std::size_t k = at; k < frames->size(); ++k) {
    (*frames)[k].T_odom_base = T_jumped_odom * (*frames)[k].T_odom_base;
  }
}

TEST(FrontEnd, OdometryGlitchesAreCaughtAndMatchedAway) {
  const std::vector<Pose2> truth = DriveThroughTheWorld();
  std::vector<Frame> frames = MakeFrames(truth);
  // Yaw jumps of 30-80 degrees while the robot drives or turns smoothly. (A translation jump is
  // caught too; where the scan cannot tell the two poses apart, the odometry keeps the frame
  // unless the jump is beyond traction: TranslationGlitchesBeyondTraction... below.)
  InjectGlitch(&frames, 120, Pose2(0.0, 0.0, DegToRad(45.0)));
  InjectGlitch(&frames, 260, Pose2(0.0, 0.0, DegToRad(-80.0)));
  InjectGlitch(&frames, 340, Pose2(0.0, 0.0, DegToRad(60.0)));
  InjectGlitch(&frames, 420, Pose2(0.0, 0.0, DegToRad(30.0)));
  FrontEndOptions options;
  FrontEnd front_end(options);
  std::vector<Pose2> estimate;
  std::vector<Pose2> odometry;
  for (const Frame& frame : frames) {
    estimate.push_back(front_end.AddFrame(frame).T_odom_base);
    odometry.push_back(frame.T_odom_base);
  }
  const FrontEndStats& stats = front_end.Stats();
  EXPECT_GE(stats.odometry_doubtful, 4);
  // A few false alarms at most: the drive turns in place and starts again at every waypoint.
  EXPECT_LE(stats.odometry_doubtful, 20);
  EXPECT_EQ(stats.fallback_rejected, 0);
  EXPECT_GT(EndError(truth, odometry), 2.0);
  EXPECT_LT(EndError(truth, estimate), 0.15);
  const auto [estimate_xy, estimate_theta] = RelativeError(truth, estimate, 20);
  EXPECT_LT(estimate_xy, 0.02);
  EXPECT_LT(estimate_theta, DegToRad(0.5));
}

// A corridor 2 m wide and 105 m long: from x = 25 m to 70 m no end wall is within the laser's
// 30 m, so nothing the scan sees measures the position along it.
std::vector<internal::Segment> LongCorridor() {
  return {{{-5.0, -1.0}, {100.0, -1.0}},
          {{-5.0, 1.0}, {100.0, 1.0}},
          {{-5.0, -1.0}, {-5.0, 1.0}},
          {{100.0, -1.0}, {100.0, 1.0}}};
}

TEST(FrontEnd, TranslationGlitchesBeyondTractionDoNotMoveTheEstimateAlongACorridor) {
  const std::vector<Pose2> truth = Drive(Pose2(0.0, 0.0, 0.0), {{60.0, 0.0}});
  ASSERT_GT(truth.size(), 1400U);
  std::vector<Frame> frames = MakeFrames(truth, LongCorridor());
  const std::vector<Frame> clean = frames;
  // Jumps of 0.4-0.8 m along the corridor in one 0.1 s step (1 g allows 5 cm) at x = 28-52 m.
  InjectGlitch(&frames, 700, Pose2(0.6, 0.0, 0.0));
  InjectGlitch(&frames, 900, Pose2(0.5, 0.0, 0.0));
  InjectGlitch(&frames, 1100, Pose2(-0.4, 0.0, 0.0));
  InjectGlitch(&frames, 1300, Pose2(0.8, 0.0, 0.0));
  auto run = [&](const std::vector<Frame>& input, const FrontEndOptions& options) {
    FrontEnd front_end(options);
    std::vector<Pose2> estimate;
    for (const Frame& frame : input) {
      estimate.push_back(front_end.AddFrame(frame).T_odom_base);
    }
    return EndError(truth, estimate);
  };
  // Along the corridor the odometry carries the estimate, with its 2 % scale error.
  const double without_glitches = run(clean, FrontEndOptions{});
  // Without the physical limit the scan cannot tell the glitched pose from the constant
  // velocity's, and the odometry keeps the frame: every jump stays in the estimate.
  FrontEndOptions no_limit;
  no_limit.odometry_check.max_acceleration = 1e9;
  const double followed = run(frames, no_limit);
  // With it the glitched increments are no measurement, and the constant velocity holds.
  const double held = run(frames, FrontEndOptions{});
  EXPECT_GT(followed, without_glitches + 1.0);
  EXPECT_LT(held, without_glitches + 0.1);
  std::printf("end error: no glitches %.3f m, glitches followed %.3f m, held %.3f m\n",
              without_glitches, followed, held);
}

// The robot drives east, then reverses back west along the same line without turning, at 0.32 m
// per frame (a low scan rate); the odometry reports the reversal as forward motion. The motion
// check sees nothing wrong (the odometry goes on as before), but the scans no longer fit the map
// at the odometry's prediction: the poor match triggers the wide search, whose pose overrules
// the odometry.
TEST(FrontEnd, OdometryThatMissesAReversalIsOverruledByThePoorMatch) {
  std::vector<Pose2> truth;
  for (double x = 1.0; x <= 9.3; x += 0.32) truth.emplace_back(x, 3.7, 0.0);
  const double turn_x = truth.back().x();
  for (double x = turn_x - 0.32; x >= 2.0; x -= 0.32) truth.emplace_back(x, 3.7, 0.0);
  std::vector<Frame> frames = MakeFrames(truth);
  // The odometry: every step forward, by its length.
  Pose2 odometry = truth.front();
  for (std::size_t k = 1; k < frames.size(); ++k) {
    const Pose2 step = Between(truth[k - 1], truth[k]);
    odometry = odometry * Pose2(std::abs(step.x()), step.y(), step.theta());
    frames[k].T_odom_base = odometry;
  }
  auto run = [&](bool enabled) {
    FrontEndOptions options;
    options.poor_match.enabled = enabled;
    options.poor_match.window = 15;  // the drive east has 26 frames
    FrontEnd front_end(options);
    Pose2 last;
    for (const Frame& frame : frames) {
      last = front_end.AddFrame(frame).T_odom_base;
    }
    return std::make_pair(front_end.Stats(), last);
  };
  const auto [off_stats, off_last] = run(false);
  const auto [stats, last] = run(true);
  // Without the check the estimate follows the odometry east; with it, the scans bring it back.
  EXPECT_GT((off_last.translation() - truth.back().translation()).norm(), 2.0);
  EXPECT_EQ(off_stats.poor_matches, 0);
  EXPECT_LT((last.translation() - truth.back().translation()).norm(), 0.15);
  EXPECT_LT(std::abs(NormalizeAngle(last.theta() - truth.back().theta())), 0.03);
  EXPECT_GT(stats.poor_rescued, 0);
  // Once overruled, the odometry stays doubtful until a match confirms it; it never does here.
  EXPECT_EQ(off_stats.odometry_doubtful, 0);
  EXPECT_GT(stats.odometry_overruled, static_cast<int>(frames.size()) / 3);
}

TEST(FrontEnd, WithoutOdometryTheScansAloneCarryTheEstimate) {
  const std::vector<Pose2> truth = DriveThroughTheWorld();
  std::vector<Frame> frames = MakeFrames(truth);
  for (Frame& frame : frames) {
    frame.has_odometry = false;
    frame.T_odom_base = Pose2();
  }
  FrontEnd front_end(FrontEndOptions{});
  std::vector<Pose2> estimate;
  for (const Frame& frame : frames) {
    estimate.push_back(front_end.AddFrame(frame).T_odom_base);
  }
  const FrontEndStats& stats = front_end.Stats();
  EXPECT_EQ(stats.odometry_missing, static_cast<long>(frames.size()) - 1);
  EXPECT_EQ(stats.matched, static_cast<long>(frames.size()) - 1);
  EXPECT_LT(EndError(truth, estimate), 0.15);
  const auto [estimate_xy, estimate_theta] = RelativeError(truth, estimate, 20);
  EXPECT_LT(estimate_xy, 0.02);
  EXPECT_LT(estimate_theta, DegToRad(0.5));
}

TEST(FrontEnd, ScansWithoutReturnsFallBackToOdometryAndMarkNothing) {
  std::vector<Pose2> truth = DriveThroughTheWorld();
  truth.resize(60);
  std::vector<Frame> frames = MakeFrames(truth);
  // Frames 20-29: all no-returns, NaN, negative or empty.
  for (std::size_t k = 20; k < 30; ++k) {
    LaserScan& scan = frames[k].scan;
    if (k % 2 == 0) {
      scan.ranges.clear();
    } else {
      for (std::size_t b = 0; b < scan.size(); ++b) {
        const float values[] = {81.83F, 81.91F, 30.0F, std::numeric_limits<float>::quiet_NaN(),
                                -1.0F};
        scan.ranges[b] = values[b % 5];
      }
    }
  }
  FrontEndOptions options;
  options.local_map.clear_no_returns = true;
  FrontEnd front_end(options);
  Pose2 previous_estimate;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const long obstacles_before =
        front_end.Window() != nullptr ? front_end.Window()->NumObstacles() : 0;
    const FrontEndStep step = front_end.AddFrame(frames[k]);
    if (k >= 20 && k < 30) {
      EXPECT_EQ(step.status, FrameStatus::kFallbackFewPoints);
      EXPECT_LE(front_end.Window()->NumObstacles(), obstacles_before);
      // The pose follows the odometry increment.
      EXPECT_TRUE(IsApprox(Between(previous_estimate, step.T_odom_base),
                           Between(frames[k - 1].T_odom_base, frames[k].T_odom_base), 1e-9, 1e-9));
    }
    previous_estimate = step.T_odom_base;
  }
  EXPECT_EQ(front_end.Stats().fallback_few_points, 10);
  EXPECT_EQ(front_end.Stats().matched, 49);
}

TEST(FrontEnd, OdometryOnlyModeReturnsTheOdometry) {
  std::vector<Pose2> truth = DriveThroughTheWorld();
  truth.resize(50);
  const std::vector<Frame> frames = MakeFrames(truth);
  FrontEndOptions options;
  options.match = false;
  FrontEnd front_end(options);
  for (const Frame& frame : frames) {
    const FrontEndStep step = front_end.AddFrame(frame);
    EXPECT_TRUE(IsApprox(step.T_odom_base, frame.T_odom_base, 1e-9, 1e-9));
  }
  EXPECT_EQ(front_end.Stats().matched, 0);
}

}  // namespace
}  // namespace gridslam::scan_matching
