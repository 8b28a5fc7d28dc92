// Odometry faults of `gridslam perturb` (issue 16): spurious jumps (glitches), calibration errors
// (translation and rotation scale, yaw drift) and laser/odometry clock jitter. The perturbed
// odometry is rebuilt increment by increment from the (jittered) original: each increment
// T_{k-1}⁻¹ T_k has its translation scaled, its rotation scaled, the drift of its time step added
// and, at a glitch, a jump composed onto it; so after a jump the odometry carries on from the
// jumped pose, as a real glitch does. The first pose is kept.
#pragma once

#include <cstddef>
#include <vector>

#include "gridslam/perturb/perturb_options.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::perturb {

enum class GlitchKind { kYaw, kTranslation };

/// One injected glitch (for the log's comments and for tests).
struct GlitchEvent {
  std::size_t frame = 0;  ///< Index of the frame whose increment got the jump.
  Time time;              ///< That frame's printed timestamp.
  GlitchKind kind = GlitchKind::kYaw;
  Pose2 jump;  ///< Composed onto the increment, in the robot frame of the previous scan.
};

/// The perturbed odometry of `frames` (in their order; times from Frame::corrected_time) under
/// the odometry faults of `options`; `glitches` (optional) receives the injected glitches.
std::vector<Pose2> PerturbOdometry(const std::vector<Frame>& frames, const PerturbOptions& options,
                                   std::vector<GlitchEvent>* glitches);

}  // namespace gridslam::perturb
