// The ascending order of a SURF orientation assignment's sample angles (surf_descriptor.cpp),
// found by a bucket sort: about 110 keys per keypoint, for which a comparison sort's branches
// mispredict most of the time. Internal to the features module.
#pragma once

#include <cstdint>

namespace gridslam::features::internal {

/// Most keys OrderByAngle takes (the indices are bytes).
inline constexpr int kMaxAngleKeys = 256;

/// Writes to order[0 .. n) the indices of angle[0 .. n) in ascending order of the angle (ties in
/// index order) and returns true if the angles are pairwise distinct: then this is the only
/// ascending order, the one any correct sort gives. Returns false if two angles are equal.
/// Contract: 0 <= n <= kMaxAngleKeys; angles not NaN (any range; [−π, π] spreads best).
bool OrderByAngle(const float* angle, int n, std::uint8_t* order);

}  // namespace gridslam::features::internal
