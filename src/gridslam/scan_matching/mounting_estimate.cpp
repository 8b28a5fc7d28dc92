#include "gridslam/scan_matching/mounting_estimate.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::scan_matching {
namespace {

/// Tukey's biweight constant for 95 % efficiency at the normal distribution.
constexpr double kTukey = 4.685;
/// Median of the norm of a 2-D vector of independent N(0, sigma^2) components, over sigma
/// (the Rayleigh distribution's median, sqrt(2 ln 2)).
constexpr double kRayleighMedian = 1.1774100225154747;
constexpr int kReweightings = 6;
/// Summed 2 (1 - cos theta) below which the turns measure nothing (one turn of 0.1 mrad) [-].
constexpr double kMinInformation = 1e-8;

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
  // (R - I)^T (R - I) = 2 (1 - cos theta) I: every increment informs both directions alike, so
  // the normal equations are a scalar times the identity.
  std::vector<Eigen::Matrix2d> coefficients;
  coefficients.reserve(samples_.size());
  for (const Sample& sample : samples_) {
    coefficients.push_back(Coefficient(sample.theta));
  }
  std::vector<double> weights(samples_.size(), 1.0);
  std::vector<double> residuals(samples_.size(), 0.0);
  double information = 0.0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  double scale = 0.0;
  for (int pass = 0; pass <= kReweightings; ++pass) {
    information = 0.0;
    Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      information += weights[k] * 2.0 * (1.0 - std::cos(samples_[k].theta));
      rhs.noalias() += weights[k] * coefficients[k].transpose() * samples_[k].difference;
    }
    // Nothing turned (the offset is then not observable), or the reweighting dropped every
    // increment that did.
    if (!(information > kMinInformation)) {
      return result;
    }
    offset = rhs / information;
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      residuals[k] = (samples_[k].difference - coefficients[k] * offset).norm();
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
  result.offset = offset;
  result.sigma = scale / std::sqrt(information);
  result.ok = std::isfinite(result.sigma) && offset.allFinite();
  return result;
}

}  // namespace gridslam::scan_matching
