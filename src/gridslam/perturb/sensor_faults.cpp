#include "gridslam/perturb/sensor_faults.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::perturb {
namespace {

constexpr double kAngleSlack = 1e-9;     // beams exactly at +-fov/2 are kept [rad]
constexpr double kMinNoisyRange = 0.01;  // noise never turns a return into a no-return [m]

/// The beams within +-fov/2 of the laser axis. When they wrap around the end of the scan (a
/// 360 deg scanner starting at 0), the part after the wrap comes first, so that the beams stay
/// in increasing angle.
LaserScan Crop(const LaserScan& scan, double fov) {
  const std::size_t n = scan.size();
  std::vector<bool> keep(n);
  for (std::size_t k = 0; k < n; ++k) {
    keep[k] = std::abs(NormalizeAngle(scan.Angle(k))) <= fov / 2.0 + kAngleSlack;
  }
  // First kept beam after a dropped one (the start of the kept arc), if any beam is dropped.
  std::size_t first = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (keep[k] && !keep[(k + n - 1) % n]) {
      first = k;
      break;
    }
  }
  LaserScan out = scan;
  out.ranges.clear();
  out.angle_min = scan.Angle(first);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t k = (first + j) % n;
    if (!keep[k]) {
      break;
    }
    out.ranges.push_back(scan.ranges[k]);
  }
  return out;
}

}  // namespace

bool PerturbsSensor(const PerturbOptions& options) {
  return options.fov_deg > 0.0 || options.beam_step > 1 || options.max_range > 0.0 ||
         options.range_noise > 0.0 || options.beam_dropout > 0.0;
}

LaserScan PerturbScan(const LaserScan& scan, const PerturbOptions& options,
                      simulation::Random& noise, simulation::Random& dropout) {
  LaserScan out =
      options.fov_deg > 0.0 && !scan.ranges.empty() ? Crop(scan, DegToRad(options.fov_deg)) : scan;
  if (options.beam_step > 1) {
    std::vector<float> kept;
    for (std::size_t k = 0; k < out.ranges.size();
         k += static_cast<std::size_t>(options.beam_step)) {
      kept.push_back(out.ranges[k]);
    }
    out.ranges = std::move(kept);
    out.angle_increment *= options.beam_step;
  }
  if (options.max_range > 0.0) {
    out.range_max = std::min(out.range_max, options.max_range);
    const auto limit = static_cast<float>(out.range_max);
    for (float& r : out.ranges) {
      if (!std::isfinite(r) || r >= limit) {
        r = limit;
      }
    }
  }
  for (std::size_t k = 0; k < out.ranges.size(); ++k) {
    if (!out.IsHit(k)) {
      continue;
    }
    float& r = out.ranges[k];
    if (options.range_noise > 0.0) {
      r = static_cast<float>(std::max(static_cast<double>(r) + noise.Gaussian(options.range_noise),
                                      std::max(out.range_min, 0.0) + kMinNoisyRange));
    }
    if (dropout.Bernoulli(options.beam_dropout)) {
      r = 0.0F;
    }
  }
  return out;
}

}  // namespace gridslam::perturb
