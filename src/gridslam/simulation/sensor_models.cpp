#include "gridslam/simulation/sensor_models.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::simulation {

LaserSimulator::LaserSimulator(const World& world, const LaserSimOptions& options)
    : caster_(world), options_(options) {}

LaserScan LaserSimulator::EmptyScan() const {
  LaserScan scan;
  scan.angle_min = options_.StartAngle();
  scan.angle_increment = options_.Increment();
  scan.range_min = 0.0;
  scan.range_max = options_.max_range;
  return scan;
}

LaserScan LaserSimulator::Scan(const Pose2& T_world_laser, Random& random) const {
  LaserScan scan = EmptyScan();
  const auto n = static_cast<std::size_t>(options_.num_beams);
  scan.ranges.resize(n);
  const double no_return = options_.NoReturnRange();
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = T_world_laser.theta() + scan.Angle(k);
    const RayHit hit = caster_.Cast(T_world_laser.translation(), angle, options_.max_range);
    // Draw the same numbers for every beam, so one beam's outcome does not shift the others'.
    const double noise = random.Gaussian(options_.range_noise);
    const double u_spurious = random.Uniform();
    const double u_missing = random.Uniform();
    const double u_range = random.Uniform();
    double range = no_return;
    if (u_spurious < options_.spurious_probability) {
      const double longest = hit.hit ? hit.range : options_.max_range;
      range = u_range * longest;
    } else if (hit.hit && u_missing >= options_.missing_probability) {
      range = std::max(hit.range + noise, 0.0);
      if (range >= options_.max_range) {
        range = no_return;
      }
    }
    scan.ranges[k] = static_cast<float>(range);
  }
  return scan;
}

Pose2 OdometrySimulator::Measure(const Pose2& T_prev_cur, Random& random) const {
  const double dx = T_prev_cur.x();
  const double dy = T_prev_cur.y();
  const double dtheta = T_prev_cur.theta();
  const double distance = std::hypot(dx, dy);
  const double turned = std::abs(dtheta);
  // Variances grow linearly with distance and angle: sigma = k * sqrt(amount).
  const double sigma_along = options_.translation_noise * std::sqrt(distance);
  const double sigma_side = options_.lateral_noise * std::sqrt(distance);
  const double sigma_theta =
      std::sqrt(options_.rotation_noise_per_meter * options_.rotation_noise_per_meter * distance +
                options_.rotation_noise_per_radian * options_.rotation_noise_per_radian * turned);
  const double e_along = random.Gaussian(sigma_along);
  const double e_side = random.Gaussian(sigma_side);
  const double e_theta = random.Gaussian(sigma_theta);
  // Along-track and sideways errors are taken along the direction of motion.
  const double ux = distance > 0.0 ? dx / distance : 1.0;
  const double uy = distance > 0.0 ? dy / distance : 0.0;
  const double scale = 1.0 + options_.translation_scale_bias;
  const double mx = dx * scale + e_along * ux - e_side * uy;
  const double my = dy * scale + e_along * uy + e_side * ux;
  const double mtheta =
      dtheta * (1.0 + options_.rotation_scale_bias) + options_.rotation_drift * distance + e_theta;
  return {mx, my, mtheta};
}

}  // namespace gridslam::simulation
