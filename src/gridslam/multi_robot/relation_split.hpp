// Splitting the SLAM benchmark's relations (Kümmerle et al. 2009) of a log cut into several
// robots (log_split.hpp; issue 8): a relation is a relative motion of the one real robot, so it
// stays unchanged whatever frame each piece is expressed in; only its attribution changes. Each
// timestamp is given to its home robot (RobotIndex); a relation whose two timestamps have the
// same home robot is a within-robot relation of that robot, any other is a between-robot
// relation, which only a map that joined the two robots can score. With overlapping pieces a
// timestamp may lie in two robots' logs: the home rule still gives it one robot, so every
// relation lands in exactly one set.
#pragma once

#include <vector>

#include "gridslam/eval/relation.hpp"
#include "gridslam/multi_robot/robot_index.hpp"

namespace gridslam::multi_robot {

struct RelationSplit {
  std::vector<eval::Relation> within;   ///< Both timestamps of one robot, input order.
  std::vector<eval::Relation> between;  ///< Timestamps of two robots, input order.
  std::vector<std::vector<eval::Relation>> per_robot;  ///< `within` by robot.
  long unmatched = 0;  ///< Relations with a timestamp the index does not hold (left out).
};

/// Partitions `relations` by the home robots of their timestamps (`index`, matched within
/// `tolerance`); `num_robots` sizes per_robot (robots beyond it are a programming error).
RelationSplit SplitRelations(const std::vector<eval::Relation>& relations, const RobotIndex& index,
                             int num_robots, Duration tolerance);

}  // namespace gridslam::multi_robot
