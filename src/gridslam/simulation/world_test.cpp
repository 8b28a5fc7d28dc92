#include "gridslam/simulation/world.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "gridslam/simulation/internal/distance_field.hpp"
#include "gridslam/simulation/random.hpp"
#include "gridslam/simulation/ray_caster.hpp"
#include "gridslam/simulation/simulator.hpp"

namespace gridslam::simulation {
namespace {

TEST(WorldTest, BuilderCoversCellsWhoseCentresLieInTheRectangle) {
  WorldBuilder builder(2.0, 1.0, 0.1);
  builder.Carve(0.2, 0.1, 0.5, 0.4);
  const World world = builder.Build("tiny", {});
  ASSERT_EQ(world.walls.Width(), 20);
  ASSERT_EQ(world.walls.Height(), 10);
  for (int j = 0; j < 10; ++j) {
    for (int i = 0; i < 20; ++i) {
      const bool free = i >= 2 && i < 5 && j >= 1 && j < 4;
      EXPECT_EQ(world.walls(i, j), free ? 0 : 1) << i << "," << j;
    }
  }
  EXPECT_TRUE(world.IsWall({-0.1, 0.2}));  // outside the grid
  EXPECT_FALSE(world.IsWall({0.3, 0.2}));
}

TEST(WorldTest, DistanceTransformEqualsBruteForce) {
  Random random(3);
  const int w = 37;
  const int h = 23;
  std::vector<std::uint8_t> obstacle(static_cast<std::size_t>(w * h));
  for (auto& o : obstacle) {
    o = random.Bernoulli(0.05) ? 1 : 0;
  }
  const std::vector<float> d = internal::DistanceTransform(obstacle, w, h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      double best = w + h;
      for (int q = 0; q < h; ++q) {
        for (int p = 0; p < w; ++p) {
          if (obstacle[static_cast<std::size_t>(q * w + p)] != 0) {
            best = std::min(best, std::hypot(p - i, q - j));
          }
        }
      }
      EXPECT_NEAR(d[static_cast<std::size_t>(j * w + i)], best, 1e-4);
    }
  }
}

TEST(WorldTest, ClearanceNeverOverestimatesTheDistanceToAWall) {
  WorldBuilder builder(10.0, 10.0, 0.05);
  builder.Carve(1.0, 1.0, 9.0, 9.0);
  const World world = builder.Build("box", {});
  EXPECT_LE(world.Clearance({5.0, 5.0}), 4.0);
  EXPECT_GT(world.Clearance({5.0, 5.0}), 3.9);
  EXPECT_LE(world.Clearance({1.3, 5.0}), 0.3);
  EXPECT_GT(world.Clearance({1.3, 5.0}), 0.2);
  EXPECT_EQ(world.Clearance({0.5, 5.0}), 0.0);
}

TEST(WorldTest, TrueMapMarksFreeSpaceWallFacesAndSolidInterior) {
  WorldBuilder builder(10.0, 10.0, 0.05);
  builder.Carve(2.0, 2.0, 8.0, 8.0);
  const OccupancyImage map = TrueMap(builder.Build("box", {}), 0.3);
  const MapLimits& l = map.Limits();
  EXPECT_EQ(map.at(l.CellIndex({5.0, 5.0})), kFreeCell);
  EXPECT_EQ(map.at(l.CellIndex({1.9, 5.0})), kOccupiedCell);
  EXPECT_EQ(map.at(l.CellIndex({1.76, 5.0})), kOccupiedCell);
  EXPECT_EQ(map.at(l.CellIndex({1.0, 5.0})), kUnknownCell);
}

TEST(WorldTest, FloorPlanImagesAndOccupancyMapsBecomeWorlds) {
  Grid2D<std::uint8_t> image(MapLimits(0.1, {0.0, 0.0}, 4, 2), 255);
  image(1, 0) = 20;   // dark: wall
  image(2, 1) = 200;  // light: free
  const World from_image = WorldFromGrayImage("plan", image);
  EXPECT_EQ(from_image.walls(1, 0), 1);
  EXPECT_EQ(from_image.walls(2, 1), 0);
  OccupancyImage map(MapLimits(0.1, {0.0, 0.0}, 3, 1), kFreeCell);
  map(1, 0) = kUnknownCell;
  map(2, 0) = kOccupiedCell;
  const World from_map = WorldFromOccupancy("map", map);
  EXPECT_EQ(from_map.walls(0, 0), 0);
  EXPECT_EQ(from_map.walls(1, 0), 1);
  EXPECT_EQ(from_map.walls(2, 0), 1);
}

TEST(WorldTest, BuiltinWorldsHaveTheirSizeAndACollisionFreeTour) {
  for (const std::string& name : BuiltinWorldNames()) {
    const auto world = MakeBuiltinWorld(name, 0.05);
    ASSERT_TRUE(world.ok()) << name;
    const double width = world.value().walls.Width() * 0.05;
    const double height = world.value().walls.Height() * 0.05;
    EXPECT_GE(width, 49.9) << name;
    EXPECT_GE(height, 29.9) << name;
    ASSERT_GE(world.value().route.size(), 10U) << name;
    EXPECT_TRUE((world.value().route.front() - world.value().route.back()).norm() < 1e-9)
        << name << ": the tour is closed";
    // One whole tour: Simulate fails if the robot comes within robot_radius of a wall.
    SimulationOptions options;
    options.relations.revisit_stride = 1000;
    const auto run = Simulate(world.value(), {}, options);
    ASSERT_TRUE(run.ok()) << name << ": " << run.error().ToString();
    EXPECT_GT(run.value().robots[0].distance, 300.0) << name;
    EXPECT_GE(run.value().robots[0].min_clearance, options.motion.robot_radius) << name;
  }
  EXPECT_FALSE(MakeBuiltinWorld("nowhere", 0.05).ok());
}

// Smallest travel between two visits of the same place (within `radius`) among pairs of poses
// more than `min_gap` apart along the path; +inf when the path never returns.
double ShortestLoop(const RobotRun& run, double radius, double min_gap) {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> travel;
  double s = 0.0;
  for (const Frame& f : run.frames) {
    const Eigen::Vector2d p = f.T_world_base_true->translation();
    if (!points.empty()) {
      s += (p - points.back()).norm();
      if (s - travel.back() < 0.5) {
        s -= (p - points.back()).norm();
        continue;  // one pose per 0.5 m
      }
    }
    points.push_back(p);
    travel.push_back(s);
  }
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < points.size(); ++k) {
    for (std::size_t j = 0; j < k; ++j) {
      if (travel[k] - travel[j] > min_gap && (points[k] - points[j]).norm() < radius) {
        shortest = std::min(shortest, travel[k] - travel[j]);
      }
    }
  }
  return shortest;
}

