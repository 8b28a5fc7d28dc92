// Ground-truth relations for simulated logs, in the SLAM benchmark's form (Kümmerle et al. 2009;
// docs/formats.md §4): each relation is the true motion T_1_2 from the robot's pose at t1 to its
// pose at t2, expressed in the frame at t1, computed from world-frame ground truth. Three kinds:
// pairs close in time (every `short_stride`-th scan with the first scan `short_span` later),
// revisits (a scan paired with the nearest earlier scan at least `revisit_min_gap` before it,
// within `revisit_max_distance` and `revisit_max_angle` and in line of sight: loop closures
// with known answers), and between robots (the same test across two robots' logs, no time gap).
#pragma once

#include <vector>

#include "gridslam/eval/relation.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/simulation/ray_caster.hpp"
#include "gridslam/simulation/simulation_options.hpp"
#include "gridslam/simulation/simulator.hpp"

namespace gridslam::simulation {

/// Relations within one robot's frames, which must all carry T_world_base_true and be in time
/// order. Sorted by (t1, t2).
std::vector<eval::Relation> MakeWithinRelations(const std::vector<Frame>& frames,
                                                const RelationSimOptions& options,
                                                const RayCaster& caster);

/// Relations between every pair of robots a < b: t1 from robot a's log, t2 from robot b's.
/// Sorted by (t1, t2).
std::vector<eval::Relation> MakeBetweenRelations(const std::vector<RobotRun>& robots,
                                                 const RelationSimOptions& options,
                                                 const RayCaster& caster);

}  // namespace gridslam::simulation
