#include "gridslam/grid/scan_points.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam {
namespace {

// Normal and quality of the points in `window` (laser frame) around `centre` by PCA: the normal is
// the eigenvector of the smaller eigenvalue of their scatter matrix; quality 1 - l_min / l_max.
void EstimateNormal(const Eigen::Vector2d* window, int count, Eigen::Vector2d& normal,
                    float& quality) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int k = 0; k < count; ++k) {
    mean += window[k];
  }
  mean /= count;
  double sxx = 0.0;
  double sxy = 0.0;
  double syy = 0.0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d d = window[k] - mean;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
  }
  const double half_trace = 0.5 * (sxx + syy);
  const double root = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
  const double l_max = half_trace + root;
  const double l_min = half_trace - root;
  if (l_max <= 0.0) {
    normal.setZero();
    quality = 0.0F;
    return;
  }
  // Direction of the line = eigenvector of l_max; the normal is perpendicular to it.
  Eigen::Vector2d dir = std::abs(sxy) > 1e-12
                            ? Eigen::Vector2d(l_max - syy, sxy)
                            : (sxx >= syy ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(0.0, 1.0));
  dir.normalize();
  normal = Eigen::Vector2d(-dir.y(), dir.x());
  quality = static_cast<float>(1.0 - l_min / l_max);
  if (count < 3) {
    quality *= 0.5F;  // two points always fit a line: weak evidence
  }
}

// A return with no neighbour near it may still lie on a wall seen at grazing incidence, whose
// consecutive returns are far apart but on one line: then the line through the two neighbouring
// returns gives its normal. The middle return must lie between them, within
// max(kGrazingTolerance, kGrazingRelativeTolerance * gap) of their line, and neither gap may be
// more than kGrazingGapRatio times the other (the spacing along a plane grows smoothly). An
// isolated object in front of a background (a pole, a leg) fails the test and keeps no normal.
constexpr double kGrazingTolerance = 0.03;          // [m]
constexpr double kGrazingRelativeTolerance = 0.02;  // [-]
constexpr double kGrazingGapRatio = 3.0;            // [-]

void GrazingWallNormal(const Eigen::Vector2d& before, const Eigen::Vector2d& point,
                       const Eigen::Vector2d& after, Eigen::Vector2d& normal, float& quality) {
  const Eigen::Vector2d chord = after - before;
  const double length = chord.norm();
  const double gap_before = (point - before).norm();
  const double gap_after = (after - point).norm();
  if (length <= 1e-9 || gap_before > kGrazingGapRatio * gap_after ||
      gap_after > kGrazingGapRatio * gap_before) {
    return;
  }
  const Eigen::Vector2d direction = chord / length;
  const double along = (point - before).dot(direction);
  const double deviation =
      std::abs(direction.x() * (point - before).y() - direction.y() * (point - before).x());
  const double tolerance =
      std::max(kGrazingTolerance, kGrazingRelativeTolerance * std::max(gap_before, gap_after));
  if (along <= 0.0 || along >= length || deviation > tolerance) {
    return;
  }
  normal = Eigen::Vector2d(-direction.y(), direction.x());
  // Three returns define the line: as strong as a two-point fit at best (EstimateNormal).
  quality = static_cast<float>(0.5 + 0.5 * (1.0 - deviation / tolerance));
}

}  // namespace

ScanPoints ExtractScanPoints(const LaserScan& scan, const Pose2& T_base_laser, double max_range,
                             double neighbour_distance, bool grazing_normals) {
  ScanPoints out;
  out.origin = T_base_laser.translation();
  const std::size_t n = scan.size();
  std::vector<Eigen::Vector2d> laser_points(n);
  std::vector<char> hit(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const double r = scan.ranges[k];
    const double a = scan.Angle(k);
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    if (scan.IsHit(k)) {
      if (r <= max_range) {
        hit[k] = 1;
        laser_points[k] = r * dir;
      }
    } else if (std::isfinite(r) && r >= scan.range_max && r > scan.range_min) {
      out.no_return_directions.push_back(T_base_laser.Rotation() * dir);
    }
  }
  const Eigen::Matrix2d R = T_base_laser.Rotation();
  const PointTransform to_base(T_base_laser);
  const double max_d2 = neighbour_distance * neighbour_distance;
  out.points.reserve(n);
  out.normals.reserve(n);
  out.normal_quality.reserve(n);
  Eigen::Vector2d window[5];
  for (std::size_t k = 0; k < n; ++k) {
    if (hit[k] == 0) {
      continue;
    }
    // Neighbours within neighbour_distance, or within six beam spacings at this range (walls
    // seen at up to ~80 degrees of incidence), whichever is larger.
    const double spacing = 6.0 * scan.ranges[k] * std::abs(scan.angle_increment);
    const double limit2 = std::max(max_d2, spacing * spacing);
    int count = 0;
    for (int offset = -2; offset <= 2; ++offset) {
      const auto m = static_cast<std::ptrdiff_t>(k) + offset;
      if (m < 0 || m >= static_cast<std::ptrdiff_t>(n)) {
        continue;
      }
      const auto um = static_cast<std::size_t>(m);
      if (hit[um] != 0 && (laser_points[um] - laser_points[k]).squaredNorm() <= limit2) {
        window[count++] = laser_points[um];
      }
    }
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();
    float quality = 0.0F;
    if (count >= 2) {
      EstimateNormal(window, count, normal, quality);
    } else if (grazing_normals && k > 0 && k + 1 < n && hit[k - 1] != 0 && hit[k + 1] != 0) {
      GrazingWallNormal(laser_points[k - 1], laser_points[k], laser_points[k + 1], normal, quality);
    }
    out.points.push_back(to_base(laser_points[k]));
    out.normals.push_back(R * normal);
    out.normal_quality.push_back(quality);
  }
  return out;
}

ScanReturns ExtractScanReturns(const LaserScan& scan, const Pose2& T_base_laser, double max_range) {
  ScanReturns out;
  out.origin = T_base_laser.translation();
  const PointTransform to_base(T_base_laser);
  const std::size_t n = scan.size();
  out.points.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (scan.IsHit(k) && scan.ranges[k] <= max_range) {
      const double r = scan.ranges[k];
      const double a = scan.Angle(k);
      const Eigen::Vector2d dir(std::cos(a), std::sin(a));
      out.points.push_back(to_base(r * dir));
    }
  }
  return out;
}

}  // namespace gridslam
