// The self-check's heat layer (map_quality.png, docs/self_check.md): the map in grey with, in red,
// the local share of replayed returns that do not agree with it, i.e. where the map disagrees
// with itself (double walls, smeared or erased structure).
#pragma once

#include <opencv2/core/mat.hpp>

#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/tiled_grid.hpp"
#include "gridslam/quality/map_self_check.hpp"

namespace gridslam::quality {

/// Local share of disagreeing returns, smoothed over options.heat_radius (a Gaussian of that
/// standard deviation, the kernel of cv::GaussianBlur, reflected at the map's edges); -1 where
/// fewer than `min_returns` (smoothed) returns per cell fell. Same limits as the map; only the
/// tiles near returns are computed and stored, `threads` at once (each tile on its own: the
/// result does not depend on the thread count).
TiledGrid<float> DisagreementShare(const SelfCheckResult& result, const SelfCheckOptions& options,
                                   float min_returns = 0.02F, int threads = 1);

/// BGR image (row 0 at the top, as map.png): grey occupancy, red where the share is high
/// (full red at a share of 0.5 or more). Rows are rendered `threads` at once (the same image
/// whatever the count).
cv::Mat RenderQualityImage(const OccupancyImage& map, const TiledGrid<float>& share,
                           int threads = 1);
/// The same from the fused log-odds map, thresholded as fusion::ToOccupancy does (without
/// holding the occupancy image).
cv::Mat RenderQualityImage(const TiledGrid<float>& log_odds, const fusion::FusionOptions& fusion,
                           const TiledGrid<float>& share, int threads = 1);
/// The same into `image`, whose pixels are reused when it already has the map's size and type
/// CV_8UC3 (a header over a caller's buffer stays on it).
void RenderQualityImage(const TiledGrid<float>& log_odds, const fusion::FusionOptions& fusion,
                        const TiledGrid<float>& share, int threads, cv::Mat& image);

}  // namespace gridslam::quality
