#include "gridslam/scan_matching/laser_noise_monitor.hpp"

#include <algorithm>

namespace gridslam::scan_matching {

LaserNoiseMonitor::LaserNoiseMonitor(int window)
    : window_(static_cast<std::size_t>(std::max(window, 1))) {
  recent_.reserve(window_);
}

void LaserNoiseMonitor::Add(double surface_noise) {
  if (!(surface_noise > 0.0)) {
    return;
  }
  if (recent_.size() < window_) {
    recent_.push_back(surface_noise);
  } else {
    recent_[next_] = surface_noise;
    next_ = (next_ + 1) % window_;
  }
  if (recent_.size() < kMinScans) {
    return;
  }
  std::vector<double> sorted = recent_;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  median_ = *middle;
}

}  // namespace gridslam::scan_matching
