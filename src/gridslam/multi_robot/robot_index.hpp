// Which robot a scan timestamp belongs to (issue 8; the `index.txt` of `gridslam simulate` and
// `gridslam split`, docs/design.md §2): the attribution behind splitting benchmark relations into
// within- and between-robot sets, and behind scoring a relation whose two poses lie in different
// robots' trajectories (Kümmerle et al. 2009's metric over a merged map). Timestamps are matched
// to the nearest indexed time within a tolerance, as the relation metric matches poses.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "gridslam/common/time.hpp"
#include "gridslam/eval/stamped_pose.hpp"

namespace gridslam::multi_robot {

class RobotIndex {
 public:
  RobotIndex() = default;
  /// From (time, robot) pairs in any order; a time listed twice keeps its first robot.
  explicit RobotIndex(const std::vector<std::pair<Time, int>>& entries);

  /// The robot of the indexed time nearest to `t` within `tolerance`, or nullopt.
  [[nodiscard]] std::optional<int> RobotAt(Time t, Duration tolerance) const;
  [[nodiscard]] std::size_t size() const { return entries_.size(); }
  [[nodiscard]] bool empty() const { return entries_.empty(); }

 private:
  std::vector<std::pair<Time, int>> entries_;  ///< Sorted by time, unique times.
};

/// What CombineTrajectories found.
struct CombineStats {
  long poses = 0;         ///< Poses in the combined trajectory.
  long dropped = 0;       ///< Poses left out because the index gives their time to another robot.
  long shared_times = 0;  ///< Times held by several trajectories (kept from the first, no index).
};

/// One trajectory holding, for every scan time, the pose of the robot it belongs to, so that the
/// single-trajectory relation metric (eval::EvaluateRelations) scores relations within and
/// between robots alike. The trajectories must be in one common frame (a merged map). With an
/// empty `index`, trajectory r's poses come before r + 1's and the metric takes the first pose
/// of a time, i.e. the time's lowest robot; with an index, a pose of trajectory r is kept only
/// if the index gives its time to r (or does not list the time).
std::vector<eval::StampedPose> CombineTrajectories(
    const std::vector<std::vector<eval::StampedPose>>& trajectories, const RobotIndex& index,
    Duration tolerance, CombineStats* stats = nullptr);

}  // namespace gridslam::multi_robot
