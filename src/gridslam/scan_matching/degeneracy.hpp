// Explicit degeneracy of a scan match (Zhang, Kaess, Singh 2016, "On degeneracy of
// optimization-based state estimation problems"; the localizability of Tuna et al. 2023).
//
// A scan constrains a translation direction v only through the points whose residual gradient
// has a component along v. Measured in points (the scan's Hessian times point_sigma^2, which with
// Cauchy weights counts each inlier on a wall facing v as one), the weakest direction of a long
// corridor collects a few points' worth of information from door frames and the noise of wall
// normals: far fewer than the minimum a match needs, yet, summed over hundreds of points, enough
// to outweigh the odometry prior and to let the estimate slide along the corridor. Such a
// direction is declared degenerate and the scan's information along it is removed (solution
// remapping): the prior alone carries the estimate there, and the covariance says so.
#pragma once

#include <Eigen/Core>

namespace gridslam::scan_matching {

struct DegeneracyResult {
  int degenerate_directions = 0;  ///< Translation directions the scan does not constrain (0..2).
  /// Effective number of points constraining the weakest / strongest translation direction once
  /// the yaw is marginalized (eigenvalues of the Schur complement times point_sigma^2) [-].
  double weakest_points = 0.0;
  double strongest_points = 0.0;
  Eigen::Vector2d weakest_direction = Eigen::Vector2d::UnitX();  ///< Unit vector, odometry frame.
};

/// Finds the translation directions of the scan-only normal equations (H, g on x, y, theta, in
/// units of 1/point_variance) constrained by fewer than `min_points` effective points, and
/// removes the scan's information along them from H and g (H <- Q H Q, g <- Q g with Q the
/// projector onto their complement). `point_variance` is point_sigma^2 [m^2]; min_points <= 0
/// disables the test. The yaw is never declared degenerate.
DegeneracyResult RemoveDegenerateDirections(double point_variance, double min_points,
                                            Eigen::Matrix3d* H, Eigen::Vector3d* g);
/// The same, with the directions measured on `information` (the scan's information as its wall
/// normals give it, which noisy five-beam normals overstate along a wall) and removed from H, g.
DegeneracyResult RemoveDegenerateDirections(double point_variance, double min_points,
                                            const Eigen::Matrix3d& information, Eigen::Matrix3d* H,
                                            Eigen::Vector3d* g);

}  // namespace gridslam::scan_matching
