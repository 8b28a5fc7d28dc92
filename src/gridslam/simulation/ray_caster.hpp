// Exact ray casting on a World's wall grid: a grid traversal (Amanatides & Woo 1987, "A fast
// voxel traversal algorithm") visits the cells a ray crosses in order and stops at the first
// wall cell, returning the distance to that cell's boundary, so a wall whose face lies on a cell
// boundary at distance d is measured as exactly d. Far from walls the ray jumps ahead by the
// clearance field (sphere tracing), which gives the same answer in a fraction of the steps.
#pragma once

#include <Eigen/Core>

#include "gridslam/simulation/world.hpp"

namespace gridslam::simulation {

struct RayHit {
  bool hit = false;    ///< A wall was hit within the maximum range.
  double range = 0.0;  ///< Distance to the hit [m]; the maximum range if !hit.
};

class RayCaster {
 public:
  /// `world` must outlive the caster. With `use_clearance` false every cell is visited (the
  /// reference implementation, for tests).
  explicit RayCaster(const World& world, bool use_clearance = true)
      : world_(world), use_clearance_(use_clearance) {}

  /// Casts a ray from `origin` (world frame) in direction `angle` [rad] up to `max_range` [m].
  /// A ray starting in a wall cell hits at range 0; leaving the grid counts as a hit on its
  /// boundary (the world is closed).
  [[nodiscard]] RayHit Cast(const Eigen::Vector2d& origin, double angle, double max_range) const;

  /// True when the segment from `a` to `b` crosses no wall cell.
  [[nodiscard]] bool LineOfSight(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

 private:
  const World& world_;
  bool use_clearance_;
};

}  // namespace gridslam::simulation
