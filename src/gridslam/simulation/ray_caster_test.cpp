#include "gridslam/simulation/ray_caster.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "gridslam/simulation/random.hpp"

namespace gridslam::simulation {
namespace {

// A 10 x 10 m room with free space [0.5, 9.5) x [0.5, 9.5) and a wall whose face is at x = 6.
World RoomWithWall() {
  WorldBuilder builder(10.0, 10.0, 0.05);
  builder.Carve(0.5, 0.5, 9.5, 9.5).Fill(6.0, 0.5, 6.2, 9.5);
  return builder.Build("room", {});
}

// Distance from (x, y) along `angle` to the first of the planes x = 6 (or x = 0.5 going left),
// y = 9.5 and y = 0.5.
double Expected(double x, double y, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  double d = std::numeric_limits<double>::infinity();
  if (c > 1e-12) d = std::min(d, (6.0 - x) / c);
  if (c < -1e-12) d = std::min(d, (x - 0.5) / -c);
  if (s > 1e-12) d = std::min(d, (9.5 - y) / s);
  if (s < -1e-12) d = std::min(d, (y - 0.5) / -s);
  return d;
}

TEST(RayCasterTest, RaysHitWallsWhereGeometrySaysTheyMust) {
  const World world = RoomWithWall();
  for (const bool accelerated : {false, true}) {
    const RayCaster caster(world, accelerated);
    const RayHit ahead = caster.Cast({1.0, 5.0}, 0.0, 30.0);
    EXPECT_TRUE(ahead.hit);
    EXPECT_NEAR(ahead.range, 5.0, 1e-9);
    for (int k = 0; k < 720; ++k) {
      const double angle = -std::numbers::pi + k * std::numbers::pi / 360.0;
      for (const Eigen::Vector2d& p : {Eigen::Vector2d(1.0, 5.0), Eigen::Vector2d(3.27, 2.91)}) {
        const RayHit hit = caster.Cast(p, angle, 30.0);
        ASSERT_TRUE(hit.hit);
        EXPECT_NEAR(hit.range, Expected(p.x(), p.y(), angle), 1e-9) << "angle " << angle;
      }
    }
  }
}

TEST(RayCasterTest, NoHitBeyondTheMaximumRange) {
  const World world = RoomWithWall();
  const RayCaster caster(world);
  const RayHit hit = caster.Cast({1.0, 5.0}, 0.0, 4.5);
  EXPECT_FALSE(hit.hit);
  EXPECT_EQ(hit.range, 4.5);
  EXPECT_TRUE(caster.Cast({1.0, 5.0}, 0.0, 5.01).hit);
}

TEST(RayCasterTest, RayStartingInAWallHitsAtZero) {
  const World world = RoomWithWall();
  const RayHit hit = RayCaster(world).Cast({6.1, 5.0}, 1.0, 30.0);
  EXPECT_TRUE(hit.hit);
  EXPECT_EQ(hit.range, 0.0);
}

TEST(RayCasterTest, SkippingEmptySpaceGivesTheSameRangesAsVisitingEveryCell) {
  const World world = MakeBuiltinWorld("office", 0.05).value();
  const RayCaster fast(world, true);
  const RayCaster reference(world, false);
  Random random(7);
  int tested = 0;
  while (tested < 2000) {
    const Eigen::Vector2d p(random.Uniform(0.0, 50.0), random.Uniform(0.0, 50.0));
    if (world.IsWall(p)) {
      continue;
    }
    ++tested;
    const double angle = random.Uniform(-std::numbers::pi, std::numbers::pi);
    const RayHit a = fast.Cast(p, angle, 30.0);
    const RayHit b = reference.Cast(p, angle, 30.0);
    ASSERT_EQ(a.hit, b.hit);
    EXPECT_NEAR(a.range, b.range, 1e-9);
    if (b.hit) {
      // Just before the hit the ray is in free space, just after it in a wall.
      const Eigen::Vector2d u(std::cos(angle), std::sin(angle));
      EXPECT_FALSE(world.IsWall(p + (b.range - 1e-6) * u));
      EXPECT_TRUE(world.IsWall(p + (b.range + 1e-6) * u));
    }
  }
}

TEST(RayCasterTest, LineOfSight) {
  const World world = RoomWithWall();
  const RayCaster caster(world);
  EXPECT_TRUE(caster.LineOfSight({1.0, 1.0}, {5.9, 9.0}));
  EXPECT_FALSE(caster.LineOfSight({1.0, 1.0}, {7.0, 1.0}));
  EXPECT_FALSE(caster.LineOfSight({6.1, 1.0}, {5.0, 1.0}));
}

}  // namespace
}  // namespace gridslam::simulation
