#include "gridslam/perturb/odometry_faults.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "gridslam/perturb/random_streams.hpp"
#include "gridslam/simulation/random.hpp"

namespace gridslam::perturb {
namespace {

/// Odometry at time `t` from the frames' own odometry (linear between the two scans around t,
/// clamped at the ends); `order` sorts the frames by corrected time.
Pose2 OdometryAt(const std::vector<Frame>& frames, const std::vector<std::size_t>& order, Time t) {
  auto it = std::lower_bound(order.begin(), order.end(), t, [&](std::size_t i, Time value) {
    return frames[i].corrected_time < value;
  });
  if (it == order.end()) {
    return frames[order.back()].T_odom_base;
  }
  if (it == order.begin() || frames[*it].corrected_time == t) {
    return frames[*it].T_odom_base;
  }
  const Frame& a = frames[*(it - 1)];
  const Frame& b = frames[*it];
  const double alpha =
      ToSeconds(t - a.corrected_time) / ToSeconds(b.corrected_time - a.corrected_time);
  return Interpolate(a.T_odom_base, b.T_odom_base, alpha);
}

/// Exponentially distributed waiting time with mean `mean` [s].
double ExponentialDraw(simulation::Random& random, double mean) {
  return -mean * std::log(1.0 - random.Uniform());
}

}  // namespace

std::vector<Pose2> PerturbOdometry(const std::vector<Frame>& frames, const PerturbOptions& options,
                                   std::vector<GlitchEvent>* glitches) {
  std::vector<Pose2> source(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    source[k] = frames[k].T_odom_base;
  }
  if (frames.empty() || !options.PerturbsOdometry()) {
    return source;
  }
  const auto seed = static_cast<std::uint64_t>(options.seed);
  if (options.time_jitter > 0.0) {
    std::vector<std::size_t> order(frames.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      order[k] = k;
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return frames[a].corrected_time < frames[b].corrected_time;
    });
    simulation::Random jitter(seed, kStreamTimeJitter);
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const Time t =
          frames[k].corrected_time + SecondsToDuration(jitter.Gaussian(options.time_jitter));
      source[k] = OdometryAt(frames, order, t);
    }
  }

  simulation::Random glitch_random(seed, kStreamGlitches);
  const Time start = frames.front().corrected_time;
  double next_glitch = options.glitch_period > 0.0
                           ? ExponentialDraw(glitch_random, options.glitch_period)
                           : std::numeric_limits<double>::infinity();
  std::vector<Pose2> out(frames.size());
  out[0] = source[0];
  double latest = 0.0;  // latest time seen [s after start] (file order may step back a little)
  for (std::size_t k = 1; k < frames.size(); ++k) {
    const double t = ToSeconds(frames[k].corrected_time - start);
    const double dt = std::max(0.0, t - latest);
    latest = std::max(latest, t);
    const Pose2 d = Between(source[k - 1], source[k]);
    Pose2 step(options.translation_scale * d.translation(),
               options.rotation_scale * d.theta() + options.yaw_drift * dt);
    if (latest >= next_glitch) {
      GlitchEvent event;
      event.frame = k;
      event.time = frames[k].time;
      if (glitch_random.Uniform() < options.glitch_yaw_fraction) {
        const double size =
            DegToRad(glitch_random.Uniform(options.glitch_yaw_min_deg, options.glitch_yaw_max_deg));
        const double sign = glitch_random.Uniform() < 0.5 ? -1.0 : 1.0;
        event.kind = GlitchKind::kYaw;
        event.jump = Pose2(0.0, 0.0, sign * size);
      } else {
        const double size =
            glitch_random.Uniform(options.glitch_translation_min, options.glitch_translation_max);
        const double direction = glitch_random.Uniform(-std::numbers::pi, std::numbers::pi);
        event.kind = GlitchKind::kTranslation;
        event.jump = Pose2(size * std::cos(direction), size * std::sin(direction), 0.0);
      }
      step = step * event.jump;
      if (glitches != nullptr) {
        glitches->push_back(event);
      }
      // One glitch per step: glitch times that fell into this step are skipped.
      while (next_glitch <= latest) {
        next_glitch += ExponentialDraw(glitch_random, options.glitch_period);
      }
    }
    out[k] = out[k - 1] * step;
  }
  return out;
}

}  // namespace gridslam::perturb
