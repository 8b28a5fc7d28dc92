#include "gridslam/scan/laser_scan.hpp"

#include <cmath>
#include <limits>

namespace gridslam {
namespace {

// A limit in the precision of the readings. Readings are floats, limits doubles parsed from the
// same text ("5.600000" in a header, "5.60" in the readings) or set by a tool: compared as
// doubles, a reading at the limit would fall just below it (5.6F < 5.6) and count as a hit.
float InReadingPrecision(double limit) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (limit >= kMax) {
    return std::numeric_limits<float>::infinity();
  }
  if (limit <= -kMax) {
    return -std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(limit);
}

}  // namespace

bool LaserScan::IsHit(std::size_t k) const {
  const float r = ranges[k];
  return std::isfinite(r) && r > InReadingPrecision(range_min) && r < InReadingPrecision(range_max);
}

bool LaserScan::IsNoReturn(std::size_t k) const {
  const float r = ranges[k];
  return std::isfinite(r) && r >= InReadingPrecision(range_max) &&
         r > InReadingPrecision(range_min);
}

std::size_t LaserScan::CountHits() const {
  std::size_t n = 0;
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    n += IsHit(k) ? 1 : 0;
  }
  return n;
}

std::vector<Eigen::Vector2d> LaserScan::HitPoints() const {
  std::vector<Eigen::Vector2d> points;
  points.reserve(ranges.size());
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    if (IsHit(k)) {
      const double a = Angle(k);
      const double r = ranges[k];
      points.emplace_back(r * std::cos(a), r * std::sin(a));
    }
  }
  return points;
}

}  // namespace gridslam
