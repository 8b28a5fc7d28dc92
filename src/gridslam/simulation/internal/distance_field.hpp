// Exact Euclidean distance transform of a binary grid (Felzenszwalb & Huttenlocher 2012, the
// lower envelope of parabolas, O(cells)), used by the simulator for the robot's clearance and to
// let rays skip empty space. The project's distance_transform module is the general one; this
// small copy keeps the simulator free of algorithm modules.
#pragma once

#include <cstdint>
#include <vector>

namespace gridslam::simulation::internal {

/// Distance in cells from each cell centre of a width x height row-major grid to the nearest
/// cell with `obstacle[k] != 0`; a large value (width + height) where there is none.
std::vector<float> DistanceTransform(const std::vector<std::uint8_t>& obstacle, int width,
                                     int height);

}  // namespace gridslam::simulation::internal
