#include "gridslam/scan_matching/scan_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "gridslam/common/check.hpp"
#include "gridslam/grid/log_odds.hpp"
#include "gridslam/scan_matching/correlative_search.hpp"
#include "gridslam/scan_matching/degeneracy.hpp"

namespace gridslam::scan_matching {
namespace {

// Normal equations of one Gauss-Newton step.
struct LinearSystem {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  /// H as the scan's wall normals (ScanPoints::wall_normals) project the gradients: what the
  /// walls constrain, free of the leak of noisy five-beam normals (the degeneracy test's input).
  Eigen::Matrix3d wall_information = Eigen::Matrix3d::Zero();
  int correspondences = 0;

  void Add(const Eigen::Vector3d& J, double r, double weight) {
    H.noalias() += weight * J * J.transpose();
    g.noalias() += weight * r * J;
  }
};

// Converts a yaw step to metres when comparing steps (a point 2 m away moves 2 m per radian).
constexpr double kLeverArm = 2.0;

// Cauchy weight of residual r for scale c (IRLS).
inline double CauchyWeight(double r, double c) {
  const double u = r / c;
  return 1.0 / (1.0 + u * u);
}

}  // namespace

Status ScanMatcherOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(residual == "point_to_line" || residual == "distance_field",
                                   "matcher.residual is point_to_line or distance_field"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(max_correspondence_distance > 0.0, "matcher.max_correspondence_distance > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(!robust_scales.empty(), "matcher.robust_scales not empty"));
  for (const double c : robust_scales) {
    GRIDSLAM_RETURN_IF_ERROR(Require(c > 0.0, "matcher.robust_scales > 0"));
  }
  GRIDSLAM_RETURN_IF_ERROR(Require(max_iterations >= 1, "matcher.max_iterations >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(point_sigma > 0.0, "matcher.point_sigma > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(min_points >= 3, "matcher.min_points >= 3"));
  GRIDSLAM_RETURN_IF_ERROR(Require(min_correspondences >= 3, "matcher.min_correspondences >= 3"));
  GRIDSLAM_RETURN_IF_ERROR(Require(degenerate_fraction >= 0.0 && degenerate_fraction < 0.5,
                                   "0 <= matcher.degenerate_fraction < 0.5"));
  GRIDSLAM_RETURN_IF_ERROR(Require(inlier_distance > 0.0, "matcher.inlier_distance > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(search_linear_window >= 0.0 && search_angular_window >= 0.0,
                                   "matcher search windows >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(search_angular_step > 0.0 && search_linear_step >= 1, "matcher search steps > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(search_sigma > 0.0, "matcher.search_sigma > 0"));
  return Status::Ok();
}

ScanMatcher::ScanMatcher(const ScanMatcherOptions& options)
    : options_(options), point_to_line_(options.residual == "point_to_line") {
  GRIDSLAM_CHECK(options.Validate().ok()) << options.Validate().error().ToString();
}

MatchResult ScanMatcher::Refine(const RollingWindow& map, const MatchingField& field,
                                const ScanPoints& scan, const Pose2& start, const Pose2& prior,
                                const Eigen::Matrix3d& prior_information,
                                PriorKind prior_kind) const {
  const MapLimits& limits = field.Limits();
  const double res = limits.Resolution();
  const double ox = limits.Origin().x();
  const double oy = limits.Origin().y();
  const int w = limits.Width();
  const int h = limits.Height();
  const double max_corr2 =
      options_.max_correspondence_distance * options_.max_correspondence_distance;
  const double inv_var = 1.0 / (options_.point_sigma * options_.point_sigma);
  const auto min_planarity = static_cast<float>(options_.min_planarity);
  GRIDSLAM_CHECK(!point_to_line_ || map.TracksSurfaces())
      << "the point_to_line residual needs a map that tracks surfaces";
  // The field's storage indices (and labels) address the window's layers.
  GRIDSLAM_CHECK(field.Layout() == map.Layout()) << "the field does not follow this window";
  const RingLayout& layout = field.Layout();
  const CellSurface* surfaces = map.Surfaces();

  const Eigen::LDLT<Eigen::Matrix3d> prior_ldlt(prior_information);
  const bool prior_positive = prior_ldlt.info() == Eigen::Success && prior_ldlt.isPositive() &&
                              prior_ldlt.vectorD().minCoeff() > 0.0;
  const bool wall_normals = !point_to_line_ && scan.wall_normals.size() == scan.points.size() &&
                            !scan.wall_normals.empty();
  // Outside the grid the field interpolates MaxDistance(): when that is no nearer than a
  // correspondence may be, the distance alone rejects such points and the cell test is redundant.
  const bool test_cells =
      point_to_line_ || field.MaxDistance() < options_.max_correspondence_distance;
  Eigen::Vector3d x = start.ToVector();
  MatchResult result;
  LinearSystem system;
  for (std::size_t stage = 0; stage < options_.robust_scales.size(); ++stage) {
    const double scale = options_.robust_scales[stage];
    result.converged = false;
    double damping = 1.0;
    Eigen::Vector3d previous_step = Eigen::Vector3d::Zero();
    for (int iteration = 0; iteration < options_.max_iterations; ++iteration) {
      system = LinearSystem{};
      const double c = std::cos(x.z());
      const double s = std::sin(x.z());
      for (std::size_t k = 0; k < scan.points.size(); ++k) {
        const Eigen::Vector2d& q = scan.points[k];
        const double dx = c * q.x() - s * q.y();  // rotated point = d(w)/d(theta) rotated by -90
        const double dy = s * q.x() + c * q.y();
        const double wx = dx + x.x();
        const double wy = dy + x.y();
        std::size_t index = 0;
        if (test_cells) {
          const auto ci = static_cast<int>(std::floor((wx - ox) / res));
          const auto cj = static_cast<int>(std::floor((wy - oy) / res));
          if (ci < 0 || cj < 0 || ci >= w || cj >= h) {
            continue;
          }
          index = layout.Index(ci, cj);
        }
        if (point_to_line_) {
          const std::int32_t nearest = field.Nearest(index);
          if (nearest < 0) {
            continue;
          }
          const Eigen::Vector2d m = map.MeanPoint(nearest);
          const double ex = wx - m.x();
          const double ey = wy - m.y();
          const double e2 = ex * ex + ey * ey;
          if (e2 > max_corr2) {
            continue;
          }
          ++system.correspondences;
          const CellSurface& surface = surfaces[nearest];
          const float planarity = surface.Planarity();
          if (planarity >= min_planarity) {
            const double nx = surface.normal_x / planarity;
            const double ny = surface.normal_y / planarity;
            const double r = nx * ex + ny * ey;
            const Eigen::Vector3d J(nx, ny, -nx * dy + ny * dx);
            system.Add(J, r, inv_var * CauchyWeight(r, scale));
          } else {
            const double weight = inv_var * CauchyWeight(std::sqrt(e2), scale);
            system.Add(Eigen::Vector3d(1.0, 0.0, -dy), ex, weight);
            system.Add(Eigen::Vector3d(0.0, 1.0, dx), ey, weight);
          }
        } else {
          Eigen::Vector2d gradient;
          const double d = field.Interpolate(Eigen::Vector2d(wx, wy), &gradient);
          if (d >= options_.max_correspondence_distance) {
            continue;
          }
          ++system.correspondences;
          // On a surface, only the gradient's component along the scan's own normal is
          // information; the tangential part comes from the gaps that sparse or grazing returns
          // leave in the map's walls and would pin the pose to them.
          const auto on_surface = [&](const Eigen::Vector2d& normal) {
            const double nx = c * normal.x() - s * normal.y();
            const double ny = s * normal.x() + c * normal.y();
            const double along = gradient.x() * nx + gradient.y() * ny;
            return Eigen::Vector2d(along * nx, along * ny);
          };
          const Eigen::Vector2d used =
              scan.normal_quality[k] >= min_planarity ? on_surface(scan.normals[k]) : gradient;
          const double weight = inv_var * CauchyWeight(d, scale);
          const Eigen::Vector3d J(used.x(), used.y(), -used.x() * dy + used.y() * dx);
          system.Add(J, d, weight);
          if (wall_normals) {
            const Eigen::Vector2d wall = scan.wall_normal_quality[k] >= min_planarity
                                             ? on_surface(scan.wall_normals[k])
                                             : gradient;
            const Eigen::Vector3d Jw(wall.x(), wall.y(), -wall.x() * dy + wall.y() * dx);
            system.wall_information.noalias() += weight * Jw * Jw.transpose();
          }
        }
      }
      // Directions the scan hardly constrains (along a corridor) are the prior's alone when the
      // prior measures the motion; without a prior (zero information), or with a motion model
      // for one, nothing better than the scan's few points carries them.
      if (prior_positive && prior_kind == PriorKind::kMeasured) {
        const Eigen::Matrix3d information = wall_normals ? system.wall_information : system.H;
        result.degeneracy =
            RemoveDegenerateDirections(options_.point_sigma * options_.point_sigma,
                                       options_.degenerate_fraction * system.correspondences,
                                       information, &system.H, &system.g);
      }
      const Eigen::Vector3d prior_error(x.x() - prior.x(), x.y() - prior.y(),
                                        NormalizeAngle(x.z() - prior.theta()));
      system.H += prior_information;
      system.g += prior_information * prior_error;
      ++result.iterations;
      if (system.correspondences < options_.min_correspondences) {
        result.T_odom_base = start;
        result.correspondences = system.correspondences;
        return result;  // not ok
      }
      const Eigen::LDLT<Eigen::Matrix3d> ldlt(system.H);
      if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) {
        break;
      }
      Eigen::Vector3d delta = -ldlt.solve(system.g);
      if (!delta.allFinite()) {
        break;
      }
      // Keep steps inside the region where the linearization means something.
      const double step_xy = delta.head<2>().norm();
      if (step_xy > 0.25) {
        delta.head<2>() *= 0.25 / step_xy;
      }
      delta.z() = std::clamp(delta.z(), -0.2, 0.2);
      // The distance field is only piecewise smooth: when a step turns back on the previous one,
      // the iterate oscillates around a kink, so the steps are damped from then on.
      const Eigen::Vector3d scaled(delta.x(), delta.y(), delta.z() * kLeverArm);
      if (scaled.dot(previous_step) < -0.5 * scaled.norm() * previous_step.norm()) {
        damping *= 0.5;
      }
      previous_step = scaled;
      delta *= damping;
      x += delta;
      x.z() = NormalizeAngle(x.z());
      if (delta.head<2>().norm() < options_.convergence_translation &&
          std::abs(delta.z()) < options_.convergence_rotation) {
        result.converged = true;
        break;
      }
    }
  }
  result.T_odom_base = Pose2::FromVector(x);
  result.correspondences = system.correspondences;
  const Eigen::Matrix3d covariance = system.H.inverse();
  result.covariance = Eigen::Matrix3d::Identity();
  if (covariance.allFinite()) {
    result.covariance = 0.5 * (covariance + covariance.transpose());
  }
  result.score = Score(map, field, scan, result.T_odom_base, &result.correspondences);
  result.ok = result.correspondences >= options_.min_correspondences;
  return result;
}

double ScanMatcher::Score(const RollingWindow& map, const MatchingField& field,
                          const ScanPoints& scan, const Pose2& pose, int* correspondences) const {
  const MapLimits& limits = field.Limits();
  const Eigen::Matrix2d R = pose.Rotation();
  const double inlier2 = options_.inlier_distance * options_.inlier_distance;
  const double max_corr2 =
      options_.max_correspondence_distance * options_.max_correspondence_distance;
  GRIDSLAM_CHECK(field.Layout() == map.Layout()) << "the field does not follow this window";
  const RingLayout& layout = field.Layout();
  const float* log_odds = map.LogOdds().data();
  int observed = 0;
  int inliers = 0;
  int matched = 0;
  for (const Eigen::Vector2d& q : scan.points) {
    const Eigen::Vector2d p = R * q + pose.translation();
    const Eigen::Array2i cell = limits.CellIndex(p);
    if (!limits.Contains(cell)) {
      continue;
    }
    const std::size_t index = layout.Index(cell);
    const std::int32_t nearest = field.Nearest(index);
    double e2 = std::numeric_limits<double>::infinity();
    if (nearest >= 0) {
      if (point_to_line_) {
        const Eigen::Vector2d e = p - map.MeanPoint(nearest);
        const CellSurface& surface = map.Surface(static_cast<std::size_t>(nearest));
        const float planarity = surface.Planarity();
        if (planarity >= static_cast<float>(options_.min_planarity)) {
          const double along_normal =
              (surface.normal_x * e.x() + surface.normal_y * e.y()) / planarity;
          e2 = along_normal * along_normal;
        } else {
          e2 = e.squaredNorm();
        }
        matched += e.squaredNorm() <= max_corr2 ? 1 : 0;
      } else {
        const double d = field.Interpolate(p, nullptr);
        e2 = d * d;
        matched += d < options_.max_correspondence_distance ? 1 : 0;
      }
    }
    if (nearest >= 0 || log_odds[index] != kUnknownLogOdds) {
      ++observed;
      inliers += e2 <= inlier2 ? 1 : 0;
    }
  }
  if (correspondences != nullptr) {
    *correspondences = matched;
  }
  return observed > 0 ? static_cast<double>(inliers) / observed : 0.0;
}

MatchResult ScanMatcher::Match(const RollingWindow& map, const MatchingField& field,
                               const ScanPoints& scan, const Pose2& T_odom_base_prior,
                               const Eigen::Matrix3d& prior_information,
                               PriorKind prior_kind) const {
  MatchResult best =
      Refine(map, field, scan, T_odom_base_prior, T_odom_base_prior, prior_information, prior_kind);
  if (!options_.correlative_search || (best.ok && best.score >= options_.good_score)) {
    return best;
  }
  const SearchResult search = CorrelativeSearch(field, scan, T_odom_base_prior, options_);
  MatchResult other = Refine(map, field, scan, search.T_odom_base, T_odom_base_prior,
                             prior_information, prior_kind);
  other.iterations += best.iterations;
  other.searched = true;
  best.searched = true;
  if (other.ok && (!best.ok || other.score > best.score + 0.05)) {
    return other;
  }
  best.iterations = other.iterations;
  return best;
}

}  // namespace gridslam::scan_matching
