#include "gridslam/grid/scan_points.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gridslam {
namespace {

// The scatter of a window of points about their line: the sums of squares across it (l_min, the
// residual) and along it (l_max, the spread).
struct LineScatter {
  double across = 0.0;
  double along = 0.0;
};

// Normal and quality of the points in `window` (laser frame) around `centre` by PCA: the normal is
// the eigenvector of the smaller eigenvalue of their scatter matrix; quality 1 - l_min / l_max.
LineScatter EstimateNormal(const Eigen::Vector2d* window, int count, Eigen::Vector2d& normal,
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
    return {};
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
  return {std::max(l_min, 0.0), l_max};
}

// Half-widths [beams] a normal's window may grow to, doubling from the base window's 2.
constexpr int kBaseHalfWindow = 2;
constexpr int kMaxHalfWindow = 8;
// Median of chi-squared(3) / 3: a base window's residual variance (5 points, 2 fitted line
// parameters, 3 degrees of freedom) over its median is unbiased for the noise variance.
constexpr double kChiSquared3MedianOverDof = 0.789;
// Fewer full base windows than this in a scan: no noise estimate to grow windows by.
constexpr std::size_t kMinNoiseSamples = 10;

// Whether every point of a window lies within sqrt(max_d2) of its centre (the middle point).
bool Compact(const Eigen::Vector2d* window, int count, double max_d2) {
  const Eigen::Vector2d& centre = window[count / 2];
  for (int i = 0; i < count; ++i) {
    if ((window[i] - centre).squaredNorm() > max_d2) {
      return false;
    }
  }
  return true;
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

// The unit directions of a scan's beams in the laser frame. A laser's scans share their beam
// geometry, so the last geometry's directions are kept per thread: the same angles give the same
// cosines and sines, without a sincos per beam and scan.
const std::vector<Eigen::Vector2d>& BeamDirections(const LaserScan& scan) {
  struct Cache {
    double angle_min = 0.0;
    double angle_increment = 0.0;
    std::vector<Eigen::Vector2d> directions;
  };
  thread_local Cache cache;
  const std::size_t n = scan.size();
  if (cache.angle_min != scan.angle_min || cache.angle_increment != scan.angle_increment ||
      cache.directions.size() != n) {
    cache.angle_min = scan.angle_min;
    cache.angle_increment = scan.angle_increment;
    cache.directions.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double a = scan.Angle(k);
      cache.directions[k] = Eigen::Vector2d(std::cos(a), std::sin(a));
    }
  }
  return cache.directions;
}

}  // namespace

ScanPoints ExtractScanPoints(const LaserScan& scan, const Pose2& T_base_laser, double max_range,
                             double neighbour_distance, bool grazing_normals) {
  NormalEstimation normals;
  normals.neighbour_distance = neighbour_distance;
  normals.grazing_normals = grazing_normals;
  return ExtractScanPoints(scan, T_base_laser, max_range, normals);
}

