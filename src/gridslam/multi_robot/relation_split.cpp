#include "gridslam/multi_robot/relation_split.hpp"

#include "gridslam/common/check.hpp"

namespace gridslam::multi_robot {

RelationSplit SplitRelations(const std::vector<eval::Relation>& relations, const RobotIndex& index,
                             int num_robots, Duration tolerance) {
  GRIDSLAM_CHECK(num_robots >= 1) << num_robots;
  RelationSplit split;
  split.per_robot.resize(static_cast<std::size_t>(num_robots));
  for (const eval::Relation& relation : relations) {
    const std::optional<int> a = index.RobotAt(relation.t1, tolerance);
    const std::optional<int> b = index.RobotAt(relation.t2, tolerance);
    if (!a.has_value() || !b.has_value()) {
      ++split.unmatched;
      continue;
    }
    GRIDSLAM_CHECK(*a >= 0 && *a < num_robots && *b >= 0 && *b < num_robots)
        << "robot " << *a << " or " << *b << " outside 0.." << num_robots - 1;
    if (*a == *b) {
      split.within.push_back(relation);
      split.per_robot[static_cast<std::size_t>(*a)].push_back(relation);
    } else {
      split.between.push_back(relation);
    }
  }
  return split;
}

}  // namespace gridslam::multi_robot
