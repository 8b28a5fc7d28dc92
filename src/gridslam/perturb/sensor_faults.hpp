// Sensor faults of `gridslam perturb` (issue 16), applied to one scan in this order: crop the
// field of view, keep every k-th beam, limit the range, add Gaussian range noise, drop returns.
// No-returns are written the way the CARMEN reader understands them: a range limit R sets
// LaserScan::range_max = R (the writer's maximum_range field) and every reading at or beyond R
// to R itself, which is outside the open interval (range_min, range_max) of hits; a dropped
// return becomes 0 (at or below range_min).
#pragma once

#include "gridslam/perturb/perturb_options.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/simulation/random.hpp"

namespace gridslam::perturb {

/// The scan under the sensor faults of `options`; `noise` and `dropout` are the random streams
/// of the range noise and of the dropped returns (draws are taken for hits only).
LaserScan PerturbScan(const LaserScan& scan, const PerturbOptions& options,
                      simulation::Random& noise, simulation::Random& dropout);

/// True when some sensor fault of `options` is on.
bool PerturbsSensor(const PerturbOptions& options);

}  // namespace gridslam::perturb
