#include "gridslam/simulation/route.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace gridslam::simulation {
namespace {

Route Square() {
  return Route::Make({{0.0, 0.0}, {4.0, 0.0}, {4.0, 4.0}, {0.0, 4.0}, {0.0, 0.0}}).value();
}

TEST(RouteTest, ArcLengthParameterization) {
  const Route route = Square();
  EXPECT_DOUBLE_EQ(route.Length(), 16.0);
  EXPECT_TRUE(route.PointAt(2.0).isApprox(Eigen::Vector2d(2.0, 0.0)));
  EXPECT_TRUE(route.PointAt(6.0).isApprox(Eigen::Vector2d(4.0, 2.0)));
  EXPECT_TRUE(route.PointAt(18.0).isApprox(Eigen::Vector2d(2.0, 0.0)));  // wraps
  EXPECT_TRUE(route.PointAt(-2.0).isApprox(Eigen::Vector2d(0.0, 2.0)));  // wraps backwards
  EXPECT_NEAR(route.Project({2.0, 0.3}, 0.0, 4.0), 2.0, 1e-12);
  EXPECT_NEAR(route.Project({2.0, 0.3}, 16.0, 20.0), 18.0, 1e-12);
  // Only the window counts: the point near the last side is projected onto the first one.
  EXPECT_NEAR(route.Project({0.1, 1.0}, 0.0, 3.0), 0.1, 1e-12);
  EXPECT_NEAR(route.Project({0.1, 1.0}, 10.0, 16.0), 15.0, 1e-12);
}

TEST(RouteTest, OpenRoutesGoThereAndBack) {
  const auto route = Route::Make({{0.0, 0.0}, {3.0, 0.0}, {3.0, 1.0}});
  ASSERT_TRUE(route.ok());
  EXPECT_DOUBLE_EQ(route.value().Length(), 8.0);
  EXPECT_TRUE(route.value().PointAt(6.0).isApprox(Eigen::Vector2d(2.0, 0.0)));
  EXPECT_FALSE(Route::Make({{0.0, 0.0}}).ok());
  EXPECT_FALSE(Route::Make({{0.0, 0.0}, {0.0, 0.0}, {1.0, 0.0}}).ok());
}

TEST(RouteTest, ReversedRunsTheOtherWay) {
  const Route reversed = Square().Reversed();
  EXPECT_DOUBLE_EQ(reversed.Length(), 16.0);
  EXPECT_TRUE(reversed.PointAt(2.0).isApprox(Eigen::Vector2d(0.0, 2.0)));
}

TEST(PurePursuitTest, FollowsASquareClosely) {
  const Route route = Square();
  MotionSimOptions options;
  PurePursuit controller(route, options, 2.0, 2.0 + route.Length());
  RobotState state{controller.StartPose(), 0.0, 0.0};
  EXPECT_NEAR(state.pose.theta(), 0.0, 1e-12);
  const double dt = options.control_period;
  double max_deviation = 0.0;
  int steps = 0;
  while (!controller.Finished() && steps < 100000) {
    controller.Control(state, dt);
    EXPECT_LE(std::abs(state.v), options.max_speed + 1e-9);
    EXPECT_LE(std::abs(state.w), options.max_angular_speed + 1e-9);
    state.pose = IntegrateUnicycle(state.pose, state.v, state.w, dt);
    const Eigen::Vector2d p = state.pose.translation();
    const double s = route.Project(p, 0.0, route.Length());
    max_deviation = std::max(max_deviation, (route.PointAt(s) - p).norm());
    ++steps;
  }
  EXPECT_TRUE(controller.Finished());
  EXPECT_NEAR((state.pose.translation() - Eigen::Vector2d(2.0, 0.0)).norm(), 0.0, 0.05);
  EXPECT_LT(max_deviation, 0.35);  // corners are cut by a fraction of the lookahead
  // 16 m at 0.5 m/s plus slowing down in the corners.
  EXPECT_LT(steps * dt, 60.0);
}

TEST(PurePursuitTest, UnicycleIntegrationIsExactOnArcs) {
  // A quarter circle of radius 2: v = 1, w = 0.5, for pi seconds.
  Pose2 pose;
  const int n = 1000;
  for (int k = 0; k < n; ++k) {
    pose = IntegrateUnicycle(pose, 1.0, 0.5, std::numbers::pi / n);
  }
  EXPECT_NEAR(pose.x(), 2.0, 1e-9);
  EXPECT_NEAR(pose.y(), 2.0, 1e-9);
  EXPECT_NEAR(pose.theta(), std::numbers::pi / 2.0, 1e-9);
}

}  // namespace
}  // namespace gridslam::simulation
