// The self-check's local baseline (docs/self_check.md, "Returns confirmed by their neighbourhood"):
// which returns of the replayed scans the map of their own stretch of trajectory confirms. A
// person walking past, a glass door, a return at a grazing angle disagrees with a map however
// well the trajectory is aligned; the scans taken just before and after, aligned by the front end
// alone, already carve such a return away. A return that its neighbourhood confirms and the
// final map does not is what a misaligned trajectory leaves: the self-check's score counts only
// confirmed returns.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/quality/self_check_options.hpp"

namespace gridslam::quality {

/// The indices of the scans the self-check replays, in order: the first scan with a return
/// buffer, then each one at least min_motion or min_rotation from the last one kept.
std::vector<std::size_t> ReplayedScans(const std::vector<fusion::PosedScan>& scans,
                                       const SelfCheckOptions& options);

/// For every scan of `scans` (borrowed), one flag per return of ExtractScanReturns(scan,
/// T_base_laser, options.max_range): 1 when the return is confirmed by its neighbourhood, 0 when
/// not; an empty vector for the scans not replayed (ReplayedScans). The replayed scans are cut,
/// in order, into stretches of options.local_travel metres of travel; each stretch's scans are
/// fused alone (FuseScans with `fusion`'s sensor model) and a return is confirmed when an
/// occupied cell of its stretch's map lies within options.agreement_distance. A stretch too large
/// to fuse (more than fusion::kMaxFusedCells) confirms all its returns. Stretches are
/// independent: `threads` of them at once give the same flags as one.
std::vector<std::vector<std::uint8_t>> LocalConfirmation(
    const std::vector<fusion::PosedScan>& scans, const fusion::FusionOptions& fusion,
    const SelfCheckOptions& options, int threads = 1);

}  // namespace gridslam::quality
