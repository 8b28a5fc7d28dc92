#include "gridslam/description/key_map_cells.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/matching/grid_verification.hpp"

namespace gridslam::description {
namespace {

// Random log-odds with obstacles, free and unknown cells, NaN and both infinities; a cell count
// that is not a multiple of 64.
Grid2D<float> RandomLogOdds(int width, int height, unsigned seed) {
  const MapLimits limits(0.05, Eigen::Vector2d(-1.0, 2.0), width, height);
  Grid2D<float> log_odds(limits, 0.0F);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-3.0F, 3.0F);
  std::uniform_int_distribution<int> kind(0, 99);
  for (std::size_t k = 0; k < log_odds.size(); ++k) {
    const int c = kind(rng);
    float v = value(rng);
    if (c == 0) {
      v = std::numeric_limits<float>::quiet_NaN();
    } else if (c == 1) {
      v = std::numeric_limits<float>::infinity();
    } else if (c == 2) {
      v = -std::numeric_limits<float>::infinity();
    } else if (c < 40) {
      v = 0.0F;
    } else if (c < 45) {
      v = 0.05F;  // exactly at the observed threshold: not observed
    }
    log_odds.data()[k] = v;
  }
  return log_odds;
}

TEST(KeyMapCells, BitsFollowTheThresholds) {
  for (const auto& [width, height] : {std::pair{37, 23}, std::pair{64, 3}, std::pair{1, 1}}) {
    const Grid2D<float> log_odds = RandomLogOdds(width, height, 7U + static_cast<unsigned>(width));
    const KeyMapCells cells(log_odds, 0.6F, 0.05F);
    for (int j = 0; j < height; ++j) {
      for (int i = 0; i < width; ++i) {
        const float l = log_odds(i, j);
        EXPECT_EQ(cells.Obstacle(i, j), l > 0.6F) << i << " " << j;
        EXPECT_EQ(cells.Observed(i, j), std::abs(l) > 0.05F) << i << " " << j;
      }
    }
    // The bits past the last cell are clear.
    const std::size_t n = log_odds.size();
    if (n % 64 != 0) {
      EXPECT_EQ(cells.ObstacleBits().back() >> (n % 64), 0U);
      EXPECT_EQ(cells.ObservedBits().back() >> (n % 64), 0U);
    }
  }
}

TEST(KeyMapCells, GeometryIsTheSameFromEveryDistanceSource) {
  const Grid2D<float> log_odds = RandomLogOdds(83, 61, 3U);
  const KeyMapCells cells(log_odds, 0.6F, 0.05F);
  const cv::Mat distance_cells = distance_transform::DistanceTransformCells(ObstacleImage(cells));
  distance_transform::SquaredDistanceField field;
  SquaredObstacleDistances(cells, field);
  const KeyMapGeometry from_image = ComputeGeometry(cells, &distance_cells);
  const KeyMapGeometry computed = ComputeGeometry(cells);
  const KeyMapGeometry from_field = ComputeGeometry(cells, field);
  for (const KeyMapGeometry* g : {&computed, &from_field}) {
    ASSERT_EQ(g->distance.size(), from_image.distance.size());
    for (std::size_t k = 0; k < from_image.distance.size(); ++k) {
      EXPECT_EQ(g->distance.data()[k], from_image.distance.data()[k]) << k;
    }
    EXPECT_EQ(g->obstacle_points, from_image.obstacle_points);
  }
  int unknown = 0;
  for (std::size_t k = 0; k < from_image.distance.size(); ++k) {
    unknown += from_image.distance.data()[k] == matching::kUnknownDistance ? 1 : 0;
  }
  EXPECT_GT(unknown, 0);
}

// The distance field by its definition, cell by cell: the distance in metres (float of the distance
// in cells times the resolution) on observed cells with an obstacle somewhere, unknown elsewhere.
// Sizes below, at and above a multiple of 64 cells, and a key map observed everywhere (whole words
// of observed cells).
TEST(KeyMapCells, GeometryDistanceFollowsItsDefinition) {
  for (const auto& [width, height, fill] : {std::tuple{83, 61, false}, std::tuple{64, 5, false},
                                            std::tuple{65, 3, true}, std::tuple{1, 1, true}}) {
    Grid2D<float> log_odds = RandomLogOdds(width, height, 11U + static_cast<unsigned>(width));
    if (fill) {  // every cell observed, a few obstacles
      for (std::size_t k = 0; k < log_odds.size(); ++k) {
        log_odds.data()[k] = k % 7 == 3 ? 2.0F : -1.0F;
      }
    }
    const KeyMapCells cells(log_odds, 0.6F, 0.05F);
    const cv::Mat distance_cells = distance_transform::DistanceTransformCells(ObstacleImage(cells));
    const KeyMapGeometry geometry = ComputeGeometry(cells);
    ASSERT_EQ(geometry.distance.Width(), width);
    ASSERT_EQ(geometry.distance.Height(), height);
    for (int j = 0; j < height; ++j) {
      for (int i = 0; i < width; ++i) {
        const float d = distance_cells.at<float>(j, i);
        const float expected = cells.Observed(i, j) && std::isfinite(d)
                                   ? static_cast<float>(d * cells.Limits().Resolution())
                                   : matching::kUnknownDistance;
        EXPECT_EQ(geometry.distance(i, j), expected) << i << " " << j;
      }
    }
  }
}

}  // namespace
}  // namespace gridslam::description
