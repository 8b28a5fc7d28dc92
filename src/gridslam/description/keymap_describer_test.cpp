#include "gridslam/description/keymap_describer.hpp"

#include <algorithm>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "gridslam/grid/log_odds.hpp"
#include "gridslam/matching/align.hpp"

namespace gridslam::description {
namespace {

struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
};

// An office-like set of walls in a world frame [m]: rooms with doors along a corridor.
std::vector<Segment> OfficeWalls() {
  std::vector<Segment> walls = {{{-6, -1}, {6, -1}}, {{-6, 1.2}, {6, 1.2}}};
  for (int k = 0; k < 4; ++k) {
    const double x0 = -6.0 + 3.0 * k;
    const double depth = 2.5 + 0.7 * k;
    walls.push_back({{x0, 1.2}, {x0, 1.2 + depth}});
    walls.push_back({{x0, 1.2 + depth}, {x0 + 3.0, 1.2 + depth}});
    walls.push_back({{x0 + 0.3 + 0.4 * k, -1}, {x0 + 0.3 + 0.4 * k, -2.0 - 0.5 * k}});
  }
  walls.push_back({{-3.5, 3.0}, {-2.5, 3.0}});
  walls.push_back({{1.0, 2.4}, {1.0, 3.6}});
  return walls;
}

// A key map (frame: yaw 0 at `centre_world`) whose grid sees `walls` moved by T_world_walls:
// walls are rasterized as obstacles, everything within 7 m of the centre is observed free.
keymap::KeyMap MakeKeyMap(const std::vector<Segment>& walls, const Pose2& T_key_walls) {
  const double resolution = 0.05;
  const int size = 300;
  keymap::KeyMap key_map;
  const MapLimits limits(resolution, Eigen::Vector2d(-7.5, -7.5), size, size);
  key_map.log_odds = Grid2D<float>(limits, kUnknownLogOdds);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      if (limits.CellCenter({i, j}).norm() < 7.0) {
        key_map.log_odds(i, j) = -2.0F;
      }
    }
  }
  for (const Segment& s : walls) {
    const Eigen::Vector2d a = T_key_walls * s.a;
    const Eigen::Vector2d b = T_key_walls * s.b;
    const int steps = static_cast<int>((b - a).norm() / (0.25 * resolution)) + 1;
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(k) / steps);
      const Eigen::Array2i cell = limits.CellIndex(p);
      if (limits.Contains(cell) && p.norm() < 7.0) {
        key_map.log_odds.at(cell) = 3.0F;
      }
    }
  }
  return key_map;
}

TEST(KeyMapDescriber, FeaturesAreMetricAndObstaclesFound) {
  const KeyMapDescriber describer{DescriptionOptions{}};
  const keymap::KeyMap key_map = MakeKeyMap(OfficeWalls(), Pose2::Identity());
  const KeyMapDescription d = describer.Describe(key_map);
  EXPECT_GE(d.features.size(), 10);
  EXPECT_EQ(d.features.laplacian_sign.size(), d.features.points.size());
  EXPECT_EQ(d.features.descriptors.rows, d.features.size());
  EXPECT_GT(d.obstacle_points.size(), 500U);
  for (const auto& p : d.features.points) {
    EXPECT_LT(p.cwiseAbs().maxCoeff(), 7.5);
  }
  // An obstacle cell has distance 0; an unobserved corner is unknown.
  const Eigen::Array2i wall = key_map.log_odds.Limits().CellIndex(Eigen::Vector2d(0.0, -1.0));
  EXPECT_NEAR(d.distance.at(wall), 0.0F, 1e-6F);
  EXPECT_LT(d.distance(0, 0), 0.0F);
}

// Two key maps of the same walls, the second seeing them rotated and shifted: the aligner must
// recover T_a_b (p_a = T_a_b * p_b) from the descriptions alone, for several rotations.
TEST(KeyMapDescriber, AlignmentRecoversKnownTransform) {
  const KeyMapDescriber describer{DescriptionOptions{}};
  const auto walls = OfficeWalls();
  const keymap::KeyMap map_a = MakeKeyMap(walls, Pose2::Identity());
  const KeyMapDescription a = describer.Describe(map_a);
  for (const double angle_deg : {0.0, 30.0, 90.0, 137.0}) {
    const Pose2 T_b_walls(0.4, -0.3, angle_deg * std::numbers::pi / 180.0);
    const keymap::KeyMap map_b = MakeKeyMap(walls, T_b_walls);
    const KeyMapDescription b = describer.Describe(map_b);
    const auto verification = KeyMapDescription::Verification(a, b);
    const matching::AlignResult result =
        matching::Align(a.features, b.features, matching::AlignOptions{}, &verification);
    ASSERT_TRUE(result.accepted) << angle_deg << " deg: " << ToString(result.reason);
    const Pose2 expected = T_b_walls.Inverse();  // T_a_b with a = walls frame
    EXPECT_LT((result.T_a_b.translation() - expected.translation()).norm(), 0.05) << angle_deg;
    EXPECT_LT(std::abs(NormalizeAngle(result.T_a_b.theta() - expected.theta())), 0.01) << angle_deg;
  }
}

// With a detection margin the detector also searches near the key map's edge, where its larger
// filters do not fit inside the image; the keypoints it finds far from the edge are kept (the
// margin is a multiple of the coarsest sampling step, so the sampling grids do not move), and
// none lies outside the key map.
TEST(KeyMapDescriber, DetectionMarginAddsFeaturesNearTheEdge) {
  const keymap::KeyMap key_map = MakeKeyMap(OfficeWalls(), Pose2(3.5, 3.0, 0.3));
  DescriptionOptions options;
  const KeyMapDescription without = KeyMapDescriber(options).Describe(key_map);
  options.detection_margin = 2.5;
  const KeyMapDescription with = KeyMapDescriber(options).Describe(key_map);
  ASSERT_GE(without.features.size(), 5);
  EXPECT_GT(with.features.size(), without.features.size());
  EXPECT_EQ(with.features.descriptors.rows, with.features.size());
  const MapLimits& limits = key_map.log_odds.Limits();
  const auto edge_distance = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d lo = p - limits.Origin();
    const Eigen::Vector2d hi =
        limits.Origin() + Eigen::Vector2d(limits.Width(), limits.Height()) * 0.05 - p;
    return std::min(lo.minCoeff(), hi.minCoeff());
  };
  double closest_without = 1e9;
  for (const auto& p : without.features.points) {
    closest_without = std::min(closest_without, edge_distance(p));
  }
  double closest_with = 1e9;
  for (const auto& p : with.features.points) {
    EXPECT_GE(edge_distance(p), 0.0);
    closest_with = std::min(closest_with, edge_distance(p));
  }
  EXPECT_LT(closest_with, closest_without);
  // Away from the edge (beyond the largest filter's half extent, 4.9 m) nothing changes; nearer,
  // a sub-sample fit may now move to a sample that had no neighbourhood before.
  int inner = 0;
  for (int k = 0; k < without.features.size(); ++k) {
    const auto& p = without.features.points[static_cast<std::size_t>(k)];
    if (edge_distance(p) < 5.0) {
      continue;
    }
    ++inner;
    bool found = false;
    for (const auto& q : with.features.points) {
      found = found || (p - q).norm() < 1e-6;
    }
    EXPECT_TRUE(found) << "keypoint " << k << " at " << p.transpose() << " lost";
  }
  EXPECT_GT(inner, 0);
}

}  // namespace
}  // namespace gridslam::description