TEST(WorldTest, CampusTourIsLongAndClosesItsLoopsOnlyAfterLongExcursions) {
  const auto world = MakeBuiltinWorld("campus", 0.05);
  ASSERT_TRUE(world.ok());
  EXPECT_GE(world.value().walls.Width() * 0.05, 249.9);
  SimulationOptions options;
  options.relations.revisit_stride = 1000;
  const auto run = Simulate(world.value(), {}, options);
  ASSERT_TRUE(run.ok()) << run.error().ToString();
  const RobotRun& robot = run.value().robots[0];
  EXPECT_GT(robot.distance, 1500.0);
  // Places seen again (within 3 m) are seen again only after 300 m or more.
  const double loop = ShortestLoop(robot, 3.0, 30.0);
  EXPECT_GE(loop, 300.0);
  EXPECT_LT(loop, 400.0);  // ... and the tour does close loops (the 310 m one).
}

/// Beams of a 360-beam scan at `at`, in a corridor along x, that end more than 1.5 m to its side
/// (in a room behind a door).
int BeamsIntoRooms(const RayCaster& caster, const Eigen::Vector2d& at, double max_range) {
  int beyond = 0;
  for (int k = 0; k < 360; ++k) {
    const double angle = (k + 0.5) * 2.0 * std::numbers::pi / 360.0;
    const RayHit hit = caster.Cast(at, angle, max_range);
    beyond += std::abs(hit.range * std::sin(angle)) > 1.5 ? 1 : 0;
  }
  return beyond;
}

TEST(WorldTest, CorridorsAreASquareRingWithBlankStretchesAndRooms) {
  const auto world = MakeBuiltinWorld("corridors", 0.05);
  ASSERT_TRUE(world.ok());
  const World& w = world.value();
  // The ring: free on the centrelines of all four 60 m sides, walls beside them.
  for (const double u : {8.0, 20.0, 36.0, 50.0, 64.0}) {
    EXPECT_FALSE(w.IsWall({u, 6.0}));
    EXPECT_FALSE(w.IsWall({u, 66.0}));
    EXPECT_FALSE(w.IsWall({6.0, u}));
    EXPECT_FALSE(w.IsWall({66.0, u}));
  }
  EXPECT_TRUE(w.IsWall({36.0, 36.0}));  // the solid core
  // In the middle of the south side's blank stretch a 10 m 360-degree lidar sees the two
  // corridor walls and nothing else.
  const RayCaster caster(w);
  int hits = 0;
  for (int k = 0; k < 360; ++k) {
    const double angle = (k + 0.5) * 2.0 * std::numbers::pi / 360.0;
    const RayHit hit = caster.Cast({48.0, 6.0}, angle, 10.0);
    if (hit.hit) {
      ++hits;
      const double y = 6.0 + hit.range * std::sin(angle);
      EXPECT_NEAR(std::abs(y - 6.0), 1.2, 0.06) << "beam " << k;
    }
  }
  EXPECT_GT(hits, 300);
  // ... while the door stretch has openings into rooms (some beams reach beyond the walls).
  EXPECT_GT(BeamsIntoRooms(caster, {22.0, 6.0}, 10.0), 10);
  // The tour: twice round the ring (about 480 m) and four room visits, collision-free.
  SimulationOptions options;
  options.relations.revisit_stride = 1000;
  const auto run = Simulate(w, {}, options);
  ASSERT_TRUE(run.ok()) << run.error().ToString();
  EXPECT_GT(run.value().robots[0].distance, 480.0);
  int in_rooms = 0;  // scans taken off the ring's centre lines, i.e. inside a room
  for (const Frame& f : run.value().robots[0].frames) {
    const Eigen::Vector2d p = f.T_world_base_true->translation();
    const double off = std::min({std::abs(p.x() - 6.0), std::abs(p.x() - 66.0),
                                 std::abs(p.y() - 6.0), std::abs(p.y() - 66.0)});
    in_rooms += off > 2.0 ? 1 : 0;
  }
  EXPECT_GT(in_rooms, 4 * 10);
}

