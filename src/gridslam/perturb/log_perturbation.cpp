#include "gridslam/perturb/log_perturbation.hpp"

#include <algorithm>
#include <string>

#include "gridslam/perturb/random_streams.hpp"
#include "gridslam/perturb/sensor_faults.hpp"

namespace gridslam::perturb {

Result<PerturbedLog> PerturbLog(const std::vector<Frame>& frames, const PerturbOptions& options) {
  GRIDSLAM_RETURN_IF_ERROR(options.Validate());
  PerturbedLog out;
  if (frames.empty()) {
    return out;
  }
  // 1. Cut.
  std::vector<Frame> cut;
  const Time first = frames.front().corrected_time;
  for (const Frame& f : frames) {
    const double t = ToSeconds(f.corrected_time - first);
    if (t < options.start || (options.duration > 0.0 && t > options.start + options.duration)) {
      ++out.cut;
      continue;
    }
    cut.push_back(f);
  }
  if (cut.empty()) {
    return InvalidInput("perturb: the cut [" + std::to_string(options.start) + " s, +" +
                        std::to_string(options.duration) + " s] keeps no scan");
  }
  // 2. Odometry faults (on every scan of the cut, so glitch times do not depend on keep_every).
  const bool has_odometry =
      std::all_of(cut.begin(), cut.end(), [](const Frame& f) { return f.has_odometry; });
  if (has_odometry && options.PerturbsOdometry()) {
    const std::vector<Pose2> odometry = PerturbOdometry(cut, options, &out.glitches);
    for (std::size_t k = 0; k < cut.size(); ++k) {
      cut[k].T_odom_base = odometry[k];
    }
  }
  // 3. Keep every k-th scan; 4. sensor faults; 5. odometry removal.
  const auto seed = static_cast<std::uint64_t>(options.seed);
  simulation::Random noise(seed, kStreamRangeNoise);
  simulation::Random dropout(seed, kStreamBeamDropout);
  const bool sensor = PerturbsSensor(options);
  for (std::size_t k = 0; k < cut.size(); ++k) {
    if (k % static_cast<std::size_t>(options.keep_every) != 0) {
      ++out.decimated;
      continue;
    }
    Frame f = std::move(cut[k]);
    if (sensor) {
      f.scan = PerturbScan(f.scan, options, noise, dropout);
    }
    if (options.remove_odometry) {
      f.T_odom_base = Pose2::Identity();
      f.has_odometry = false;
    }
    out.frames.push_back(std::move(f));
  }
  return out;
}

}  // namespace gridslam::perturb
