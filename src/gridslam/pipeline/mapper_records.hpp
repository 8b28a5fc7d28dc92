// What the mapper reports about its decisions: loop-closure records, joins of robots, and the
// events of the online API (mapper.hpp, docs/online_api.md).
#pragma once

#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/loop_closure/closure_arbiter.hpp"

namespace gridslam::pipeline {

using loop_closure::ClosureOutcome;

/// One loop-closure attempt that got as far as a verified alignment.
struct ClosureRecord {
  int from = 0;  ///< Older key map (vertex id).
  int to = 0;    ///< Newer key map.
  Pose2 T_from_to;
  ClosureOutcome outcome = ClosureOutcome::kAccepted;  ///< ToString(outcome) in reports.
  bool appearance = false;  ///< Found by the appearance search (no prior).
};

/// When two robots' graphs were joined.
struct JoinRecord {
  int robot_a = 0;
  int robot_b = 0;
  Time time;         ///< Time of the frame that completed the join.
  int vertex_a = 0;  ///< The first matched key maps.
  int vertex_b = 0;
  int matches = 0;  ///< Consistent matches used.
};

/// Something the mapper did that a live user may want to react to (Mapper::DrainEvents).
struct MapperEvent {
  enum class Kind {
    kKeyMapAdded,      ///< `vertex` of `robot` is new.
    kClosureAccepted,  ///< Loop edge `vertex` (from) - `other` (to) added; `closure` its record.
    kClosureRemoved,   ///< Loop edge of record `closure` removed (pruned).
    kRobotsJoined,     ///< `robot` and `other_robot` now share one map frame.
  };
  Kind kind = Kind::kKeyMapAdded;
  Time time;  ///< Time of the latest frame when it happened.
  int robot = -1;
  int other_robot = -1;
  int vertex = -1;
  int other = -1;
  int closure = -1;  ///< Index into the closure records.
};

}  // namespace gridslam::pipeline
