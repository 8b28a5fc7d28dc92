// `gridslam perturb` on a log's frames (issue 16): cut, odometry faults, keep every k-th scan,
// sensor faults, odometry removal, in this order. Every printed laser timestamp (Frame::time) is
// kept, so the benchmark relations still apply to the scans that remain.
#pragma once

#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/perturb/odometry_faults.hpp"
#include "gridslam/perturb/perturb_options.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::perturb {

struct PerturbedLog {
  std::vector<Frame> frames;  ///< The perturbed scans, in file order.
  /// The injected glitches; GlitchEvent::frame indexes the scans of the cut (before
  /// keep_every), GlitchEvent::time is the scan's printed timestamp.
  std::vector<GlitchEvent> glitches;
  long cut = 0;        ///< Scans outside [start, start + duration].
  long decimated = 0;  ///< Scans dropped by keep_every.
};

/// The frames (file order) under the faults of `options`. InvalidInput for invalid options or
/// when the cut keeps no scan.
Result<PerturbedLog> PerturbLog(const std::vector<Frame>& frames, const PerturbOptions& options);

}  // namespace gridslam::perturb
