#include "gridslam/quality/local_confirmation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gridslam/common/angles.hpp"
#include "gridslam/common/parallel.hpp"
#include "gridslam/grid/log_odds.hpp"
#include "gridslam/grid/scan_points.hpp"

namespace gridslam::quality {

std::vector<std::size_t> ReplayedScans(const std::vector<fusion::PosedScan>& scans,
                                       const SelfCheckOptions& options) {
  std::vector<std::size_t> replayed;
  const Pose2* last = nullptr;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    if (scans[s].scan == nullptr) {
      continue;
    }
    const Pose2& pose = scans[s].T_map_base;
    if (last != nullptr && (pose.translation() - last->translation()).norm() < options.min_motion &&
        std::abs(NormalizeAngle(pose.theta() - last->theta())) < options.min_rotation) {
      continue;
    }
    last = &pose;
    replayed.push_back(s);
  }
  return replayed;
}

namespace {

// Flags of the returns of `stretch` (indices into `scans`) against the map of those scans alone.
void ConfirmStretch(const std::vector<fusion::PosedScan>& scans,
                    const std::vector<std::size_t>& stretch, const fusion::FusionOptions& fusion,
                    const SelfCheckOptions& options,
                    std::vector<std::vector<std::uint8_t>>& flags) {
  std::vector<fusion::PosedScan> posed;
  posed.reserve(stretch.size());
  for (const std::size_t s : stretch) {
    posed.push_back(scans[s]);
  }
  // Every scan of the stretch is inserted, however close to the previous one.
  fusion::FusionOptions local = fusion;
  local.min_motion = 0.0;
  local.min_rotation = 0.0;
  Grid2D<float> map;
  try {
    map = fusion::FuseScans(posed, local);
  } catch (const std::length_error&) {
    // The stretch's returns span more cells than a map may hold (a resolution far finer than its
    // range): no baseline, every return of the stretch counts.
    for (const std::size_t s : stretch) {
      flags[s].assign(ExtractScanReturns(*scans[s].scan, scans[s].T_base_laser, options.max_range)
                          .points.size(),
                      1);
    }
    return;
  }
  const MapLimits& limits = map.Limits();
  const auto occupied = static_cast<float>(ProbabilityToLogOdds(fusion.occupied_probability));
  // The cells within agreement_distance of a return's cell (centre to centre, with the same
  // slack as the global check).
  const double reach = options.agreement_distance / limits.Resolution() + 1e-6;
  const int r = static_cast<int>(std::floor(reach));
  std::vector<Eigen::Array2i> disk;
  for (int dj = -r; dj <= r; ++dj) {
    for (int di = -r; di <= r; ++di) {
      if (di * di + dj * dj <= reach * reach) {
        disk.emplace_back(di, dj);
      }
    }
  }
  for (const std::size_t s : stretch) {
    const ScanReturns returns =
        ExtractScanReturns(*scans[s].scan, scans[s].T_base_laser, options.max_range);
    const PointTransform to_map(scans[s].T_map_base);
    std::vector<std::uint8_t>& out = flags[s];
    out.assign(returns.points.size(), 0);
    for (std::size_t p = 0; p < returns.points.size(); ++p) {
      const Eigen::Array2i cell = limits.CellIndex(to_map(returns.points[p]));
      for (const Eigen::Array2i& d : disk) {
        const Eigen::Array2i c = cell + d;
        if (limits.Contains(c) && map.at(c) > occupied) {
          out[p] = 1;
          break;
        }
      }
    }
  }
}

}  // namespace

std::vector<std::vector<std::uint8_t>> LocalConfirmation(
    const std::vector<fusion::PosedScan>& scans, const fusion::FusionOptions& fusion,
    const SelfCheckOptions& options, int threads) {
  std::vector<std::vector<std::uint8_t>> flags(scans.size());
  const std::vector<std::size_t> replayed = ReplayedScans(scans, options);
  // Stretches of local_travel metres of the corrected trajectory, in replay order.
  std::vector<std::vector<std::size_t>> stretches;
  // A stretch spans less than local_travel, whatever one step is (a run-away trajectory).
  double travel = 0.0;
  for (std::size_t n = 0; n < replayed.size(); ++n) {
    const double step = n == 0 ? 0.0
                               : (scans[replayed[n]].T_map_base.translation() -
                                  scans[replayed[n - 1]].T_map_base.translation())
                                     .norm();
    if (stretches.empty() || !(travel + step < options.local_travel)) {
      stretches.emplace_back();
      travel = 0.0;
    } else {
      travel += step;
    }
    stretches.back().push_back(replayed[n]);
  }
  // Each stretch writes the flags of its own scans only.
  RunParts(stretches.size(), PartCount(stretches.size(), threads),
           [&](std::size_t /*part*/, std::size_t begin, std::size_t end) {
             for (std::size_t k = begin; k < end; ++k) {
               ConfirmStretch(scans, stretches[k], fusion, options, flags);
             }
           });
  return flags;
}

}  // namespace gridslam::quality
