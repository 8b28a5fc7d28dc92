#include "gridslam/scan_matching/match_score_monitor.hpp"

#include <random>

#include <gtest/gtest.h>

namespace gridslam::scan_matching {
namespace {

PoorMatchOptions Window(int window) {
  PoorMatchOptions options;
  options.window = window;
  return options;
}

TEST(MatchScoreMonitor, NothingIsPoorBeforeTheWindowHasFilled) {
  MatchScoreMonitor monitor(Window(10));
  for (int k = 0; k < 9; ++k) monitor.Add(0.95);
  EXPECT_FALSE(monitor.Poor(0.0));
  EXPECT_FALSE(monitor.Usual(1.0));
  monitor.Add(0.95);
  EXPECT_TRUE(monitor.Poor(0.0));
  EXPECT_TRUE(monitor.Usual(0.95));
}

TEST(MatchScoreMonitor, AnOfficeAndAHallHaveTheirOwnLevels) {
  std::mt19937 rng(1);
  // An office: scores 0.95 +- 0.01. A drop to 0.7 is poor; 0.85 is within min_drop.
  MatchScoreMonitor office(Window(100));
  std::normal_distribution<double> office_scores(0.95, 0.01);
  for (int k = 0; k < 100; ++k) office.Add(office_scores(rng));
  EXPECT_TRUE(office.Poor(0.7));
  EXPECT_FALSE(office.Poor(0.85));
  EXPECT_NEAR(office.Threshold(), 0.80, 0.01);
  EXPECT_TRUE(office.Usual(0.95));
  EXPECT_TRUE(office.Usual(0.94));
  EXPECT_TRUE(office.Usual(0.91));  // within usual_floor
  EXPECT_FALSE(office.Usual(0.85));
  // A hall: scores 0.7 +- 0.08. The same 0.6 is ordinary there; only far lower is poor.
  MatchScoreMonitor hall(Window(100));
  std::normal_distribution<double> hall_scores(0.7, 0.08);
  for (int k = 0; k < 100; ++k) hall.Add(hall_scores(rng));
  EXPECT_FALSE(hall.Poor(0.6));
  EXPECT_FALSE(hall.Poor(0.3));
  EXPECT_TRUE(hall.Poor(0.1));
}

TEST(MatchScoreMonitor, TheWindowForgetsOldScores) {
  MatchScoreMonitor monitor(Window(20));
  for (int k = 0; k < 20; ++k) monitor.Add(0.95);
  EXPECT_TRUE(monitor.Poor(0.6));
  for (int k = 0; k < 20; ++k) monitor.Add(0.6);
  EXPECT_FALSE(monitor.Poor(0.6));
}

MatchScoreMonitor Office() {
  MatchScoreMonitor monitor(Window(20));
  for (int k = 0; k < 20; ++k) monitor.Add(0.95);
  return monitor;
}

TEST(MatchScoreMonitor, ARescueMustBeClearlyBetterUsualAndUnique) {
  const MatchScoreMonitor office = Office();
  const RescueRule rule;  // margin 0.05, distinct beyond 0.3 m or 0.07 rad
  EXPECT_EQ(office.Choose({}, Pose2(), 0.5, rule).verdict, RescueVerdict::kNone);
  // One clear winner; a refinement that converged to (nearly) the same pose is no rival.
  RescueChoice c = office.Choose(
      {{Pose2(0.1, 0.0, 0.0), 0.7}, {Pose2(-0.6, 0.0, 0.0), 0.96}, {Pose2(-0.58, 0.01, 0.0), 0.95}},
      Pose2(), 0.6, rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kRescued);
  EXPECT_EQ(c.best, 1U);
  ASSERT_TRUE(c.has_rival);
  EXPECT_EQ(c.rival, 0U);
  // A look-alike along the corridor, or turned, as near the prediction and scoring about as
  // well: ambiguous.
  c = office.Choose({{Pose2(-0.6, 0.0, 0.0), 0.96}, {Pose2(0.5, 0.0, 0.0), 0.93}}, Pose2(), 0.6,
                    rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kAmbiguous);
  c = office.Choose({{Pose2(-0.6, 0.0, 0.0), 0.96}, {Pose2(0.0, 0.0, 0.5), 0.92}}, Pose2(), 0.6,
                    rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kAmbiguous);
  // The same look-alikes farther from the prediction than the best pose: the prediction decides.
  c = office.Choose({{Pose2(-0.6, 0.0, 0.0), 0.96}, {Pose2(-1.0, 0.8, 0.0), 0.93}}, Pose2(), 0.6,
                    rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kRescued);
  c = office.Choose({{Pose2(-0.6, 0.0, 0.0), 0.96}, {Pose2(-0.6, 0.0, 1.6), 0.95}}, Pose2(), 0.6,
                    rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kRescued);
  // Not clearly better than the poor match, or not a usual score for this office.
  c = office.Choose({{Pose2(-0.6, 0.0, 0.0), 0.96}}, Pose2(), 0.93, rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kNotClear);
  c = office.Choose({{Pose2(-0.6, 0.0, 0.0), 0.75}}, Pose2(), 0.5, rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kNotClear);
  // A failed match (poor score -1) is beaten by any usual pose.
  c = office.Choose({{Pose2(-0.6, 0.0, 0.0), 0.94}}, Pose2(), -1.0, rule);
  EXPECT_EQ(c.verdict, RescueVerdict::kRescued);
}

TEST(PoorMatchOptions, ValidateRejectsBadValues) {
  EXPECT_TRUE(PoorMatchOptions{}.Validate().ok());
  PoorMatchOptions bad;
  bad.window = 0;
  EXPECT_FALSE(bad.Validate().ok());
  bad = PoorMatchOptions{};
  bad.min_drop = 1.0;
  EXPECT_FALSE(bad.Validate().ok());
}

}  // namespace
}  // namespace gridslam::scan_matching
