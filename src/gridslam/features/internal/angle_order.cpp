#include "gridslam/features/internal/angle_order.hpp"

#include <array>
#include <numbers>

#include "gridslam/common/check.hpp"

namespace gridslam::features::internal {
namespace {

constexpr int kBuckets = 256;

// The bucket of an angle: [−π, π] in kBuckets equal parts, anything outside in the end buckets.
// Non-decreasing in the angle (each float step rounds monotonically), so after the stable
// scatter only keys in the same bucket can be out of order.
inline int Bucket(float angle) {
  constexpr auto kPi = static_cast<float>(std::numbers::pi);
  constexpr auto kPerRadian = static_cast<float>(kBuckets / (2.0 * std::numbers::pi));
  const float t = (angle + kPi) * kPerRadian;
  if (!(t >= 0.0F)) {
    return 0;
  }
  return t < static_cast<float>(kBuckets) ? static_cast<int>(t) : kBuckets - 1;
}

}  // namespace

bool OrderByAngle(const float* angle, int n, std::uint8_t* order) {
  GRIDSLAM_CHECK(n >= 0 && n <= kMaxAngleKeys) << "n " << n;
  std::array<std::uint8_t, kMaxAngleKeys> bucket;  // NOLINT(cppcoreguidelines-pro-type-member-init)
  std::array<int, kBuckets> start{};
  for (int k = 0; k < n; ++k) {
    const int b = Bucket(angle[k]);
    bucket[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(b);
    ++start[static_cast<std::size_t>(b)];
  }
  int sum = 0;
  for (int& s : start) {
    const int count = s;
    s = sum;
    sum += count;
  }
  for (int k = 0; k < n; ++k) {
    order[start[bucket[static_cast<std::size_t>(k)]]++] = static_cast<std::uint8_t>(k);
  }
  // Insertion sort (stable): only the few keys sharing a bucket move.
  for (int i = 1; i < n; ++i) {
    const std::uint8_t key = order[i];
    const float v = angle[key];
    int j = i;
    for (; j > 0 && v < angle[order[j - 1]]; --j) {
      order[j] = order[j - 1];
    }
    order[j] = key;
  }
  for (int i = 1; i < n; ++i) {
    if (angle[order[i]] == angle[order[i - 1]]) {
      return false;
    }
  }
  return true;
}

}  // namespace gridslam::features::internal
