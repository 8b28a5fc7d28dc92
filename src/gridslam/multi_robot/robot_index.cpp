#include "gridslam/multi_robot/robot_index.hpp"

#include <algorithm>
#include <set>

namespace gridslam::multi_robot {

RobotIndex::RobotIndex(const std::vector<std::pair<Time, int>>& entries) : entries_(entries) {
  std::stable_sort(entries_.begin(), entries_.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  entries_.erase(std::unique(entries_.begin(), entries_.end(),
                             [](const auto& a, const auto& b) { return a.first == b.first; }),
                 entries_.end());
}

std::optional<int> RobotIndex::RobotAt(Time t, Duration tolerance) const {
  const auto it = std::lower_bound(entries_.begin(), entries_.end(), t,
                                   [](const auto& e, Time time) { return e.first < time; });
  std::optional<std::pair<Duration, int>> best;
  if (it != entries_.end()) {
    best = {it->first - t, it->second};
  }
  if (it != entries_.begin()) {
    const auto& before = *(it - 1);
    if (!best || t - before.first < best->first) {
      best = {t - before.first, before.second};
    }
  }
  if (!best || best->first > tolerance) {
    return std::nullopt;
  }
  return best->second;
}

std::vector<eval::StampedPose> CombineTrajectories(
    const std::vector<std::vector<eval::StampedPose>>& trajectories, const RobotIndex& index,
    Duration tolerance, CombineStats* stats) {
  CombineStats counts;
  std::vector<eval::StampedPose> combined;
  std::set<Time> seen;
  for (std::size_t r = 0; r < trajectories.size(); ++r) {
    std::set<Time> own;
    for (const eval::StampedPose& pose : trajectories[r]) {
      if (!index.empty()) {
        const std::optional<int> robot = index.RobotAt(pose.time, tolerance);
        if (robot.has_value() && *robot != static_cast<int>(r)) {
          ++counts.dropped;
          continue;
        }
      } else if (seen.count(pose.time) > 0) {
        ++counts.shared_times;
      }
      own.insert(pose.time);
      combined.push_back(pose);
    }
    seen.insert(own.begin(), own.end());
  }
  counts.poses = static_cast<long>(combined.size());
  if (stats != nullptr) {
    *stats = counts;
  }
  return combined;
}

}  // namespace gridslam::multi_robot
