#include "gridslam/geometry/pose2.hpp"

#include <cmath>

#include <Eigen/LU>

namespace gridslam {

Eigen::Matrix2d Pose2::Rotation() const {
  const double c = std::cos(theta_);
  const double s = std::sin(theta_);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

Eigen::Matrix3d Pose2::Matrix() const {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  m.topLeftCorner<2, 2>() = Rotation();
  m.topRightCorner<2, 1>() = translation_;
  return m;
}

Pose2 Pose2::Inverse() const {
  const Eigen::Matrix2d rt = Rotation().transpose();
  return {-(rt * translation_), -theta_};
}

Pose2 Pose2::operator*(const Pose2& other) const {
  return {translation_ + Rotation() * other.translation_, theta_ + other.theta_};
}

Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& p) const {
  return translation_ + Rotation() * p;
}

namespace {

// V(omega) = [[a, -b], [b, a]] with a = sin(w)/w, b = (1 - cos(w))/w (Eq. (156) in Sola et al.,
// "A micro Lie theory"), Taylor-expanded for small omega.
Eigen::Matrix2d LeftJacobianV(double omega) {
  double a = 0.0;
  double b = 0.0;
  if (std::abs(omega) < 1e-6) {
    const double w2 = omega * omega;
    a = 1.0 - w2 / 6.0;
    b = omega / 2.0 - omega * w2 / 24.0;
  } else {
    a = std::sin(omega) / omega;
    b = (1.0 - std::cos(omega)) / omega;
  }
  Eigen::Matrix2d v;
  v << a, -b, b, a;
  return v;
}

}  // namespace

Pose2 Pose2::Exp(const Eigen::Vector3d& tangent) {
  const double omega = tangent.z();
  return {LeftJacobianV(omega) * tangent.head<2>(), omega};
}

Eigen::Vector3d Pose2::Log() const {
  const Eigen::Vector2d v = LeftJacobianV(theta_).inverse() * translation_;
  return {v.x(), v.y(), theta_};
}

Pose2 Interpolate(const Pose2& a, const Pose2& b, double alpha) {
  const Eigen::Vector2d t = a.translation() + alpha * (b.translation() - a.translation());
  const double dtheta = NormalizeAngle(b.theta() - a.theta());
  return {t, a.theta() + alpha * dtheta};
}

bool IsApprox(const Pose2& a, const Pose2& b, double tol_xy, double tol_theta) {
  return (a.translation() - b.translation()).norm() <= tol_xy &&
         std::abs(NormalizeAngle(a.theta() - b.theta())) <= tol_theta;
}

}  // namespace gridslam
