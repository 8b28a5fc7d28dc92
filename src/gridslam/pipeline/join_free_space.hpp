// The free-space check of a join (loop_closure/free_space_check.hpp) on the graph: the
// contradiction of each alignment of the join (its two key maps' returns in each other's cells)
// against the robots' own, each key map of the join against its robot's key maps
// FreeSpaceCheckOptions::baseline_travel behind it under their estimates.
// Contract: reads the graph only.
#pragma once

#include <vector>

#include "gridslam/loop_closure/closure_arbiter.hpp"
#include "gridslam/loop_closure/free_space_check.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"

namespace gridslam::pipeline {

/// `group`: the matches that would join two components (ComponentJoiner::Join's input).
loop_closure::FreeSpaceVerdict CheckJoinFreeSpace(
    const std::vector<loop_closure::Match>& group, const KeyMapGraph& graph,
    const loop_closure::FreeSpaceCheckOptions& options);

}  // namespace gridslam::pipeline
