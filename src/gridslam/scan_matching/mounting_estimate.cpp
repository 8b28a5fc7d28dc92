#include "gridslam/scan_matching/mounting_estimate.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace gridslam::scan_matching {
namespace {

/// Tukey's biweight constant for 95 % efficiency at the normal distribution.
constexpr double kTukey = 4.685;
/// Median of the norm of a 2-D vector of independent N(0, sigma^2) components, over sigma
/// (the Rayleigh distribution's median, sqrt(2 ln 2)).
constexpr double kRayleighMedian = 1.1774100225154747;
constexpr int kReweightings = 6;

/// (R(theta) - I), the coefficient of the offset in one increment's translation difference.
Eigen::Matrix2d Coefficient(double theta) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  Eigen::Matrix2d a;
  a << c - 1.0, -s, s, c - 1.0;
  return a;
}

double Median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

void MountingEstimate::Add(const Pose2& odometry_increment, const Pose2& matched_increment) {
  samples_.push_back({odometry_increment.theta(),
                      matched_increment.translation() - odometry_increment.translation()});
}

MountingResult MountingEstimate::Estimate(int min_increments) const {
  MountingResult result;
  result.increments = size();
  if (result.increments < std::max(min_increments, 3)) {
    return result;
  }
  std::vector<double> weights(samples_.size(), 1.0);
  std::vector<double> residuals(samples_.size(), 0.0);
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  double scale = 0.0;
  for (int pass = 0; pass <= kReweightings; ++pass) {
    normal.setZero();
    Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      const Eigen::Matrix2d a = Coefficient(samples_[k].theta);
      normal.noalias() += weights[k] * a.transpose() * a;
      rhs.noalias() += weights[k] * a.transpose() * samples_[k].difference;
    }
    const Eigen::LDLT<Eigen::Matrix2d> ldlt(normal);
    // Singular when no increment turned (the offset is then not observable), or when the
    // reweighting dropped every turning one.
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
        ldlt.vectorD().minCoeff() <= 1e-12 * std::max(1.0, ldlt.vectorD().maxCoeff())) {
      return result;
    }
    offset = ldlt.solve(rhs);
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      residuals[k] = (samples_[k].difference - Coefficient(samples_[k].theta) * offset).norm();
    }
    scale = Median(residuals) / kRayleighMedian;  // per component
    if (pass == kReweightings || scale <= 0.0) {
      break;
    }
    const double c = kTukey * scale;
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      const double u = residuals[k] / c;
      weights[k] = u < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
    }
  }
  const Eigen::Matrix2d covariance = scale * scale * normal.inverse();
  if (!covariance.allFinite()) {
    return result;
  }
  result.offset = offset;
  result.sigma = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  result.ok = true;
  return result;
}

}  // namespace gridslam::scan_matching
