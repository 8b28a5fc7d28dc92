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
  /// Normals whose direction the scan's noise leaves within NormalEstimation::max_angle_sigma:
  /// fitted to more beams where five span too short a stretch of wall (empty unless asked for).
  /// What a wall constrains; the five-beam normals are what the matcher's residuals use.
  std::vector<Eigen::Vector2d> wall_normals;
  std::vector<float> wall_normal_quality;
  std::vector<Eigen::Vector2d> no_return_directions;  ///< Unit directions of beams >= range_max.
  /// The scatter of the returns about their surfaces as the normals' line fits measure it: the
  /// median residual of the compact five-beam windows (five hits within neighbour_distance of
  /// the middle one), unbiased for Gaussian noise [m] (0 when no window was compact).
  double surface_noise = 0.0;

  [[nodiscard]] std::size_t size() const { return points.size(); }
};

/// How the normals of a scan's returns are estimated.
struct NormalEstimation {
  /// Neighbours farther than this from a return are not part of its window [m].
  double neighbour_distance = 0.25;
  /// Isolated returns on the line through their neighbours' returns get its normal.
  bool grazing_normals = false;
  /// Normals are fitted to the return and up to two hits on either side. With max_angle_sigma >
  /// 0 [rad], the scan also gets wall_normals: where the scan's own noise (`surface_noise`) over
  /// so short a stretch of wall leaves a normal's direction a standard error above
  /// max_angle_sigma, its window grows to up to 8 beams on either side, within
  /// neighbour_distance.
  double max_angle_sigma = 0.0;
};

/// Converts `scan` with the laser mounting `T_base_laser`, normals as `normals` says.
ScanPoints ExtractScanPoints(const LaserScan& scan, const Pose2& T_base_laser, double max_range,
                             const NormalEstimation& normals);

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