ScanPoints ExtractScanPoints(const LaserScan& scan, const Pose2& T_base_laser, double max_range,
                             const NormalEstimation& options) {
  ScanPoints out;
  out.origin = T_base_laser.translation();
  const std::size_t n = scan.size();
  std::vector<Eigen::Vector2d> laser_points(n);
  std::vector<char> hit(n, 0);
  const std::vector<Eigen::Vector2d>& directions = BeamDirections(scan);
  for (std::size_t k = 0; k < n; ++k) {
    const double r = scan.ranges[k];
    const Eigen::Vector2d& dir = directions[k];
    if (scan.IsHit(k)) {
      if (r <= max_range) {
        hit[k] = 1;
        laser_points[k] = r * dir;
      }
    } else if (scan.IsNoReturn(k)) {
      out.no_return_directions.push_back(T_base_laser.Rotation() * dir);
    }
  }
  const double max_d2 = options.neighbour_distance * options.neighbour_distance;
  Eigen::Vector2d window[2 * kMaxHalfWindow + 1];
  // The hits within `half` beams of beam k that lie within neighbour_distance of it; the two
  // nearest on either side may also lie within six beam spacings at its range, if that is more
  // (walls seen at up to ~80 degrees of incidence).
  const auto gather = [&](std::size_t k, int half) {
    const double spacing = 6.0 * scan.ranges[k] * std::abs(scan.angle_increment);
    const double near2 = std::max(max_d2, spacing * spacing);
    int count = 0;
    for (int offset = -half; offset <= half; ++offset) {
      const auto m = static_cast<std::ptrdiff_t>(k) + offset;
      if (m < 0 || m >= static_cast<std::ptrdiff_t>(n)) {
        continue;
      }
      const auto um = static_cast<std::size_t>(m);
      const double limit2 = std::abs(offset) <= kBaseHalfWindow ? near2 : max_d2;
      if (hit[um] != 0 && (laser_points[um] - laser_points[k]).squaredNorm() <= limit2) {
        window[count++] = laser_points[um];
      }
    }
    return count;
  };

  std::vector<Eigen::Vector2d> normals(n, Eigen::Vector2d::Zero());
  std::vector<float> quality(n, 0.0F);
  std::vector<double> spread(n, 0.0);  // the base window's sum of squares along its line
  std::vector<double> residuals;       // full base windows' residual variances
  std::vector<Eigen::Vector2d> wall_normals;
  std::vector<float> wall_quality;
  for (std::size_t k = 0; k < n; ++k) {
    if (hit[k] == 0) {
      continue;
    }
    const int count = gather(k, kBaseHalfWindow);
    if (count >= 2) {
      const LineScatter scatter = EstimateNormal(window, count, normals[k], quality[k]);
      spread[k] = scatter.along;
      // The noise is measured on compact windows only: five returns within neighbour_distance
      // of the centre. A window stretched to six beam spacings at a far range spans metres of
      // wall and door frames, whose shape its residual reads as noise (a quiet laser at 1° in
      // wide halls measured 44 mm that way, 8 mm on its compact windows).
      if (count == 2 * kBaseHalfWindow + 1 && Compact(window, count, max_d2)) {
        residuals.push_back(scatter.across / (count - 2));
      }
    } else if (options.grazing_normals && k > 0 && k + 1 < n && hit[k - 1] != 0 &&
               hit[k + 1] != 0) {
      GrazingWallNormal(laser_points[k - 1], laser_points[k], laser_points[k + 1], normals[k],
                        quality[k]);
    }
  }

  // The noise, from the median residual of the base windows (robust to corners and edges). A
  // line fitted to points spread by S along it has a direction error of sigma / sqrt(S) [rad];
  // where the base window's spread is too small for max_angle_sigma, the wall normal's window
  // grows to the nearest neighbours that give enough spread (at most kMaxHalfWindow beams either
  // side, within neighbour_distance).
  if (!residuals.empty()) {
    const auto middle = residuals.begin() + static_cast<std::ptrdiff_t>(residuals.size() / 2);
    std::nth_element(residuals.begin(), middle, residuals.end());
    const double noise_variance = *middle / kChiSquared3MedianOverDof;
    out.surface_noise = std::sqrt(noise_variance);
    if (options.max_angle_sigma > 0.0 && residuals.size() >= kMinNoiseSamples) {
      const double needed = noise_variance / (options.max_angle_sigma * options.max_angle_sigma);
      wall_normals = normals;
      wall_quality = quality;
      for (std::size_t k = 0; k < n; ++k) {
        if (spread[k] <= 0.0 || spread[k] >= needed) {
          continue;
        }
        for (int half = 2 * kBaseHalfWindow; half <= kMaxHalfWindow; half *= 2) {
          const int count = gather(k, half);
          if (count < 3) {
            break;
          }
          if (EstimateNormal(window, count, wall_normals[k], wall_quality[k]).along >= needed) {
            break;
          }
        }
      }
    }
  }

  const Eigen::Matrix2d R = T_base_laser.Rotation();
  const PointTransform to_base(T_base_laser);
  out.points.reserve(n);
  out.normals.reserve(n);
  out.normal_quality.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (hit[k] != 0) {
      out.points.push_back(to_base(laser_points[k]));
      out.normals.push_back(R * normals[k]);
      out.normal_quality.push_back(quality[k]);
      if (!wall_normals.empty()) {
        out.wall_normals.push_back(R * wall_normals[k]);
        out.wall_normal_quality.push_back(wall_quality[k]);
      }
    }
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
