#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "gridslam/pipeline/key_map_aligner.hpp"

namespace gridslam::pipeline {
namespace {

// A small key map: a wall across it, observed free in front.
description::KeyMapCells Wall() {
  const MapLimits limits(0.05, Eigen::Vector2d(-2.0, -2.0), 80, 80);
  Grid2D<float> log_odds(limits, 0.0F);
  for (int i = 0; i < 80; ++i) {
    for (int j = 0; j < 80; ++j) {
      const double y = limits.CellCenter({i, j}).y();
      log_odds(i, j) = std::abs(y - 1.0) < 0.03 ? 2.0F : (y < 1.0 ? -2.0F : 0.0F);
    }
  }
  return description::KeyMapCells(log_odds, 0.4F, 0.1F);
}

TEST(GeometryCache, ServesWhatItHoldsAndRecomputesTheSameAfterAClear) {
  const description::KeyMapCells cells = Wall();
  GeometryCache cache(4);
  const GeometryCache::Geometry first = cache.Get(7, cells);  // a miss: computed
  EXPECT_EQ(cache.misses(), 1);
  EXPECT_EQ(cache.Get(7, cells), first);  // a hit: the same object
  EXPECT_EQ(cache.misses(), 1);
  EXPECT_EQ(cache.size(), 1U);

  cache.Clear();
  EXPECT_EQ(cache.size(), 0U);
  const GeometryCache::Geometry again = cache.Get(7, cells);
  EXPECT_EQ(cache.misses(), 2);
  EXPECT_NE(again, first);
  // Recomputed from the cells: the same values.
  ASSERT_EQ(again->obstacle_points.size(), first->obstacle_points.size());
  EXPECT_FALSE(again->obstacle_points.empty());
  ASSERT_EQ(again->distance.size(), first->distance.size());
  for (std::size_t k = 0; k < first->distance.size(); ++k) {
    ASSERT_EQ(again->distance.data()[k], first->distance.data()[k]) << k;
  }
}

TEST(GeometryCache, KeepsAtMostItsCapacity) {
  const description::KeyMapCells cells = Wall();
  GeometryCache cache(2);
  for (int id = 0; id < 5; ++id) {
    (void)cache.Get(id, cells);
  }
  EXPECT_EQ(cache.size(), 2U);
  (void)cache.Get(4, cells);  // the most recent: still there
  EXPECT_EQ(cache.misses(), 5);
  (void)cache.Get(0, cells);  // evicted long ago
  EXPECT_EQ(cache.misses(), 6);
}

}  // namespace
}  // namespace gridslam::pipeline
