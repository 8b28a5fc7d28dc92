// The simulator's two noise models. The range sensor ray-casts every beam in the world and
// adds Gaussian range noise, occasional spurious short returns (dust, people) and missing
// returns; a beam that hits nothing within the maximum range is a no-return, written as the
// configured no-return range (max range, or a sentinel such as 81.91 m as in the Freiburg logs;
// docs/formats.md §1.5). The odometry integrates each true motion increment with a random error
// whose variance grows linearly with distance travelled and angle turned (a random walk, so the
// error does not depend on the integration step; Thrun et al., Probabilistic Robotics §5.4), plus
// an optional systematic scale and drift bias.
#pragma once

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/simulation/random.hpp"
#include "gridslam/simulation/ray_caster.hpp"
#include "gridslam/simulation/simulation_options.hpp"

namespace gridslam::simulation {

class LaserSimulator {
 public:
  /// `world` must outlive the simulator.
  LaserSimulator(const World& world, const LaserSimOptions& options);

  /// One scan from the laser at `T_world_laser`; noise drawn from `random`.
  [[nodiscard]] LaserScan Scan(const Pose2& T_world_laser, Random& random) const;

  /// The scan's geometry with no ranges.
  [[nodiscard]] LaserScan EmptyScan() const;

 private:
  RayCaster caster_;
  LaserSimOptions options_;
};

class OdometrySimulator {
 public:
  explicit OdometrySimulator(const OdometryNoiseOptions& options) : options_(options) {}

  /// The measured motion for the true body-frame increment `T_prev_cur` (x forward, y left).
  [[nodiscard]] Pose2 Measure(const Pose2& T_prev_cur, Random& random) const;

 private:
  OdometryNoiseOptions options_;
};

}  // namespace gridslam::simulation
