// SE(2) rigid transform (Sophus/manif style, tangent order (x, y, theta)). `T_a_b` is the pose of
// frame b in frame a and maps points from b to a: p_a = T_a_b * p_b, T_a_c = T_a_b * T_b_c.
// theta is always normalized to [-pi, pi).
#pragma once

#include <Eigen/Core>

#include "gridslam/common/angles.hpp"

namespace gridslam {

class Pose2 {
 public:
  Pose2() = default;
  Pose2(double x, double y, double theta) : translation_(x, y), theta_(NormalizeAngle(theta)) {}
  Pose2(const Eigen::Vector2d& translation, double theta)
      : translation_(translation), theta_(NormalizeAngle(theta)) {}

  static Pose2 Identity() { return {}; }
  /// From a vector (x, y, theta).
  static Pose2 FromVector(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

  [[nodiscard]] double x() const { return translation_.x(); }
  [[nodiscard]] double y() const { return translation_.y(); }
  [[nodiscard]] double theta() const { return theta_; }
  [[nodiscard]] const Eigen::Vector2d& translation() const { return translation_; }
  /// 2x2 rotation matrix R(theta).
  [[nodiscard]] Eigen::Matrix2d Rotation() const;
  /// (x, y, theta) as a vector (not the Lie-algebra log; see Log()).
  [[nodiscard]] Eigen::Vector3d ToVector() const { return {x(), y(), theta_}; }
  /// 3x3 homogeneous matrix.
  [[nodiscard]] Eigen::Matrix3d Matrix() const;

  [[nodiscard]] Pose2 Inverse() const;
  /// Composition: (T_a_b * T_b_c) = T_a_c.
  Pose2 operator*(const Pose2& other) const;
  /// Transforms a point: p_a = T_a_b * p_b.
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const;

  /// Exponential map of the tangent vector (v_x, v_y, omega), with a Taylor branch near 0.
  static Pose2 Exp(const Eigen::Vector3d& tangent);
  /// Logarithm: the tangent vector (v_x, v_y, omega) with Exp(Log(T)) == T.
  [[nodiscard]] Eigen::Vector3d Log() const;

 private:
  Eigen::Vector2d translation_ = Eigen::Vector2d::Zero();
  double theta_ = 0.0;
};

/// A pose applied to many points with its rotation computed once: the same numbers as `T * p`,
/// without a cosine and a sine per point.
class PointTransform {
 public:
  explicit PointTransform(const Pose2& T) : rotation_(T.Rotation()), translation_(T.translation()) {}
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const { return translation_ + rotation_ * p; }

 private:
  Eigen::Matrix2d rotation_;
  Eigen::Vector2d translation_;
};

/// T_a_b = T_w_a^-1 * T_w_b: the pose of b in a's frame.
inline Pose2 Between(const Pose2& T_w_a, const Pose2& T_w_b) { return T_w_a.Inverse() * T_w_b; }

/// Linear interpolation in x, y and along the shortest arc in theta; alpha in [0, 1].
Pose2 Interpolate(const Pose2& a, const Pose2& b, double alpha);

/// True when translations differ by at most `tol_xy` and angles by at most `tol_theta`.
bool IsApprox(const Pose2& a, const Pose2& b, double tol_xy = 1e-9, double tol_theta = 1e-9);

}  // namespace gridslam
