#include "gridslam/scan/laser_scan.hpp"

#include <cmath>

namespace gridslam {

bool LaserScan::IsHit(std::size_t k) const {
  const double r = ranges[k];
  return std::isfinite(r) && r > range_min && r < range_max;
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
