// A laser scan turned into what the local map and the scan matcher consume: the returns as points
// in the robot (base) frame, each with a surface normal estimated by PCA over its neighbouring
// beams (as PL-ICP's orientation estimate, docs/method.md §6 step 1), the laser's position,
// and the directions of the no-return beams (which may clear free space but never mark
// obstacles, docs/design.md §1.1). Works for any beam count and per-scan start angle (interleaved
// scanners) and applies the laser's mounting on the robot.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam {

struct ScanPoints {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< Laser position in the base frame [m].
  std::vector<Eigen::Vector2d> points;   ///< Returns (LaserScan::IsHit) in the base frame [m].
  std::vector<Eigen::Vector2d> normals;  ///< Unit normals in the base frame; zero if unknown.
  std::vector<float> normal_quality;     ///< 1 = clean line through the neighbours, 0 = unknown.
  std::vector<Eigen::Vector2d> no_return_directions;  ///< Unit directions of beams >= range_max.

  [[nodiscard]] std::size_t size() const { return points.size(); }
};

/// Converts `scan` with the laser mounting `T_base_laser`. Returns farther than `max_range` [m]
/// are dropped (they count neither as hits nor as no-returns); readings that are not finite or at
/// or below range_min are ignored. Normals use up to two hits on either side of a beam that lie
/// within `neighbour_distance` [m] of it, or within six beam spacings at its range if that is
/// more (far walls seen at a grazing angle). With `grazing_normals`, a return with no such
/// neighbour that lies on the line through the returns of the beams on either side, between them,
/// gets that line's normal (a wall at grazing incidence; an isolated object keeps none).
ScanPoints ExtractScanPoints(const LaserScan& scan, const Pose2& T_base_laser, double max_range,
                             double neighbour_distance = 0.25, bool grazing_normals = false);

/// The returns of a scan alone (no normals, no no-return directions).
struct ScanReturns {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< Laser position in the base frame [m].
  std::vector<Eigen::Vector2d> points;               ///< As ScanPoints::points, the same numbers.
};

/// ExtractScanPoints' points and origin without the rest (for ray casting and replays).
ScanReturns ExtractScanReturns(const LaserScan& scan, const Pose2& T_base_laser, double max_range);

}  // namespace gridslam