TEST(WorldTest, CourtsAreALargeRingDrivenBothWays) {
  const auto world = MakeBuiltinWorld("courts", 0.05);
  ASSERT_TRUE(world.ok());
  const World& w = world.value();
  // The ring and the middle corridor are free on their centrelines; the courtyards are solid.
  for (const double x : {14.0, 70.0, 130.0, 190.0, 246.0}) {
    EXPECT_FALSE(w.IsWall({x, 12.0}));
    EXPECT_FALSE(w.IsWall({x, 118.0}));
  }
  for (const double y : {14.0, 65.0, 116.0}) {
    EXPECT_FALSE(w.IsWall({12.0, y}));
    EXPECT_FALSE(w.IsWall({130.0, y}));
    EXPECT_FALSE(w.IsWall({248.0, y}));
  }
  EXPECT_TRUE(w.IsWall({70.0, 65.0}));
  EXPECT_TRUE(w.IsWall({190.0, 65.0}));
  // The layout draws other rooms along the same corridors; layout 0 is refused.
  const auto other = MakeBuiltinWorld("courts", 0.05, 2);
  ASSERT_TRUE(other.ok());
  EXPECT_FALSE(other.value().IsWall({130.0, 65.0}));
  int differ = 0;
  for (double x = 14.0; x < 246.0; x += 0.5) {
    differ += w.IsWall({x, 15.0}) != other.value().IsWall({x, 15.0}) ? 1 : 0;
  }
  EXPECT_GT(differ, 10);
  EXPECT_FALSE(MakeBuiltinWorld("courts", 0.05, 0).ok());
  // Rooms open off the corridors: from the south corridor some beams reach beyond its walls.
  EXPECT_GT(BeamsIntoRooms(RayCaster(w), {70.0, 12.0}, 30.0), 10);
  // The tour: about 1.8 km, collision-free; it comes back to its start only after the whole
  // ring (690 m), and some corridor is driven in both directions.
  SimulationOptions options;
  options.relations.revisit_stride = 1000;
  const auto run = Simulate(w, {}, options);
  ASSERT_TRUE(run.ok()) << run.error().ToString();
  const RobotRun& robot = run.value().robots[0];
  EXPECT_GT(robot.distance, 1750.0);
  EXPECT_LT(robot.distance, 1900.0);
  const Eigen::Vector2d start = robot.frames.front().T_world_base_true->translation();
  bool left = false;
  double travel = 0.0;
  double back_after = 0.0;  // path length when the robot first comes back near its start
  for (std::size_t k = 1; k < robot.frames.size() && back_after == 0.0; ++k) {
    const Eigen::Vector2d p = robot.frames[k].T_world_base_true->translation();
    travel += (p - robot.frames[k - 1].T_world_base_true->translation()).norm();
    left = left || (p - start).norm() > 10.0;
    if (left && (p - start).norm() < 3.0) {
      back_after = travel;
    }
  }
  EXPECT_GT(back_after, 650.0);
  bool both_ways = false;
  const auto& frames = robot.frames;
  for (std::size_t k = 0; k < frames.size() && !both_ways; k += 25) {
    for (std::size_t j = 0; j + 1000 < k && !both_ways; j += 5) {
      const Pose2& a = *frames[j].T_world_base_true;
      const Pose2& b = *frames[k].T_world_base_true;
      both_ways = (a.translation() - b.translation()).norm() < 0.5 &&
                  std::abs(NormalizeAngle(a.theta() - b.theta())) > 3.0;
    }
  }
  EXPECT_TRUE(both_ways);
}

}  // namespace
}  // namespace gridslam::simulation
